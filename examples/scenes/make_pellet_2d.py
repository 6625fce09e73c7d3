"""Makes pellet_2d.msh, the 2D cross-section of a rod whose pellet sits off-centre in its
cladding (the rod's axis at the origin, the pellet's centre 5 um along x: the as-built gap is
15 um on one side and 25 um on the other), for pellet_2d.toml.

Dimensions (mm): pellet radius 4.1; cladding inner radius 4.12, outer 4.75. Pellet and
cladding are meshed apart (quadrangles of 0.1 mm along the gap, growing to 0.6 mm inside the pellet; the interface
does not match: the two circles' nodes differ).

Physical groups: "pellet" and "cladding" (the cells); "pellet_outer" (the pellet's circle, the
slave side of the gap), "cladding_inner" (the master side), "cladding_outer" (the coolant).

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_pellet_2d.py

With `--centred OUT.msh`: the pellet on the axis (the tests run it against the generated
cross-section).
"""

import os
import sys

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))

A = 4.1e-3
B = 4.12e-3
C = 4.75e-3
OFFSET = 5e-6
SURFACE_SIZE = 0.1e-3  # along the gap's two circles
PELLET_SIZE = 0.6e-3  # inside the pellet


def main(centred=None):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("pellet_2d")
    occ = gmsh.model.occ
    e = 0.0 if centred else OFFSET
    pellet = occ.addDisk(e, 0.0, 0.0, A, A)
    outer = occ.addDisk(0.0, 0.0, 0.0, C, C)
    inner = occ.addDisk(0.0, 0.0, 0.0, B, B)
    cladding, _ = occ.cut([(2, outer)], [(2, inner)])
    occ.synchronize()
    cladding = cladding[0][1]
    # Fine along the circles (a chord of 0.1 mm lies 0.3 um inside a 4.1 mm circle, 1.5 % of
    # the 20 um gap), coarse inside the pellet.
    gmsh.model.mesh.setSize(gmsh.model.getBoundary([(2, pellet)], recursive=True), SURFACE_SIZE)
    gmsh.model.mesh.setSize(gmsh.model.getBoundary([(2, cladding)], recursive=True), SURFACE_SIZE)
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "CurvesList", [c for _, c in gmsh.model.getBoundary([(2, pellet)], oriented=False)])
    grade = field.add("Threshold")
    field.setNumber(grade, "InField", dist)
    field.setNumber(grade, "SizeMin", SURFACE_SIZE)
    field.setNumber(grade, "SizeMax", PELLET_SIZE)
    field.setNumber(grade, "DistMin", 0.2e-3)
    field.setNumber(grade, "DistMax", 2.0e-3)
    field.setAsBackgroundMesh(grade)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    for s in (pellet, cladding):
        gmsh.model.mesh.setRecombine(2, s)
    gmsh.option.setNumber("Mesh.Algorithm", 8)
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 2)
    circle = [c for _, c in gmsh.model.getBoundary([(2, pellet)], oriented=False)]
    ring = [c for _, c in gmsh.model.getBoundary([(2, cladding)], oriented=False)]

    def radius(curve):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
        return 0.5 * (x1 - x0)

    gmsh.model.addPhysicalGroup(2, [pellet], name="pellet")
    gmsh.model.addPhysicalGroup(2, [cladding], name="cladding")
    gmsh.model.addPhysicalGroup(1, circle, name="pellet_outer")
    gmsh.model.addPhysicalGroup(1, [c for c in ring if radius(c) < 0.5 * (B + C)], name="cladding_inner")
    gmsh.model.addPhysicalGroup(1, [c for c in ring if radius(c) > 0.5 * (B + C)], name="cladding_outer")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    out = centred or os.path.join(HERE, "pellet_2d.msh")
    gmsh.write(out)
    gmsh.finalize()
    print("wrote", out)


if __name__ == "__main__":
    main(sys.argv[2] if len(sys.argv) > 2 and sys.argv[1] == "--centred" else None)
