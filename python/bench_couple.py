"""Benchmark of mortar.couple from Python against the library's own time for the same call.

    python bench_couple.py [--n 708] [--repeats 3] [--threads N] [--json PATH]

The case is `bench_coupling`'s plane3d (examples/bench_coupling.rs): the unit square at
z = 0, slave n x n cells cut into triangles along the (0,0)-(1,1) diagonal (2 n^2 faces:
n = 708 gives 1,002,528), master floor(1.5 n) + 1 cells per side cut along the other
diagonal, facing the slave. The meshes are made with numpy (not timed), then coupled with
segment-based integration and standard multipliers, orient=False (the meshes face each
other already, as the Rust benchmark's do; --orient times the facing step too).

Times, medians over the repeats:
- python: the whole `mortar.couple` call (checks and conversions of the arrays, the
  library's work with the GIL released, the scipy matrices);
- library: the library's wall time inside that call (`stats["seconds"]`): building its
  meshes from the arrays, validating the interface, assembling D and M: what a Rust
  program starting from the same arrays pays;
- assembly: `assemble_coupling` alone (`stats["seconds_by_phase"]["coupling"]`), the time
  `cargo run --release --example bench_coupling` reports (mesh set-up excluded).

The overhead ratio is python / library. For scale: a vectorised numpy + shapely
implementation does about 65 thousand pairs per second on this machine (docs/performance.md).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys

import numpy as np

import mortar


def square_triangles(n: int, anti: bool, flip: bool):
    """The unit square at z = 0 as n x n cells cut into two triangles each: along the
    (0,0)-(1,1) diagonal, or the other one with `anti`; normals +z, or -z with `flip`."""
    t = np.linspace(0.0, 1.0, n + 1)
    x, y = np.meshgrid(t, t)
    points = np.c_[x.ravel(), y.ravel(), np.zeros(x.size)]
    i, j = np.meshgrid(np.arange(n), np.arange(n))
    a = (i + (n + 1) * j).ravel()
    b, c, d = a + 1, a + n + 2, a + n + 1  # the cell's corners, counter-clockwise
    if anti:
        tris = np.vstack([np.c_[a, b, d], np.c_[b, c, d]])
    else:
        tris = np.vstack([np.c_[a, b, c], np.c_[a, c, d]])
    # Cell by cell, as the Rust generator orders them (spatially coherent).
    tris = tris.reshape(2, -1, 3).transpose(1, 0, 2).reshape(-1, 3)
    if flip:
        tris = tris[:, ::-1]
    return np.ascontiguousarray(points), np.ascontiguousarray(tris, dtype=np.int64)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=708, help="slave cells per side (2 n^2 faces)")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--json", default=None, help="also write the record to this file")
    p.add_argument(
        "--orient", action="store_true", help="orient=True (time the facing step as well)"
    )
    a = p.parse_args(argv)

    slave = (*square_triangles(a.n, anti=False, flip=False), "triangle")
    master = (*square_triangles(a.n * 3 // 2 + 1, anti=True, flip=True), "triangle")
    runs = []
    for _ in range(a.repeats):
        c = mortar.couple(slave, master, threads=a.threads, orient=a.orient)
        s = c.stats
        runs.append(
            {
                "python": s["seconds_call"],
                "library": s["seconds"],
                "assembly": s["seconds_by_phase"]["coupling"],
                "meshes": s["seconds_by_phase"]["meshes"],
                "interface": s["seconds_by_phase"]["interface"],
                "orientation": s["seconds_by_phase"]["orientation"],
            }
        )
        pairs, area, threads = s["pairs"], s["area"], s["threads"]
        del c
    med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    record = {
        "case": "plane3d",
        "n": a.n,
        "slave_faces": int(slave[1].shape[0]),
        "master_faces": int(master[1].shape[0]),
        "pairs": pairs,
        "area": area,
        "threads": threads,
        "orient": a.orient,
        "repeats": a.repeats,
        "median_seconds": med,
        "runs": runs,
        "overhead_python_over_library": med["python"] / med["library"],
        "python_over_assembly": med["python"] / med["assembly"],
        "pairs_per_second_python": pairs / med["python"],
    }
    print(json.dumps(record))
    print(
        f"plane3d n={a.n}: {record['slave_faces']:,} slave faces, {pairs:,} pairs, "
        f"{threads} threads: mortar.couple {med['python']:.2f} s, the library's work "
        f"{med['library']:.2f} s (meshes {med['meshes']:.2f}, interface "
        f"{med['interface']:.2f}, assembly {med['assembly']:.2f}): python / library "
        f"{record['overhead_python_over_library']:.3f}, python / assembly "
        f"{record['python_over_assembly']:.3f}; {pairs / med['python'] / 1e6:.2f}M pairs/s "
        f"(numpy + shapely: ~0.065M)",
        file=sys.stderr,
    )
    if a.json:
        with open(a.json, "w", encoding="utf-8") as f:
            json.dump(record, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
