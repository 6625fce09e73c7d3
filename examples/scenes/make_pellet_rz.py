"""Makes pellet_rz.msh, the r-z section (x = r, y = z) of a dished and chamfered LWR pellet in
its cladding, for pellet_rz.toml: half a pellet, from its mid-plane (y = 0, a plane of
symmetry) to the land of its end face (y = H), in a stack of identical pellets.

Dimensions (mm): pellet radius 4.1, half height 4.9 (a 9.8 mm pellet); a spherical dish of
footprint radius 2.9 and depth 0.3 in the end face; a chamfer 0.5 wide and 0.15 high at the
outer edge; so the land (the flat annulus that touches the next pellet) runs from r = 2.9 to
r = 3.6. Cladding: inner radius 4.12, outer 4.75, over the same height. Pellet and cladding are
meshed apart (quadrangles of 0.2 mm and of 0.1 mm: the interface r = a does not match).

Physical groups: "pellet" and "cladding" (the cells); "pellet_outer" (the pellet's lateral
surface r = a, the slave side of the gap), "pellet_free" (dish and chamfer, wetted by the
plenum gas), "cladding_inner" (r = b, the master side), "cladding_outer" (r = c, the coolant).

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_pellet_rz.py

With `--plain OUT.msh`: the same segment without dish and chamfer (a plain cylinder, its end
flat), which the tests run against the generated r-z section.
"""

import math
import os
import sys

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))

A = 4.1e-3  # pellet radius
H = 4.9e-3  # half height: mid-plane to land
DISH_R = 2.9e-3  # footprint radius of the dish
DISH_DEPTH = 0.3e-3
CHAMFER_W = 0.5e-3
CHAMFER_H = 0.15e-3
B = 4.12e-3  # cladding inner radius
C = 4.75e-3  # cladding outer radius
PELLET_SIZE = 0.2e-3
CLADDING_SIZE = 0.1e-3


def main(plain=None):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("pellet_rz")
    geo = gmsh.model.geo

    # The dish: a spherical cap through (0, H - depth) and (DISH_R, H), its centre on the axis.
    rho = (DISH_R**2 + DISH_DEPTH**2) / (2.0 * DISH_DEPTH)
    centre_y = H - DISH_DEPTH + rho
    if plain:
        p = [
            geo.addPoint(0.0, 0.0, 0.0, PELLET_SIZE),
            geo.addPoint(A, 0.0, 0.0, PELLET_SIZE),
            geo.addPoint(A, H, 0.0, PELLET_SIZE),
            geo.addPoint(0.0, H, 0.0, PELLET_SIZE),
        ]
        bottom = geo.addLine(p[0], p[1])
        outer = geo.addLine(p[1], p[2])
        top = geo.addLine(p[2], p[3])
        axis = geo.addLine(p[3], p[0])
        free = []
        loop = geo.addCurveLoop([bottom, outer, top, axis])
    else:
        p = [
            geo.addPoint(0.0, 0.0, 0.0, PELLET_SIZE),
            geo.addPoint(A, 0.0, 0.0, PELLET_SIZE),
            geo.addPoint(A, H - CHAMFER_H, 0.0, PELLET_SIZE / 2),
            geo.addPoint(A - CHAMFER_W, H, 0.0, PELLET_SIZE / 2),
            geo.addPoint(DISH_R, H, 0.0, PELLET_SIZE / 2),
            geo.addPoint(0.0, H - DISH_DEPTH, 0.0, PELLET_SIZE),
        ]
        centre = geo.addPoint(0.0, centre_y, 0.0, PELLET_SIZE)
        bottom = geo.addLine(p[0], p[1])
        outer = geo.addLine(p[1], p[2])
        chamfer = geo.addLine(p[2], p[3])
        land = geo.addLine(p[3], p[4])
        dish = geo.addCircleArc(p[4], centre, p[5])
        axis = geo.addLine(p[5], p[0])
        free = [chamfer, dish]
        loop = geo.addCurveLoop([bottom, outer, chamfer, land, dish, axis])
    pellet = geo.addPlaneSurface([loop])

    q = [
        geo.addPoint(B, 0.0, 0.0, CLADDING_SIZE),
        geo.addPoint(C, 0.0, 0.0, CLADDING_SIZE),
        geo.addPoint(C, H, 0.0, CLADDING_SIZE),
        geo.addPoint(B, H, 0.0, CLADDING_SIZE),
    ]
    c_bottom = geo.addLine(q[0], q[1])
    c_outer = geo.addLine(q[1], q[2])
    c_top = geo.addLine(q[2], q[3])
    c_inner = geo.addLine(q[3], q[0])
    cladding = geo.addPlaneSurface([geo.addCurveLoop([c_bottom, c_outer, c_top, c_inner])])
    geo.synchronize()

    for s in (pellet, cladding):
        gmsh.model.mesh.setRecombine(2, s)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # frontal-Delaunay for quadrangles
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 2)  # blossom: quadrangles only
    gmsh.model.addPhysicalGroup(2, [pellet], name="pellet")
    gmsh.model.addPhysicalGroup(2, [cladding], name="cladding")
    gmsh.model.addPhysicalGroup(1, [outer], name="pellet_outer")
    if free:
        gmsh.model.addPhysicalGroup(1, free, name="pellet_free")
    gmsh.model.addPhysicalGroup(1, [c_inner], name="cladding_inner")
    gmsh.model.addPhysicalGroup(1, [c_outer], name="cladding_outer")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    out = plain or os.path.join(HERE, "pellet_rz.msh")
    gmsh.write(out)
    gmsh.finalize()
    dish_volume = math.pi * DISH_DEPTH / 6.0 * (3.0 * DISH_R**2 + DISH_DEPTH**2)
    chamfer_volume = 2.0 * math.pi * (A - CHAMFER_W / 3.0) * 0.5 * CHAMFER_W * CHAMFER_H
    print("wrote", out, "" if plain else "end voids (revolved) %.6e m^3" % (dish_volume + chamfer_volume))


if __name__ == "__main__":
    main(sys.argv[2] if len(sys.argv) > 2 and sys.argv[1] == "--plain" else None)
