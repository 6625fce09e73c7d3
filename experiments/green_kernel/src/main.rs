//! Experiment (issue 13, item 1; stop 43): would a branch-free, 4-wide kernel make the
//! moments of triangle-triangle overlaps much cheaper than the clipping the toolkit does?
//!
//! Both kernels compute, for each candidate pair (a slave and a master triangle of a planar
//! interface), the moments of order 0, 1 and 2 of their overlap about the slave's first
//! vertex, the quantities `closed_form_into` turns into the D and M blocks:
//!
//! - `sh_moments`: Sutherland-Hodgman clipping of the master by the slave's edges (I. E.
//!   Sutherland, G. W. Hodgman, "Reentrant polygon clipping", CACM 17(1), 1974) with the
//!   toolkit's tolerance rule, then the boundary sums of the clip polygon (C. Steger, "On
//!   the calculation of arbitrary moments of polygons", TU Munich FGBV-96-05, 1996): the
//!   shape of `ConvexClipper::clip_buffered` and `Moments::of`, without the projection,
//!   the merging of near vertices and the blocks.
//! - `green4`: the same moments from the overlap's boundary without building the polygon
//!   (Green's theorem: the boundary of the overlap is the part of each triangle's edges
//!   inside the other). Each edge's part is an interval of its parameter, the intersection
//!   of three half-plane conditions (min/max, no branch), and contributes Steger's segment
//!   terms; four master triangles of one slave triangle at a time (`wide::f64x4`).
//!   Coincident edges are counted once: the slave's edges count where they lie in the
//!   master within the tolerance, the master's only where strictly inside the slave, and a
//!   slave edge lying on a master edge of the opposite direction (two faces that only
//!   touch) counts nothing.
//!
//! The meshes: the unit square cut into `2 n^2` slave triangles and `2 (1.5 n)^2` master
//! triangles, either aligned (every third slave grid line on a master one: coincident
//! edges, as in the benchmark's plane3d) or the master turned by 0.013 rad and moved.
//! Candidates by bounding boxes. Prints the time per candidate of each (median of 4 passes
//! after a first) and the largest difference between their moments, relative to the
//! moments' scale (`h^2`, `h^3`, `h^4`).
//!
//! `RUSTFLAGS="-C target-cpu=native" cargo run --release -- 300 aligned` (or `rotated`).
use std::time::Instant;
use wide::f64x4;

type V = [f64; 2];

#[derive(Clone, Copy, Default, Debug)]
struct Mom {
    a: f64,
    f: [f64; 2],
    s: [f64; 3],
}

fn cross(a: V, b: V) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1]]
}

/// Sutherland-Hodgman of subject `m` (CCW) by clip `s` (CCW), tol, then fan moments about s[0].
fn sh_moments(s: &[V; 3], m: &[V; 3], tol: f64) -> Mom {
    let mut buf = [[[0.0; 2]; 16]; 2];
    buf[0][..3].copy_from_slice(m);
    let mut len = 3;
    let mut cur = 0;
    for i in 0..3 {
        let a = s[i];
        let e = sub(s[(i + 1) % 3], a);
        let inv = 1.0 / (e[0] * e[0] + e[1] * e[1]).sqrt();
        let (x, y) = buf.split_at_mut(1);
        let (src, dst) = if cur == 0 {
            (&x[0], &mut y[0])
        } else {
            (&y[0], &mut x[0])
        };
        let mut d = [0.0; 16];
        let mut inside = 0;
        for k in 0..len {
            d[k] = cross(e, sub(src[k], a)) * inv;
            inside += (d[k] >= -tol) as usize;
        }
        if inside == len {
            continue;
        }
        if inside == 0 {
            len = 0;
            break;
        }
        let mut n = 0;
        let (mut p, mut dp) = (src[len - 1], d[len - 1]);
        for k in 0..len {
            let (q, dq) = (src[k], d[k]);
            let (pi, qi) = (dp >= -tol, dq >= -tol);
            if pi != qi {
                let t = (dp / (dp - dq)).clamp(0.0, 1.0);
                dst[n] = [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t];
                n += 1;
            }
            if qi {
                dst[n] = q;
                n += 1;
            }
            p = q;
            dp = dq;
        }
        len = n;
        cur = 1 - cur;
    }
    let v = &buf[cur][..len];
    let mut out = Mom::default();
    if len < 3 {
        return out;
    }
    let o = s[0];
    for i in 0..len {
        let a = sub(v[i], o);
        let b = sub(v[(i + 1) % len], o);
        let t = 0.5 * cross(a, b);
        out.a += t;
        out.f[0] += (a[0] + b[0]) * (t / 3.0);
        out.f[1] += (a[1] + b[1]) * (t / 3.0);
        let t6 = t / 6.0;
        out.s[0] += t6 * (a[0] * a[0] + b[0] * b[0] + a[0] * b[0]);
        out.s[1] += t6 * (a[0] * a[1] + b[0] * b[1] + 0.5 * (a[0] * b[1] + b[0] * a[1]));
        out.s[2] += t6 * (a[1] * a[1] + b[1] * b[1] + a[1] * b[1]);
    }
    out
}

