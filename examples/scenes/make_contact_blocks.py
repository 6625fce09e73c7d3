"""Makes the two Gmsh meshes of contact_blocks.toml: a block [0,1] x [1,2] of triangles (size
0.2) resting on a block [0,1] x [0,1] of 4 x 4 quadrangles, meshed apart (non-matching at
y = 1); each file has its body's group and the face groups NAME_top, NAME_bottom, NAME_left.

    python3 -m venv venv && venv/bin/pip install gmsh && venv/bin/python make_contact_blocks.py
"""

import os

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))


def block(name, y0, quads):
    gmsh.model.add(name)
    occ = gmsh.model.occ
    s = occ.addRectangle(0, y0, 0, 1, 1)
    occ.synchronize()
    curves = [c for _, c in gmsh.model.getBoundary([(2, s)], oriented=False)]
    if quads:
        for c in curves:
            gmsh.model.mesh.setTransfiniteCurve(c, 5)
        gmsh.model.mesh.setTransfiniteSurface(s)
        gmsh.model.mesh.setRecombine(2, s)
    else:
        pts = gmsh.model.getBoundary([(2, s)], recursive=True)
        gmsh.model.mesh.setSize(pts, 0.2)

    def where(test):
        out = []
        for c in curves:
            x0, ya, _, x1, yb, _ = gmsh.model.getBoundingBox(1, c)
            if test(x0, ya, x1, yb):
                out.append(c)
        return out

    gmsh.model.addPhysicalGroup(2, [s], name=name)
    gmsh.model.addPhysicalGroup(1, where(lambda x0, ya, x1, yb: abs(ya - y0 - 1) < 1e-6 and abs(yb - y0 - 1) < 1e-6), name=name + "_top")
    gmsh.model.addPhysicalGroup(1, where(lambda x0, ya, x1, yb: abs(ya - y0) < 1e-6 and abs(yb - y0) < 1e-6), name=name + "_bottom")
    gmsh.model.addPhysicalGroup(1, where(lambda x0, ya, x1, yb: abs(x0) < 1e-6 and abs(x1) < 1e-6), name=name + "_left")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(os.path.join(HERE, name + ".msh"))
    gmsh.model.remove()


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    block("contact_lower", 0.0, True)
    block("contact_upper", 1.0, False)
    gmsh.finalize()


if __name__ == "__main__":
    main()
