"""Makes the Gmsh meshes that the tests read, with Gmsh's own defaults (OpenCASCADE geometry,
Frontal-Delaunay triangles, Gmsh's node and curve orientation), as a new user would.

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_meshes.py

Writes, next to this script:
- pellet_gap_2d.msh: a disc (the pellet, radius 4.1 mm) inside an annulus (the cladding,
  4.18 to 4.75 mm), an 80 um open gap, triangles; groups pellet, cladding (2D),
  pellet_surface, cladding_inner, cladding_outer (1D). ASCII.
- pellet_gap_3d.msh: a cylinder (radius 4.1 mm, height 2 mm) inside a tube (4.18 to 4.75 mm),
  tetrahedra; groups pellet, cladding (3D), pellet_surface, cladding_inner (2D, lateral
  surfaces). Binary.
"""

import os

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
A, B, C = 4.1e-3, 4.18e-3, 4.75e-3


def pellet_2d():
    gmsh.model.add("pellet_gap_2d")
    occ = gmsh.model.occ
    pellet = occ.addDisk(0, 0, 0, A, A)
    outer = occ.addDisk(0, 0, 0, C, C)
    inner = occ.addDisk(0, 0, 0, B, B)
    cladding, _ = occ.cut([(2, outer)], [(2, inner)])
    occ.synchronize()
    clad = cladding[0][1]
    gmsh.model.addPhysicalGroup(2, [pellet], name="pellet")
    gmsh.model.addPhysicalGroup(2, [clad], name="cladding")
    pellet_curves = [c[1] for c in gmsh.model.getBoundary([(2, pellet)], oriented=False)]
    gmsh.model.addPhysicalGroup(1, pellet_curves, name="pellet_surface")
    clad_curves = [c[1] for c in gmsh.model.getBoundary([(2, clad)], oriented=False)]
    def radius(curve):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
        return 0.5 * (x1 - x0)
    inner_c = [c for c in clad_curves if radius(c) < 0.5 * (B + C)]
    outer_c = [c for c in clad_curves if radius(c) >= 0.5 * (B + C)]
    gmsh.model.addPhysicalGroup(1, inner_c, name="cladding_inner")
    gmsh.model.addPhysicalGroup(1, outer_c, name="cladding_outer")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.35e-3)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(os.path.join(HERE, "pellet_gap_2d.msh"))
    gmsh.model.remove()


def pellet_3d():
    gmsh.model.add("pellet_gap_3d")
    occ = gmsh.model.occ
    h = 2e-3
    pellet = occ.addCylinder(0, 0, 0, 0, 0, h, A)
    outer = occ.addCylinder(0, 0, 0, 0, 0, h, C)
    inner = occ.addCylinder(0, 0, 0, 0, 0, h, B)
    cladding, _ = occ.cut([(3, outer)], [(3, inner)])
    occ.synchronize()
    clad = cladding[0][1]
    gmsh.model.addPhysicalGroup(3, [pellet], name="pellet")
    gmsh.model.addPhysicalGroup(3, [clad], name="cladding")

    def lateral(volume, r):
        out = []
        for dim, s in gmsh.model.getBoundary([(3, volume)], oriented=False):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
            if z1 - z0 > 0.5 * h and abs(0.5 * (x1 - x0) - r) < 1e-5:
                out.append(s)
        return out

    gmsh.model.addPhysicalGroup(2, lateral(pellet, A), name="pellet_surface")
    gmsh.model.addPhysicalGroup(2, lateral(clad, B), name="cladding_inner")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.6e-3)
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(os.path.join(HERE, "pellet_gap_3d.msh"))
    gmsh.model.remove()


if __name__ == "__main__":
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    pellet_2d()
    pellet_3d()
    gmsh.finalize()
