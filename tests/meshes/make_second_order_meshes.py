"""Makes the second-order Gmsh meshes that tests/integration/second_order.rs reads: two bodies
meshed independently (so that their interface is non-conforming), Mesh.ElementOrder = 2, with
Gmsh's own node order, as a new user would.

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_second_order_meshes.py

Each file holds two bodies and the two faces of their common interface:
- so_2d_quad8.msh: left [0,1]x[0,1] in Tri6 (size 0.3), right [1,2]x[0,1] in Quad8 (4 x 4,
  incomplete second order); groups left, right, left_x1, right_x0, left_x0, right_x1.
- so_2d_quad9.msh: the same with Quad9 on the left (3 x 3) and Tri6 on the right (size 0.27).
- so_3d_hex20.msh: bottom [0,1]^2 x [0,0.5] in Hex20 (3 x 3 x 2), top [0,1]^2 x [0.5,1] in
  Tet10 (size 0.35); groups bottom, top, bottom_top, top_bottom, bottom_z0, top_z1.
- so_3d_hex27.msh: the same with Tet10 below (size 0.35) and Hex27 above (4 x 4 x 2).
- so_2d_arc.msh: a disc of radius 1 in Tri6 (its circle in 20 Line3) and the annulus
  1 < r < 2 around it in Tri6 (its inner circle in 27 Line3), meshed apart, the middle nodes
  on the circle: curved Line3 faces; groups disc, annulus, disc_edge, annulus_inner.
- so3_2d_tri10.msh: Mesh.ElementOrder = 3, the 2D bodies both in cubic Tri10 (Gmsh type 21,
  faces Line4, type 26: elements the library does not ship; examples/extend_element.rs
  defines them), left size 0.45, right 0.3; the groups of so_2d_quad8.msh.
- fo_3d_hex8.msh: first order (Mesh.ElementOrder = 1), Hex8 below (3 x 3 x 2) and Tet4
  above (size 0.35); the groups of so_3d_hex20.msh.
ASCII, Gmsh 4.1 format.
"""

import os

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))


def body_2d(x0, quads, n, size):
    occ = gmsh.model.occ
    s = occ.addRectangle(x0, 0, 0, 1, 1)
    occ.synchronize()
    curves = [c[1] for c in gmsh.model.getBoundary([(2, s)], oriented=False)]
    if quads:
        for c in curves:
            gmsh.model.mesh.setTransfiniteCurve(c, n + 1)
        gmsh.model.mesh.setTransfiniteSurface(s)
        gmsh.model.mesh.setRecombine(2, s)
    else:
        pts = gmsh.model.getBoundary([(2, s)], recursive=True)
        gmsh.model.mesh.setSize(pts, size)
    return s, curves


def at_x(curves, x):
    out = []
    for c in curves:
        x0, _, _, x1, _, _ = gmsh.model.getBoundingBox(1, c)
        if abs(x0 - x) < 1e-6 and abs(x1 - x) < 1e-6:
            out.append(c)
    return out


def file_2d(name, left_quads, right_quads, incomplete, order=2, sizes=None):
    gmsh.model.add(name)
    if sizes is None:
        sizes = (0.3, 0.27 if incomplete == 0 else 0.3)
    left, lc = body_2d(0.0, left_quads, 3 if incomplete == 0 else 4, sizes[0])
    right, rc = body_2d(1.0, right_quads, 4, sizes[1])
    gmsh.model.addPhysicalGroup(2, [left], name="left")
    gmsh.model.addPhysicalGroup(2, [right], name="right")
    gmsh.model.addPhysicalGroup(1, at_x(lc, 1.0), name="left_x1")
    gmsh.model.addPhysicalGroup(1, at_x(rc, 1.0), name="right_x0")
    gmsh.model.addPhysicalGroup(1, at_x(lc, 0.0), name="left_x0")
    gmsh.model.addPhysicalGroup(1, at_x(rc, 2.0), name="right_x1")
    mesh_and_write(name, 2, incomplete, order)


