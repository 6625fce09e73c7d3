"""mortar.couple from arrays: the mortar properties on non-matching meshes in 2D and 3D, the
node maps, and the errors of bad input."""

import numpy as np
import pytest
import scipy.sparse

import mortar


def grid_quads(nx, ny, x0=0.0, x1=1.0, y0=0.0, y1=1.0, z=0.0):
    """(points, quads) of an nx x ny grid of quads over [x0, x1] x [y0, y1] at height z."""
    xs, ys = np.meshgrid(np.linspace(x0, x1, nx + 1), np.linspace(y0, y1, ny + 1))
    pts = np.c_[xs.ravel(), ys.ravel(), np.full(xs.size, z)]
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    a = (i + (nx + 1) * j).ravel()
    quads = np.c_[a, a + 1, a + nx + 2, a + nx + 1]
    return pts, quads


def grid_triangles(nx, ny, **kw):
    """The same grid, each quad cut along its (0,0)-(1,1) diagonal."""
    pts, q = grid_quads(nx, ny, **kw)
    tris = np.vstack([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    return pts, tris


def square_edge(n, x=0.5, reverse=False, jitter=0.0, seed=0):
    """The line x = const, y in [0, 1], as n two-node lines, with interior nodes moved by
    up to jitter of a segment (non-uniform spacing)."""
    y = np.linspace(0.0, 1.0, n + 1)
    if jitter:
        rng = np.random.default_rng(seed)
        y[1:-1] += rng.uniform(-jitter, jitter, n - 1) / n
    pts = np.c_[np.full(n + 1, x), y]
    lines = np.c_[np.arange(n), np.arange(1, n + 1)]
    if reverse:
        lines = lines[:, ::-1]
    return pts, lines


def check_properties(c, xs_all, xm_all, area):
    """sum(D) = area, D 1 = M 1, and the linear field reproduced: D x_s = M x_m."""
    assert isinstance(c.D, scipy.sparse.csr_array)
    assert isinstance(c.M, scipy.sparse.csr_array)
    assert c.D.shape == (len(c.slave_nodes), len(c.slave_nodes))
    assert c.M.shape == (len(c.slave_nodes), len(c.master_nodes))
    assert c.D.sum() == pytest.approx(area, rel=1e-13)
    assert c.stats["area"] == pytest.approx(area, rel=1e-13)
    d1 = c.D @ np.ones(c.D.shape[1])
    m1 = c.M @ np.ones(c.M.shape[1])
    assert np.abs(d1 - m1).max() <= 1e-14 * area
    gap = c.weighted_gap(xs_all[c.slave_nodes], xm_all[c.master_nodes])
    assert np.abs(gap).max() <= 1e-13 * area
    # The linear field u = 1 + 2x - 3y + z, node by node.
    u = lambda x: 1 + 2 * x[:, 0] - 3 * x[:, 1] + (x[:, 2] if x.shape[1] == 3 else 0)
    assert np.abs(c.D @ u(xs_all[c.slave_nodes]) - c.M @ u(xm_all[c.master_nodes])).max() <= 1e-13


@pytest.mark.parametrize("multipliers", ["standard", "dual"])
def test_2d_edges_of_two_squares(multipliers):
    # The cut x = 0.5 of [0, 1]^2 seen by the left body (7 segments) and the right (11).
    sp, sl = square_edge(7, jitter=0.3, seed=1)
    mp, ml = square_edge(11, reverse=True, jitter=0.3, seed=2)
    c = mortar.couple((sp, sl, "line"), (mp, ml, "line"), multipliers=multipliers)
    assert c.dim == 2
    assert c.normals.shape == (8, 2)
    check_properties(c, sp, mp, 1.0)
    # The node maps are rows of the points given, ascending.
    assert c.slave_nodes.tolist() == list(range(8))
    assert c.master_nodes.tolist() == list(range(12))
    # Normals are unit and perpendicular to the line (along x).
    assert np.allclose(np.abs(c.normals[:, 0]), 1.0)
    # A straight interface: coupled by the sorted merge, every slave face.
    assert c.stats["straight_line_faces"] == 7
    assert c.stats["fused_line_faces"] == 0
    if multipliers == "dual":
        offdiag = c.D - scipy.sparse.diags_array(c.D.diagonal())
        assert abs(offdiag).max() <= 1e-13 * c.D.diagonal().max()
        assert "dual" in c.formulation


@pytest.mark.parametrize("multipliers", ["standard", "dual"])
def test_3d_non_matching_triangulations(multipliers):
    sp, st = grid_triangles(6, 5)
    mp, mt = grid_triangles(9, 7)
    # A rigid motion of both: the properties do not depend on the plane's position.
    rot = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))[0]
    sp, mp = sp @ rot.T + [1.0, -2.0, 0.5], mp @ rot.T + [1.0, -2.0, 0.5]
    c = mortar.couple((sp, st, "triangle"), (mp, mt, "Tri3"), multipliers=multipliers)
    assert c.dim == 3
    check_properties(c, sp, mp, 1.0)
    assert c.stats["pairs"] > st.shape[0]
    assert c.stats["degrees_used"] == [2]
    # Linear triangles lie in their nodes' boxes: the search inflates neither side's.
    assert c.stats["slave_box_inflation"] == 0.0 and c.stats["master_box_inflation"] == 0.0
    # The slave normals are the plane's normal, one way or the other, all the same way.
    n = rot[:, 2]
    dots = c.normals @ n
    assert np.allclose(np.abs(dots), 1.0) and (np.all(dots > 0) or np.all(dots < 0))
    if multipliers == "dual":
        offdiag = c.D - scipy.sparse.diags_array(c.D.diagonal())
        assert abs(offdiag).max() <= 1e-13 * c.D.diagonal().max()


