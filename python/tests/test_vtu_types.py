"""Every VTU the package writes reads back with meshio with the right cell types: contact
scenes (run_scene, as ``mortar run``) over bodies of each shipped cell type, first and second
order, write the bodies (Tri3, Quad4, Tri6, Quad8, Quad9, Tet4, Hex8, Tet10, Hex20, Hex27)
and the slave surface (Line2, Line3, Tri3, Quad4, Tri6, Quad8, Quad9). Second-order faces
were written as triangles (Line3) or refused (9 nodes); VTK's quadratic cell types are the
reference (VTK file format documentation: 21 quadratic edge, 22 quadratic triangle, 23
quadratic quad, 28 biquadratic quad)."""

import pathlib

import meshio
import pytest

import mortar

ROOT = pathlib.Path(__file__).resolve().parents[2]
MESHES = ROOT / "tests" / "meshes"


def scene(mesh, slave, master, ends, faces, push):
    def body(name, end, value):
        return {
            "mesh": str(mesh),
            "group": name,
            "youngs_modulus": 1e9,
            "poisson_ratio": 0.3,
            "dirichlet": [{"group": end, "component": "all", "value": value}],
        }

    return {
        "kind": "contact",
        "bodies": {slave: body(slave, ends[0], push), master: body(master, ends[1], 0.0)},
        "contact": {
            "slave": {"body": slave, "group": faces[0]},
            "master": {"body": master, "group": faces[1]},
        },
    }


Z = [0.0, 0.0, -0.001]
CASES = [
    # file, slave, master, outer faces, interface faces, push, types (slave, master, surface)
    ("fo_3d_hex8.msh", "top", "bottom", ("top_z1", "bottom_z0"), ("top_bottom", "bottom_top"), Z,
     ("tetra", "hexahedron", "triangle")),
    ("fo_3d_hex8.msh", "bottom", "top", ("bottom_z0", "top_z1"), ("bottom_top", "top_bottom"),
     [0.0, 0.0, 0.001], ("hexahedron", "tetra", "quad")),
    ("so_3d_hex27.msh", "top", "bottom", ("top_z1", "bottom_z0"), ("top_bottom", "bottom_top"), Z,
     ("hexahedron27", "tetra10", "quad9")),
    ("so_3d_hex20.msh", "bottom", "top", ("bottom_z0", "top_z1"), ("bottom_top", "top_bottom"),
     [0.0, 0.0, 0.001], ("hexahedron20", "tetra10", "quad8")),
    ("so_3d_hex20.msh", "top", "bottom", ("top_z1", "bottom_z0"), ("top_bottom", "bottom_top"), Z,
     ("tetra10", "hexahedron20", "triangle6")),
    ("so_2d_quad8.msh", "right", "left", ("right_x1", "left_x0"), ("right_x0", "left_x1"),
     [-0.001, 0.0], ("quad8", "triangle6", "line3")),
    ("so_2d_quad9.msh", "left", "right", ("left_x0", "right_x1"), ("left_x1", "right_x0"),
     [0.001, 0.0], ("quad9", "triangle6", "line3")),
]


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_vtu_cell_types_read_back_with_meshio(tmp_path, case):
    file, slave, master, ends, faces, push, types = case
    report = mortar.run_scene(scene(MESHES / file, slave, master, ends, faces, push), tmp_path)
    assert report["active"] > 0
    for name, expected in zip([slave, master, "interface"], types):
        m = meshio.read(tmp_path / f"{name}.vtu")
        assert [c.type for c in m.cells] == [expected], name
        assert len(m.cells[0].data) > 0


def test_first_order_2d_example_scene_types(tmp_path):
    # The example contact scene: triangles on quadrangles, Line2 faces.
    mortar.run_scene(ROOT / "examples" / "scenes" / "contact_blocks.toml", tmp_path)
    got = {n: [c.type for c in meshio.read(tmp_path / f"{n}.vtu").cells]
           for n in ["upper", "lower", "interface"]}
    assert got == {"upper": ["triangle"], "lower": ["quad"], "interface": ["line"]}