def body_3d(z0, hexes, n, nz, size):
    occ = gmsh.model.occ
    v = occ.addBox(0, 0, z0, 1, 1, 0.5)
    occ.synchronize()
    if hexes:
        for dim, c in gmsh.model.getEntities(1):
            x0, y0, zz0, x1, y1, zz1 = gmsh.model.getBoundingBox(1, c)
            if zz0 < z0 - 1e-6 or zz1 > z0 + 0.5 + 1e-6:
                continue
            vertical = abs(zz1 - zz0) > 1e-6
            gmsh.model.mesh.setTransfiniteCurve(c, (nz if vertical else n) + 1)
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False):
            gmsh.model.mesh.setTransfiniteSurface(s)
            gmsh.model.mesh.setRecombine(2, s)
        gmsh.model.mesh.setTransfiniteVolume(v)
        gmsh.model.mesh.setRecombine(3, v)
    else:
        pts = gmsh.model.getBoundary([(3, v)], recursive=True)
        gmsh.model.mesh.setSize(pts, size)
    faces = [s for _, s in gmsh.model.getBoundary([(3, v)], oriented=False)]
    return v, faces


def at_z(faces, z):
    out = []
    for s in faces:
        _, _, z0, _, _, z1 = gmsh.model.getBoundingBox(2, s)
        if abs(z0 - z) < 1e-6 and abs(z1 - z) < 1e-6:
            out.append(s)
    return out


def file_3d(name, bottom_hexes, top_hexes, n_hex, incomplete, order=2):
    gmsh.model.add(name)
    bottom, bf = body_3d(0.0, bottom_hexes, n_hex, 2, 0.35)
    top, tf = body_3d(0.5, top_hexes, n_hex, 2, 0.35)
    gmsh.model.addPhysicalGroup(3, [bottom], name="bottom")
    gmsh.model.addPhysicalGroup(3, [top], name="top")
    gmsh.model.addPhysicalGroup(2, at_z(bf, 0.5), name="bottom_top")
    gmsh.model.addPhysicalGroup(2, at_z(tf, 0.5), name="top_bottom")
    gmsh.model.addPhysicalGroup(2, at_z(bf, 0.0), name="bottom_z0")
    gmsh.model.addPhysicalGroup(2, at_z(tf, 1.0), name="top_z1")
    mesh_and_write(name, 3, incomplete, order)


def file_arc(name):
    occ = gmsh.model.occ
    gmsh.model.add(name)
    disc = occ.addDisk(0, 0, 0, 1, 1)
    annulus = occ.cut([(2, occ.addDisk(0, 0, 0, 2, 2))], [(2, occ.addDisk(0, 0, 0, 1, 1))])
    annulus = annulus[0][0][1]
    occ.synchronize()
    circles = lambda s: [c for _, c in gmsh.model.getBoundary([(2, s)], oriented=False)]
    inner = [c for c in circles(annulus) if gmsh.model.getBoundingBox(1, c)[3] < 1.5]
    for c in circles(disc):
        gmsh.model.mesh.setTransfiniteCurve(c, 21)
    for c in inner:
        gmsh.model.mesh.setTransfiniteCurve(c, 28)
    gmsh.model.mesh.setSize(gmsh.model.getBoundary([(2, annulus)], recursive=True), 0.6)
    gmsh.model.addPhysicalGroup(2, [disc], name="disc")
    gmsh.model.addPhysicalGroup(2, [annulus], name="annulus")
    gmsh.model.addPhysicalGroup(1, circles(disc), name="disc_edge")
    gmsh.model.addPhysicalGroup(1, inner, name="annulus_inner")
    mesh_and_write(name, 2, 0)


def mesh_and_write(name, dim, incomplete, order=2):
    gmsh.option.setNumber("Mesh.ElementOrder", order)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", incomplete)
    gmsh.model.mesh.generate(dim)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(os.path.join(HERE, name + ".msh"))
    gmsh.model.remove()


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    file_2d("so_2d_quad8", False, True, 1)
    file_2d("so_2d_quad9", True, False, 0)
    file_3d("so_3d_hex20", True, False, 3, 1)
    file_3d("so_3d_hex27", False, True, 4, 0)
    file_2d("so3_2d_tri10", False, False, 0, order=3, sizes=(0.45, 0.3))
    file_arc("so_2d_arc")
    file_3d("fo_3d_hex8", True, False, 3, 0, order=1)
    gmsh.finalize()


if __name__ == "__main__":
    main()