def test_mixed_blocks_and_unused_points():
    # Slave: quads on the left half, triangles on the right; the points array has an extra
    # unused point (with NaN: unused points are not read).
    qp, q = grid_quads(4, 4)
    pts = np.vstack([qp, [[np.nan, np.nan, np.nan]]])
    left = q[(np.arange(16) % 4) < 2]
    right = q[(np.arange(16) % 4) >= 2]
    tris = np.vstack([right[:, [0, 1, 2]], right[:, [0, 2, 3]]])
    mp, mq = grid_quads(3, 5)
    c = mortar.couple((pts, [("quad", left), ("triangle", tris)]), (mp, mq, "quad"))
    check_properties(c, pts, mp, 1.0)
    assert len(c.slave_nodes) == 25 and 25 not in c.slave_nodes


def test_integer_dtypes_and_orientation():
    sp, st = grid_triangles(3, 3)
    mp, mt = grid_triangles(4, 4)
    # Same result from int32 cells, Fortran-ordered points, and the master given facing
    # the same way as the slave (orient=True turns it).
    a = mortar.couple((sp, st, "triangle"), (mp, mt, "triangle"))
    b = mortar.couple(
        (np.asfortranarray(sp), st.astype(np.int32), "triangle"),
        (mp, mt[:, ::-1].astype(np.uint16), "triangle"),
    )
    # The master's node order changes the order of summation: equal to round-off.
    assert abs(a.D - b.D).max() <= 1e-15 and abs(a.M - b.M).max() <= 1e-15
    flipped = a.stats["orientation"]["master"]["flipped"] + b.stats["orientation"]["master"]["flipped"]
    assert flipped == mt.shape[0]  # each of the two orders was flipped once
    # Without orientation, a master looking the same way as the slave overlaps nothing.
    with pytest.raises(mortar.NoOverlapError, match="reverse the node order"):
        mortar.couple((sp, st, "triangle"), (mp, mt, "triangle"), orient=False)


def test_options_and_stats():
    sp, sq = grid_quads(5, 5)
    mp, mt = grid_triangles(7, 7)
    c = mortar.couple(
        (sp, sq, "quad"), (mp, mt, "triangle"), integration="element", degree=3, threads=1
    )
    assert "element-based" in c.formulation and c.stats["threads"] == 1
    assert c.stats["degrees_used"] == [3]
    for key in ("pairs", "segments", "area", "seconds", "seconds_call", "degrees_used"):
        assert key in c.stats
    assert c.stats["seconds_call"] >= c.stats["seconds"] > 0
    # Bit-identical for any thread count.
    c1 = mortar.couple((sp, sq, "quad"), (mp, mt, "triangle"), threads=1)
    c2 = mortar.couple((sp, sq, "quad"), (mp, mt, "triangle"), threads=2)
    assert np.array_equal(c1.D.data, c2.D.data) and np.array_equal(c1.M.data, c2.M.data)


def test_partial_overlap_warns_and_can_be_required():
    sp, sq = grid_quads(4, 4)
    mp, mq = grid_quads(4, 4, x0=0.5, x1=1.5)
    with pytest.warns(RuntimeWarning, match="uncovered"):
        c = mortar.couple((sp, sq, "quad"), (mp, mq, "quad"))
    assert c.stats["area"] == pytest.approx(0.5, rel=1e-13)
    assert c.stats["uncovered_area"] == pytest.approx(0.5, rel=1e-12)
    with pytest.raises(mortar.CoverageError, match="full coverage"):
        mortar.couple((sp, sq, "quad"), (mp, mq, "quad"), require_full_coverage=True)


