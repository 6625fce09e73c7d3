//! A spatial order of faces: the Morton (Z-order) code of their centres.
//!
//! Mesh files number faces in whatever order their generator left them; Gmsh's
//! Frontal-Delaunay triangles, for one, come in an order where consecutive faces lie far
//! apart. Trees whose leaves group consecutive faces, and work cut into chunks of consecutive
//! faces, degrade badly on such an order. Sorting by the Morton code of the face centres makes
//! neighbours in the order neighbours in space, whatever the file's numbering.

use nalgebra::Vector3;
use rayon::prelude::*;

/// Spreads the low 21 bits of `v` to every third bit.
fn spread3(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | (x << 32)) & 0x1f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x1f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}

/// Spreads the low 32 bits of `v` to every second bit.
fn spread2(v: u64) -> u64 {
    let mut x = v & 0xffff_ffff;
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    x = (x | (x << 1)) & 0x5555_5555_5555_5555;
    x
}

/// The Morton code of `p` in the box `(lo, hi)`: 21 bits per axis in 3D, 32 in the plane
/// (`planar` ignores z).
pub(crate) fn morton_code(
    p: &Vector3<f64>,
    lo: &Vector3<f64>,
    hi: &Vector3<f64>,
    planar: bool,
) -> u64 {
    let bits = if planar { 32 } else { 21 };
    let cells = ((1u64 << bits) - 1) as f64;
    let q = |k: usize| -> u64 {
        let w = hi[k] - lo[k];
        if w > 0.0 && w.is_finite() {
            (((p[k] - lo[k]) / w).clamp(0.0, 1.0) * cells) as u64
        } else {
            0
        }
    };
    if planar {
        spread2(q(0)) | (spread2(q(1)) << 1)
    } else {
        spread3(q(0)) | (spread3(q(1)) << 1) | (spread3(q(2)) << 2)
    }
}

/// The bounding box `(lo, hi)` of the points `point(i)`, `i < n`, each computed once, in
/// parallel, without storing them (the least and greatest coordinates: the same box whatever
/// the thread count).
pub(crate) fn bounds_of(
    n: usize,
    point: impl Fn(usize) -> Vector3<f64> + Sync,
) -> (Vector3<f64>, Vector3<f64>) {
    let empty = || {
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        )
    };
    (0..n)
        .into_par_iter()
        .fold(empty, |(lo, hi), i| {
            let p = point(i);
            (lo.inf(&p), hi.sup(&p))
        })
        .reduce(empty, |(a, b), (c, d)| (a.inf(&c), b.sup(&d)))
}

/// The indices `0..n` sorted by the Morton code of the points `centre(i)` (ties by index, so
/// the order depends on the coordinates only, not on the thread count), as the low 32 bits of
/// keys `code << 32 | index`, in the box `frame` (`None`: the points' own box). Each point is
/// computed twice (for the bounds, then for its code) rather than stored: reading a face's
/// first node again costs less than the pages of a vector of every point.
pub(crate) fn spatial_keys(
    n: usize,
    centre: impl Fn(usize) -> Vector3<f64> + Sync,
    planar: bool,
    frame: Option<&(Vector3<f64>, Vector3<f64>)>,
) -> Vec<u128> {
    let (lo, hi) = match frame {
        Some(&b) => b,
        None => bounds_of(n, &centre),
    };
    // (code, index) packed into one integer: one comparison per pair in the sort.
    let mut keyed: Vec<u128> = (0..n)
        .into_par_iter()
        .map(|i| (morton_code(&centre(i), &lo, &hi, planar) as u128) << 32 | i as u128)
        .collect();
    keyed.par_sort_unstable();
    keyed
}

/// The indices `0..n` by the Morton code of `centre(i)` in the points' own box
/// ([`spatial_keys`]).
#[cfg(test)]
pub(crate) fn spatial_order(
    n: usize,
    centre: impl Fn(usize) -> Vector3<f64> + Sync,
    planar: bool,
) -> Vec<u32> {
    let keys = spatial_keys(n, centre, planar, None);
    keys.into_iter().map(|key| key as u32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_interleave_the_axes() {
        let lo = Vector3::zeros();
        let hi = Vector3::repeat(((1u64 << 21) - 1) as f64);
        assert_eq!(
            morton_code(&Vector3::new(1.0, 0.0, 0.0), &lo, &hi, false),
            0b001
        );
        assert_eq!(
            morton_code(&Vector3::new(0.0, 1.0, 0.0), &lo, &hi, false),
            0b010
        );
        assert_eq!(
            morton_code(&Vector3::new(0.0, 0.0, 1.0), &lo, &hi, false),
            0b100
        );
        assert_eq!(
            morton_code(&Vector3::new(3.0, 0.0, 0.0), &lo, &hi, false),
            0b1001
        );
        assert_eq!(morton_code(&hi, &lo, &hi, false), (1u64 << 63) - 1);
        let hi2 = Vector3::new(u32::MAX as f64, u32::MAX as f64, 0.0);
        assert_eq!(
            morton_code(&Vector3::new(0.0, 1.0, 5.0), &lo, &hi2, true),
            0b10
        );
        assert_eq!(morton_code(&hi2, &lo, &hi2, true), u64::MAX);
    }

    #[test]
    fn order_groups_neighbours() {
        // Points of a 4 x 4 grid given in a scrambled order come out quadrant by quadrant.
        let mut pts = Vec::new();
        for k in [5usize, 12, 0, 15, 9, 3, 6, 10, 1, 14, 7, 11, 2, 13, 4, 8] {
            pts.push(Vector3::new((k % 4) as f64, (k / 4) as f64, 0.0));
        }
        let order = spatial_order(pts.len(), |i| pts[i], true);
        let quadrant = |i: u32| {
            let p = pts[i as usize];
            (p.x >= 2.0) as u8 + 2 * (p.y >= 2.0) as u8
        };
        let q: Vec<u8> = order.iter().map(|&i| quadrant(i)).collect();
        assert_eq!(q, [0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3]);
    }
}
