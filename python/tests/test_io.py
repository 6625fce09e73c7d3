"""read_gmsh on the repository's Gmsh files, and a meshio round trip: write Gmsh files with
meshio, read them with mortar and with meshio, couple, write the result with meshio."""

import pathlib

import meshio
import numpy as np
import pytest

import mortar

SCENES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "scenes"


def test_read_gmsh_groups_of_the_tied_square():
    s = mortar.read_gmsh(SCENES / "tied_square_right.msh", "right_cut")
    m = mortar.read_gmsh(SCENES / "tied_square_left.msh", group="left_cut")
    points, cells, cell_type = s  # a plain 3-tuple
    assert cell_type == "line" and points.shape == (13, 2) and cells.shape == (12, 2)
    assert points.dtype == np.float64 and cells.dtype == np.int64
    assert np.allclose(points[:, 0], 0.5)
    assert len(s.node_tags) == 13 and len(s.cell_tags) == 12
    c = mortar.couple(s, m, multipliers="dual")
    assert c.stats["area"] == pytest.approx(1.0, rel=1e-13)
    assert np.abs(c.D.sum(axis=1) - c.M.sum(axis=1)).max() < 1e-15


def test_read_gmsh_errors():
    with pytest.raises(mortar.MeshFileError, match="no physical group named") as e:
        mortar.read_gmsh(SCENES / "tied_square_right.msh", "nope")
    assert "right_cut" in str(e.value)  # the message lists the file's groups
    with pytest.raises(OSError):
        mortar.read_gmsh(SCENES / "no_such_file.msh")


def two_bodies_interface(lines=True):
    """The faces z = 0 of two non-matching planar triangulations of [0, 2] x [0, 1], as one
    meshio mesh each, with a physical group named "cut" and (with `lines`) one named "other"
    (a strip of lines that must not be selected; meshio writes Gmsh 4.1 files of one cell
    type only)."""
    def tri_mesh(nx, ny):
        xs, ys = np.meshgrid(np.linspace(0, 2, nx + 1), np.linspace(0, 1, ny + 1))
        pts = np.c_[xs.ravel(), ys.ravel(), np.zeros(xs.size)]
        i, j = np.meshgrid(np.arange(nx), np.arange(ny))
        a = (i + (nx + 1) * j).ravel()
        tris = np.vstack([np.c_[a, a + 1, a + nx + 2], np.c_[a, a + nx + 2, a + nx + 1]])
        if not lines:
            return meshio.Mesh(
                pts,
                [("triangle", tris)],
                cell_data={
                    "gmsh:physical": [np.full(len(tris), 7)],
                    "gmsh:geometrical": [np.full(len(tris), 1)],
                },
                field_data={"cut": np.array([7, 2])},
            )
        lines_ = np.c_[np.arange(nx), np.arange(1, nx + 1)]
        return meshio.Mesh(
            pts,
            [("triangle", tris), ("line", lines_)],
            cell_data={
                "gmsh:physical": [np.full(len(tris), 7), np.full(len(lines_), 8)],
                "gmsh:geometrical": [np.full(len(tris), 1), np.full(len(lines_), 1)],
            },
            field_data={"cut": np.array([7, 2]), "other": np.array([8, 1])},
        )

    return tri_mesh(6, 4), tri_mesh(9, 5)


@pytest.mark.parametrize("binary", [False, True])
def test_meshio_round_trip(tmp_path, binary):
    slave, master = two_bodies_interface(lines=False)
    files = []
    for name, mesh in [("slave", slave), ("master", master)]:
        path = tmp_path / f"{name}.msh"
        meshio.write(path, mesh, file_format="gmsh", binary=binary)
        files.append(path)
    # mortar's own reader, the whole file (meshio writes Gmsh 4.1 without an $Entities
    # section, which selecting a physical group by mortar's reader needs: it says so).
    c_file = mortar.couple(mortar.read_gmsh(files[0]), mortar.read_gmsh(files[1]))
    with pytest.raises(mortar.MeshFileError, match="no .Entities section"):
        mortar.read_gmsh(files[0], "cut")
    # meshio's reader: the whole mesh (meshio reads the physical groups of a file only
    # with its $Entities, so its "cut" cell set comes back empty).
    ms, mm = meshio.read(files[0]), meshio.read(files[1])
    c_mesh = mortar.couple(ms, mm)
    # In memory, from meshes that also have a group of lines: by physical name, by tag.
    with_lines = two_bodies_interface(lines=True)
    c_mem = mortar.couple(*[(m, "cut") for m in with_lines])
    c_tag = mortar.couple(*[(m, 7) for m in with_lines])
    for c in (c_file, c_mesh, c_tag, c_mem):
        assert c.stats["area"] == pytest.approx(2.0, rel=1e-13)
        assert c.D.shape == (35, 35) and c.M.shape == (35, 60)
    # The same operators whichever way the surfaces came (the file's node numbering is the
    # points' order, so the node maps agree too).
    for c in (c_mesh, c_tag, c_mem):
        assert abs(c.D - c_mem.D).max() <= 1e-15 and abs(c.M - c_mem.M).max() <= 1e-15
    assert np.array_equal(c_mesh.slave_nodes, c_mem.slave_nodes)

    # Write the slave surface with the nodal areas (row sums of D) and the normals, read back.
    rows = np.asarray(c_mem.D.sum(axis=1)).ravel()
    area = np.zeros(len(slave.points))
    area[c_mem.slave_nodes] = rows
    normals = np.zeros((len(slave.points), 3))
    normals[c_mem.slave_nodes] = c_mem.normals
    out = meshio.Mesh(
        slave.points,
        [("triangle", slave.cells_dict["triangle"])],
        point_data={"nodal_area": area, "normal": normals},
    )
    vtu = tmp_path / "slave.vtu"
    meshio.write(vtu, out)
    back = meshio.read(vtu)
    assert np.array_equal(back.point_data["nodal_area"], area)
    assert back.point_data["nodal_area"].sum() == pytest.approx(2.0, rel=1e-13)


def test_meshio_selection_errors():
    slave, master = two_bodies_interface()
    with pytest.raises(mortar.InvalidInputError, match="no cell set or physical group 'nope'"):
        mortar.couple((slave, "nope"), (master, "cut"))
    # The whole mesh without a selection: its triangles (the lines are dropped).
    c = mortar.couple(slave, master)
    assert c.stats["area"] == pytest.approx(2.0, rel=1e-13)
