"""Makes pellet_stack.msh, the r-z section (x = r, y = z) of a stack of three dished and
chamfered LWR pellets in their cladding, for pellet_stack.toml: from the mid-plane of the
first pellet (y = 0, a plane of symmetry) through the whole second pellet to the mid-plane of
the third (the top, kept plane: the rest of the stack bears on it), the pellets apart by an
as-built axial gap of 4 um between their lands.

Each pellet (mm): radius 4.1, height 9.8; in each end face a spherical dish of footprint radius
2.9 and depth 0.3 and a chamfer 0.5 wide and 0.15 high at the outer edge, so the land (the flat
annulus where the next pellet bears) runs from r = 2.9 to r = 3.6. Cladding: inner radius
4.12, outer 4.75, over the stack's height. The pellets are one body of three parts, meshed
apart from the cladding (quadrangles of 0.2 mm, 0.1 mm near the ends; the cladding's of
0.1 mm): no interface matches.

Physical groups: "pellet" and "cladding" (the cells); "pellet_outer" (the pellets' lateral
surfaces r = a, the slave side of the gap), "pellet_free" (dishes and chamfers, wetted by the
plenum gas), "pellet_lands_lower" (the lower lands of the second and third pellets, the slave
sides of the pellet-pellet contact) and "pellet_lands_upper" (the upper lands of the first and
second, its master sides), "cladding_inner" (r = b, the gap's master side), "cladding_outer"
(r = c, the coolant).

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_pellet_stack.py
"""

import math
import os

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))

A = 4.1e-3  # pellet radius
L = 9.8e-3  # pellet height
DISH_R = 2.9e-3  # footprint radius of the dishes
DISH_DEPTH = 0.3e-3
CHAMFER_W = 0.5e-3
CHAMFER_H = 0.15e-3
AXIAL_GAP = 4e-6  # between the lands of neighbouring pellets, as built
B = 4.12e-3  # cladding inner radius
C = 4.75e-3  # cladding outer radius
PELLET_SIZE = 0.2e-3
END_SIZE = 0.1e-3
CLADDING_SIZE = 0.1e-3


def end_face(geo, y, down):
    """The points of a pellet end face at height y, from the lateral surface to the axis:
    the chamfer's foot on r = a, the land's outer and inner ends, the dish's bottom on the
    axis (the dish going into the pellet: up from a lower face, down from an upper one);
    the dish's arc centre."""
    s = 1.0 if down else -1.0  # into the pellet from the face
    rho = (DISH_R**2 + DISH_DEPTH**2) / (2.0 * DISH_DEPTH)
    foot = geo.addPoint(A, y + s * CHAMFER_H, 0.0, END_SIZE)
    land_out = geo.addPoint(A - CHAMFER_W, y, 0.0, END_SIZE)
    land_in = geo.addPoint(DISH_R, y, 0.0, END_SIZE)
    bottom = geo.addPoint(0.0, y + s * DISH_DEPTH, 0.0, PELLET_SIZE)
    centre = geo.addPoint(0.0, y + s * DISH_DEPTH - s * rho, 0.0, PELLET_SIZE)
    return foot, land_out, land_in, bottom, centre