/// 4 pairs at once: slave `s` (the same for the 4 lanes, relative to its vertex 0), masters
/// `m[j]` = (x, y) lanes of vertex j, both CCW. Moments of the overlap about s[0].
#[inline(always)]
fn green4(s: &[V; 3], stol: &[f64; 3], m: &[[f64x4; 2]; 3], tol: f64) -> [f64x4; 6] {
    let zero = f64x4::splat(0.0);
    let one = f64x4::splat(1.0);
    let sx: [f64x4; 3] = std::array::from_fn(|i| f64x4::splat(s[i][0]));
    let sy: [f64x4; 3] = std::array::from_fn(|i| f64x4::splat(s[i][1]));
    // slave edges
    let sex: [f64x4; 3] = std::array::from_fn(|i| sx[(i + 1) % 3] - sx[i]);
    let sey: [f64x4; 3] = std::array::from_fn(|i| sy[(i + 1) % 3] - sy[i]);
    let mx: [f64x4; 3] = std::array::from_fn(|j| m[j][0]);
    let my: [f64x4; 3] = std::array::from_fn(|j| m[j][1]);
    let mex: [f64x4; 3] = std::array::from_fn(|k| mx[(k + 1) % 3] - mx[k]);
    let mey: [f64x4; 3] = std::array::from_fn(|k| my[(k + 1) % 3] - my[k]);
    let mtol: [f64x4; 3] =
        std::array::from_fn(|k| (mex[k] * mex[k] + mey[k] * mey[k]).sqrt() * f64x4::splat(tol));
    let stol: [f64x4; 3] = std::array::from_fn(|i| f64x4::splat(stol[i]));
    // dm[k][i]: slave vertex i against master edge k; ds[i][j]: master vertex j vs slave edge i.
    let dm: [[f64x4; 3]; 3] = std::array::from_fn(|k| {
        std::array::from_fn(|i| mex[k] * (sy[i] - my[k]) - mey[k] * (sx[i] - mx[k]))
    });
    let ds: [[f64x4; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| sex[i] * (my[j] - sy[i]) - sey[i] * (mx[j] - sx[i]))
    });
    let mut acc = [zero; 6];
    let mut seg = |px: f64x4, py: f64x4, qx: f64x4, qy: f64x4, t0: f64x4, t1: f64x4, ok: f64x4| {
        let ex = qx - px;
        let ey = qy - py;
        let x0 = px + ex * t0;
        let y0 = py + ey * t0;
        let x1 = px + ex * t1;
        let y1 = py + ey * t1;
        let keep = ok & t0.simd_lt(t1);
        let c = keep.select(x0 * y1 - y0 * x1, zero);
        acc[0] += c;
        acc[1] += (x0 + x1) * c;
        acc[2] += (y0 + y1) * c;
        acc[3] += c * (x0 * x0 + x1 * x1 + x0 * x1);
        acc[4] += c * (x0 * y0 + x1 * y1 + f64x4::splat(0.5) * (x0 * y1 + x1 * y0));
        acc[5] += c * (y0 * y0 + y1 * y1 + y0 * y1);
    };
    // slave edges inside the master (closed)
    for i in 0..3 {
        let i1 = (i + 1) % 3;
        let mut t0 = zero;
        let mut t1 = one;
        let mut ok = zero.simd_eq(zero);
        for k in 0..3 {
            let (dp, dq) = (dm[k][i], dm[k][i1]);
            let lim = -mtol[k];
            let pin = dp.simd_ge(lim);
            let qin = dq.simd_ge(lim);
            let t = (dp / (dp - dq)).max(zero).min(one);
            t0 = (!pin & qin).select(t0.max(t), t0);
            t1 = (pin & !qin).select(t1.min(t), t1);
            ok &= pin | qin;
            // coincident, opposite: dropped
            let on = dp.abs().simd_le(mtol[k]) & dq.abs().simd_le(mtol[k]);
            let opp = (sex[i] * mex[k] + sey[i] * mey[k]).simd_lt(zero);
            ok &= !(on & opp);
        }
        seg(sx[i], sy[i], sx[i1], sy[i1], t0, t1, ok);
    }
    // master edges strictly inside the slave
    for k in 0..3 {
        let k1 = (k + 1) % 3;
        let mut t0 = zero;
        let mut t1 = one;
        let mut ok = zero.simd_eq(zero);
        for i in 0..3 {
            let (dp, dq) = (ds[i][k], ds[i][k1]);
            let pin = dp.simd_gt(stol[i]);
            let qin = dq.simd_gt(stol[i]);
            let t = ((dp - stol[i]) / (dp - dq)).max(zero).min(one);
            t0 = (!pin & qin).select(t0.max(t), t0);
            t1 = (pin & !qin).select(t1.min(t), t1);
            ok &= pin | qin;
        }
        seg(mx[k], my[k], mx[k1], my[k1], t0, t1, ok);
    }
    acc
}