# --- errors ---------------------------------------------------------------------------------

SP, ST = grid_triangles(2, 2)
MP, MT = grid_triangles(3, 3)


@pytest.mark.parametrize(
    "slave, match",
    [
        ((SP[:, :1], ST, "triangle"), r"shape \(9, 1\)"),
        ((SP.ravel(), ST, "triangle"), "shape"),
        ((SP.astype(str), ST, "triangle"), "dtype"),
        ((SP, ST.astype(float), "triangle"), "dtype"),
        ((SP, ST[:, :2], "triangle"), "a triangle cell has 3 nodes"),
        ((SP, ST, "hexahedron"), "known types"),
        ((SP, ST + 100, "triangle"), "refers to point"),
        ((SP, ST - 1, "triangle"), "refers to point -1"),
        ((np.where(np.arange(27).reshape(9, 3) == 4, np.nan, SP), ST, "triangle"), "non-finite"),
        ((SP + np.inf, ST, "triangle"), "non-finite"),
        ((SP, ST[:0], "triangle"), "no faces"),
        ("not a surface", "give"),
    ],
)
def test_invalid_input(slave, match):
    with pytest.raises(mortar.InvalidInputError, match=match) as e:
        mortar.couple(slave, (MP, MT, "triangle"))
    assert isinstance(e.value, ValueError) and isinstance(e.value, mortar.MortarError)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"multipliers": "mixed"}, "multipliers"),
        ({"integration": "nodal"}, "integration"),
        ({"threads": 0}, "threads"),
        ({"degree": -1}, "degree"),
        ({"degree": 99}, "degree"),
    ],
)
def test_invalid_options(kw, match):
    with pytest.raises(mortar.InvalidInputError, match=match):
        mortar.couple((SP, ST, "triangle"), (MP, MT, "triangle"), **kw)


def test_degenerate_and_inverted_faces():
    bad = ST.copy()
    bad[0, 1] = bad[0, 0]
    with pytest.raises(mortar.GeometryError, match="slave face 0 is degenerate"):
        mortar.couple((SP, bad, "triangle"), (MP, MT, "triangle"), orient=False)
    # Orienting first meets the repeated node as a fin: still a GeometryError.
    with pytest.raises(mortar.GeometryError):
        mortar.couple((SP, bad, "triangle"), (MP, MT, "triangle"))
    flat = SP.copy()
    flat[4] = flat[0]  # the centre node onto a corner: zero-area faces
    with pytest.raises(mortar.GeometryError, match="degenerate"):
        mortar.couple((flat, ST, "triangle"), (MP, MT, "triangle"))
    # A bow-tie quad.
    qp, q = grid_quads(1, 1)
    with pytest.raises(mortar.GeometryError, match="inverted|self-intersecting"):
        mortar.couple((qp, q[:, [0, 2, 1, 3]], "quad"), (MP, MT, "triangle"))


def test_no_overlap():
    with pytest.raises(mortar.NoOverlapError, match="no overlap"):
        mortar.couple((SP, ST, "triangle"), (MP + [3.0, 0.0, 0.0], MT, "triangle"))


def test_mixed_dimensions():
    lp, ll = square_edge(3)
    with pytest.raises(mortar.InvalidInputError, match="dimension"):
        mortar.couple((lp, ll, "line"), (MP, MT, "triangle"))


def test_weighted_gap_shapes():
    c = mortar.couple((SP, ST, "triangle"), (MP, MT, "triangle"))
    with pytest.raises(mortar.InvalidInputError, match="one row per slave node"):
        c.weighted_gap(SP[:3], MP[c.master_nodes])
    with pytest.raises(mortar.InvalidInputError, match="NaN"):
        c.weighted_gap(SP[c.slave_nodes] * np.nan, MP[c.master_nodes])
    # The master moved 0.1 along the slave normal (which points towards the master): an
    # open gap, and the weighted normal gap is the gap times the row sums of D.
    g = c.normal_gaps(SP[c.slave_nodes], MP[c.master_nodes] + 0.1 * c.normals[0])
    assert np.allclose(g, 0.1 * (c.D @ np.ones(c.D.shape[1])), rtol=1e-12, atol=1e-15)