def pellet(geo, y0, y1, lower_face, upper_face):
    """A pellet from y0 to y1, with a dished and chamfered lower face at y0 if lower_face
    (else the mid-plane y0, flat) and upper face at y1 if upper_face (else the mid-plane y1).
    Returns the surface and its curves: lateral, free (dishes, chamfers), lower land, upper
    land (None where absent)."""
    free = []
    lower_land = upper_land = None
    curves = []
    # Counter-clockwise: along the bottom from the axis to r = a, up r = a, back along the top.
    if lower_face:
        foot, land_out, land_in, bottom, centre = end_face(geo, y0, down=True)
        dish = geo.addCircleArc(bottom, centre, land_in)
        lower_land = geo.addLine(land_in, land_out)
        chamfer = geo.addLine(land_out, foot)
        curves += [dish, lower_land, chamfer]
        free += [dish, chamfer]
        start, lat_lo = bottom, foot
    else:
        start = geo.addPoint(0.0, y0, 0.0, PELLET_SIZE)
        lat_lo = geo.addPoint(A, y0, 0.0, PELLET_SIZE)
        curves.append(geo.addLine(start, lat_lo))
    if upper_face:
        foot, land_out, land_in, bottom, centre = end_face(geo, y1, down=False)
        lateral = geo.addLine(lat_lo, foot)
        chamfer = geo.addLine(foot, land_out)
        upper_land = geo.addLine(land_out, land_in)
        dish = geo.addCircleArc(land_in, centre, bottom)
        curves += [lateral, chamfer, upper_land, dish]
        free += [chamfer, dish]
        end = bottom
    else:
        lat_hi = geo.addPoint(A, y1, 0.0, PELLET_SIZE)
        end = geo.addPoint(0.0, y1, 0.0, PELLET_SIZE)
        lateral = geo.addLine(lat_lo, lat_hi)
        curves += [lateral, geo.addLine(lat_hi, end)]
    curves.append(geo.addLine(end, start))  # the axis, down
    surface = geo.addPlaneSurface([geo.addCurveLoop(curves)])
    return surface, lateral, free, lower_land, upper_land


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("pellet_stack")
    geo = gmsh.model.geo

    half = 0.5 * L
    y = [0.0, half, half + AXIAL_GAP, half + AXIAL_GAP + L, half + 2 * AXIAL_GAP + L]
    top = y[4] + half
    parts = [
        pellet(geo, y[0], y[1], lower_face=False, upper_face=True),
        pellet(geo, y[2], y[3], lower_face=True, upper_face=True),
        pellet(geo, y[4], top, lower_face=True, upper_face=False),
    ]
    q = [
        geo.addPoint(B, 0.0, 0.0, CLADDING_SIZE),
        geo.addPoint(C, 0.0, 0.0, CLADDING_SIZE),
        geo.addPoint(C, top, 0.0, CLADDING_SIZE),
        geo.addPoint(B, top, 0.0, CLADDING_SIZE),
    ]
    c_bottom = geo.addLine(q[0], q[1])
    c_outer = geo.addLine(q[1], q[2])
    c_top = geo.addLine(q[2], q[3])
    c_inner = geo.addLine(q[3], q[0])
    cladding = geo.addPlaneSurface([geo.addCurveLoop([c_bottom, c_outer, c_top, c_inner])])
    geo.synchronize()

    surfaces = [p[0] for p in parts]
    for s in surfaces + [cladding]:
        gmsh.model.mesh.setRecombine(2, s)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # frontal-Delaunay for quadrangles
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 2)  # blossom: quadrangles only
    gmsh.model.addPhysicalGroup(2, surfaces, name="pellet")
    gmsh.model.addPhysicalGroup(2, [cladding], name="cladding")
    gmsh.model.addPhysicalGroup(1, [p[1] for p in parts], name="pellet_outer")
    gmsh.model.addPhysicalGroup(1, [c for p in parts for c in p[2]], name="pellet_free")
    gmsh.model.addPhysicalGroup(1, [p[3] for p in parts if p[3]], name="pellet_lands_lower")
    gmsh.model.addPhysicalGroup(1, [p[4] for p in parts if p[4]], name="pellet_lands_upper")
    gmsh.model.addPhysicalGroup(1, [c_inner], name="cladding_inner")
    gmsh.model.addPhysicalGroup(1, [c_outer], name="cladding_outer")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    out = os.path.join(HERE, "pellet_stack.msh")
    gmsh.write(out)
    gmsh.finalize()
    dish = math.pi * DISH_DEPTH / 6.0 * (3.0 * DISH_R**2 + DISH_DEPTH**2)
    chamfer = 2.0 * math.pi * (A - CHAMFER_W / 3.0) * 0.5 * CHAMFER_W * CHAMFER_H
    gaps = 2 * math.pi * A**2 * AXIAL_GAP
    print("wrote", out, "end voids (revolved) %.6e m^3" % (4 * (dish + chamfer) + gaps))


if __name__ == "__main__":
    main()