struct Mesh {
    v: Vec<V>,
    t: Vec<[u32; 3]>,
}

fn grid(n: usize, rot: f64, shift: V) -> Mesh {
    let mut v = Vec::new();
    let h = 1.0 / n as f64;
    let (c, s) = (rot.cos(), rot.sin());
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * h - 0.5, j as f64 * h - 0.5);
            v.push([
                c * x - s * y + 0.5 + shift[0],
                s * x + c * y + 0.5 + shift[1],
            ]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh { v, t }
}

fn tri(m: &Mesh, f: usize) -> [V; 3] {
    let t = m.t[f];
    [m.v[t[0] as usize], m.v[t[1] as usize], m.v[t[2] as usize]]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ns: usize = args.get(1).map(|a| a.parse().unwrap()).unwrap_or(200);
    let aligned = args.get(2).map(|a| a == "aligned").unwrap_or(true);
    let slave = grid(ns, 0.0, [0.0, 0.0]);
    let nm = ns * 3 / 2;
    let master = if aligned {
        grid(nm, 0.0, [0.0, 0.0])
    } else {
        grid(nm, 0.013, [1e-4, 3e-5])
    };
    // candidates by boxes (bucket grid on master)
    let hb = 1.0 / nm as f64;
    let nb = nm + 4;
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); nb * nb];
    let bidx = |x: f64| (((x + 0.02) / hb) as isize).clamp(0, nb as isize - 1) as usize;
    for f in 0..master.t.len() {
        let t = tri(&master, f);
        let c = [
            (t[0][0] + t[1][0] + t[2][0]) / 3.0,
            (t[0][1] + t[1][1] + t[2][1]) / 3.0,
        ];
        buckets[bidx(c[1]) * nb + bidx(c[0])].push(f as u32);
    }
    let bbox = |t: &[V; 3]| {
        let lo = [
            t[0][0].min(t[1][0]).min(t[2][0]),
            t[0][1].min(t[1][1]).min(t[2][1]),
        ];
        let hi = [
            t[0][0].max(t[1][0]).max(t[2][0]),
            t[0][1].max(t[1][1]).max(t[2][1]),
        ];
        (lo, hi)
    };
    let tol = 1e-12 / ns as f64;
    let mut cands: Vec<(u32, Vec<u32>)> = Vec::new();
    let mut ncand = 0;
    for f in 0..slave.t.len() {
        let t = tri(&slave, f);
        let (lo, hi) = bbox(&t);
        let mut c = Vec::new();
        for by in bidx(lo[1] - 2.0 * hb)..=bidx(hi[1] + 2.0 * hb) {
            for bx in bidx(lo[0] - 2.0 * hb)..=bidx(hi[0] + 2.0 * hb) {
                for &m in &buckets[by * nb + bx] {
                    let (ml, mh) = bbox(&tri(&master, m as usize));
                    if ml[0] <= hi[0] + tol
                        && ml[1] <= hi[1] + tol
                        && mh[0] >= lo[0] - tol
                        && mh[1] >= lo[1] - tol
                    {
                        c.push(m);
                    }
                }
            }
        }
        ncand += c.len();
        cands.push((f as u32, c));
    }
    // Reference: S-H
    let rel = |t: &[V; 3], p: V| sub(p, t[0]);
    let mut sh_out = Vec::with_capacity(ncand);
    let mut pairs = 0;
    let reps = 5;
    let mut sh_times = Vec::new();
    for r in 0..reps {
        sh_out.clear();
        pairs = 0;
        let t0 = Instant::now();
        for (f, c) in &cands {
            let s = tri(&slave, *f as usize);
            let s0 = [[0.0, 0.0], rel(&s, s[1]), rel(&s, s[2])];
            for &m in c {
                let mt = tri(&master, m as usize);
                let mm = [rel(&s, mt[0]), rel(&s, mt[1]), rel(&s, mt[2])];
                let mo = sh_moments(&s0, &mm, tol);
                pairs += (mo.a > 0.0) as usize;
                sh_out.push(mo);
            }
        }
        let dt = t0.elapsed().as_secs_f64();
        if r > 0 {
            sh_times.push(dt);
        }
        std::hint::black_box(&sh_out);
    }
    // Green, 4 wide
    let mut g_out: Vec<[f64; 6]> = Vec::with_capacity(ncand + 4);
    let mut g_times = Vec::new();
    for r in 0..reps {
        g_out.clear();
        let t0 = Instant::now();
        for (f, c) in &cands {
            let s = tri(&slave, *f as usize);
            let s0 = [[0.0, 0.0], rel(&s, s[1]), rel(&s, s[2])];
            let stol: [f64; 3] = std::array::from_fn(|i| {
                let e = sub(s0[(i + 1) % 3], s0[i]);
                tol * (e[0] * e[0] + e[1] * e[1]).sqrt()
            });
            for chunk in c.chunks(4) {
                let mut xs = [[[0.0f64; 4]; 2]; 3];
                for l in 0..4 {
                    let mt = if l < chunk.len() {
                        let t = tri(&master, chunk[l] as usize);
                        [rel(&s, t[0]), rel(&s, t[1]), rel(&s, t[2])]
                    } else {
                        [[1e3, 1e3], [1e3 + 1.0, 1e3], [1e3, 1e3 + 1.0]]
                    };
                    for j in 0..3 {
                        xs[j][0][l] = mt[j][0];
                        xs[j][1][l] = mt[j][1];
                    }
                }
                let m: [[f64x4; 2]; 3] =
                    std::array::from_fn(|j| [f64x4::from(xs[j][0]), f64x4::from(xs[j][1])]);
                let acc = green4(&s0, &stol, &m, tol);
                let a: [[f64; 4]; 6] = std::array::from_fn(|q| acc[q].to_array());
                g_out.extend((0..chunk.len()).map(|l| {
                    [
                        0.5 * a[0][l],
                        a[1][l] / 6.0,
                        a[2][l] / 6.0,
                        a[3][l] / 12.0,
                        a[4][l] / 12.0,
                        a[5][l] / 12.0,
                    ]
                }));
            }
        }
        let dt = t0.elapsed().as_secs_f64();
        if r > 0 {
            g_times.push(dt);
        }
        std::hint::black_box(&g_out);
    }
    // compare
    let h2 = 1.0 / (ns * ns) as f64;
    let mut worst = 0.0f64;
    let mut worst_at = 0;
    for (k, (a, b)) in sh_out.iter().zip(&g_out).enumerate() {
        let sa = [a.a, a.f[0], a.f[1], a.s[0], a.s[1], a.s[2]];
        let scale = [
            h2,
            h2 / ns as f64,
            h2 / ns as f64,
            h2 * h2,
            h2 * h2,
            h2 * h2,
        ];
        for q in 0..6 {
            let e = (sa[q] - b[q]).abs() / scale[q];
            if e > worst {
                worst = e;
                worst_at = k;
            }
        }
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v[v.len() / 2]
    };
    let (ts, tg) = (med(&mut sh_times), med(&mut g_times));
    println!(
        "ns={ns} aligned={aligned} candidates={ncand} pairs={pairs} | S-H {:.1} ns/cand ({:.2}M pairs/s) | green4 {:.1} ns/cand ({:.2}M pairs/s) | ratio {:.2} | worst rel diff {:.2e} at {}",
        ts / ncand as f64 * 1e9,
        pairs as f64 / ts / 1e6,
        tg / ncand as f64 * 1e9,
        pairs as f64 / tg / 1e6,
        ts / tg,
        worst,
        worst_at
    );
    if worst > 1e-9 {
        println!("sh {:?}\ngreen {:?}", sh_out[worst_at], g_out[worst_at]);
        let mut k = 0;
        'outer: for (f, c) in &cands {
            for &m in c {
                if k == worst_at {
                    let s = tri(&slave, *f as usize);
                    let mt = tri(&master, m as usize);
                    println!(
                        "slave {:?}\nmaster {:?}",
                        s.map(|p| rel(&s, p)),
                        mt.map(|p| rel(&s, p))
                    );
                    break 'outer;
                }
                k += 1;
            }
        }
    }
}