def test_lines_with_three_columns_are_2d():
    # Lines given with a z = 0 column (as meshio gives a 2D mesh's points): a 2D problem.
    sp, sl = square_edge(4)
    mp, ml = square_edge(5, reverse=True)
    c = mortar.couple((np.c_[sp, np.zeros(5)], sl, "line"), (mp, ml, "line"))
    assert c.dim == 2 and c.normals.shape == (5, 2)
    assert c.weighted_gap(sp[c.slave_nodes], mp[c.master_nodes]).shape == (5, 2)
    # Off the plane z = 0, lines are refused.
    with pytest.raises(mortar.InvalidInputError, match="dimension"):
        mortar.couple((np.c_[sp, np.ones(5)], sl, "line"), (mp, ml, "line"))


def test_gil_is_released_while_the_library_works():
    # A Python thread keeps working while another thread is inside mortar.couple. Measured
    # by the CPU time the waiting thread spends (time.thread_time), not by wall-clock pauses,
    # so that a loaded machine does not decide it: with the GIL held the waiting thread is
    # blocked, waking at every 5 ms switch interval (measured 1.4 % of the wall time with a
    # call that holds the GIL, a backtracking regular expression); released, it spins for its
    # share of a core (100 % on an idle machine, a third with four busy processes on two
    # cores). The bound, 10 %, sits between the two.
    import threading
    import time

    sp, st = grid_triangles(120, 120)
    mp, mt = grid_triangles(181, 181)
    result = {}

    def work():
        result["c"] = mortar.couple((sp, st, "triangle"), (mp, mt, "triangle"), threads=1)

    t = threading.Thread(target=work)
    cpu = time.thread_time()
    t.start()
    spins = 0
    while t.is_alive():
        spins += 1
    cpu = time.thread_time() - cpu
    t.join()
    library = result["c"].stats["seconds"]
    assert library > 0.1
    assert cpu > 0.1 * library, (cpu, library, spins)


def test_huge_options_are_refused():
    with pytest.raises(mortar.InvalidInputError, match="threads"):
        mortar.couple((SP, ST, "triangle"), (MP, MT, "triangle"), threads=2**40)
    with pytest.raises(mortar.InvalidInputError, match="degree"):
        mortar.couple((SP, ST, "triangle"), (MP, MT, "triangle"), degree=2**40)


def test_segment_dials_reach_the_integration():
    # A slave quad that is not a parallelogram against a finer Tri3 master: cutting its clip
    # triangles (quad_subdivision) changes only the distribution of M; D, D 1 = M 1 stay.
    s_pts = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.2, 0.0], [0.0, 0.8, 0.0]])
    s = (s_pts, np.array([[0, 1, 2, 3]]), "quad")
    m = grid_triangles(5, 5, x0=-0.1, x1=1.3, y0=-0.1, y1=1.3)
    plain = mortar.couple(s, (*m, "triangle"))
    cut = mortar.couple(s, (*m, "triangle"), quad_subdivision=4)
    assert "cut 4x4" in cut.formulation
    assert abs(cut.D - plain.D).max() < 1e-14
    assert np.abs(cut.D.sum(axis=1) - cut.M.sum(axis=1)).max() < 1e-14
    assert abs(cut.M - plain.M).max() > 1e-9
    with pytest.raises(mortar.InvalidInputError, match="quad subdivision"):
        mortar.couple(s, (*m, "triangle"), quad_subdivision=0)
    with pytest.raises(mortar.InvalidInputError, match="segment"):
        mortar.couple(s, (*m, "triangle"), integration="element", subdivision=2)


def test_search_radius_reaches_the_interface():
    # Two unit squares of 4 x 4 quads (face size 0.25) 0.3 apart: a search radius below the
    # gap finds no master face, one above it couples the whole area (as mortar couple
    # --search-radius does); a negative radius is refused by the library's settings.
    sp_, sq = grid_quads(4, 4)
    mp_, mq = grid_quads(3, 3, z=0.3)
    with pytest.raises(mortar.NoOverlapError):
        mortar.couple((sp_, sq, "quad"), (mp_, mq, "quad"), search_radius=0.2)
    c = mortar.couple((sp_, sq, "quad"), (mp_, mq, "quad"), search_radius=0.5)
    assert c.stats["area"] == pytest.approx(1.0, rel=1e-13)
    assert c.stats["uncovered_area"] == 0.0
    assert c.warnings == []
    for bad, match in [(-1.0, "search radius"), (float("nan"), "search radius"), ("far", "search_radius")]:
        with pytest.raises(mortar.InvalidInputError, match=match):
            mortar.couple((sp_, sq, "quad"), (mp_, mq, "quad"), search_radius=bad)
