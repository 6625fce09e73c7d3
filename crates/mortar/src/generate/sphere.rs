//! The sphere as Tri3 faces, from a subdivided icosahedron projected onto it.

use std::collections::HashMap;

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use mortar_elements::TRI3;
use nalgebra::Vector3;

/// The sphere of radius `radius` about the origin as Tri3 faces: the icosahedron with each
/// face cut into `subdivisions^2` triangles, every node projected onto the sphere
/// (`20 subdivisions^2` faces, `10 subdivisions^2 + 2` nodes). Normals point outward, or
/// inward if `flip`. A closed curved surface: every slave point projected along the nodal
/// normals finds another sphere's faces.
///
/// # Errors
/// None for `subdivisions >= 1` and a positive finite radius.
pub fn sphere_surface(
    radius: f64,
    subdivisions: usize,
    flip: bool,
    first_node_tag: u64,
) -> Result<SurfaceMesh> {
    let n = subdivisions.max(1);
    let phi = 0.5 * (1.0 + 5f64.sqrt());
    let corners: [Vector3<f64>; 12] = [
        Vector3::new(-1.0, phi, 0.0),
        Vector3::new(1.0, phi, 0.0),
        Vector3::new(-1.0, -phi, 0.0),
        Vector3::new(1.0, -phi, 0.0),
        Vector3::new(0.0, -1.0, phi),
        Vector3::new(0.0, 1.0, phi),
        Vector3::new(0.0, -1.0, -phi),
        Vector3::new(0.0, 1.0, -phi),
        Vector3::new(phi, 0.0, -1.0),
        Vector3::new(phi, 0.0, 1.0),
        Vector3::new(-phi, 0.0, -1.0),
        Vector3::new(-phi, 0.0, 1.0),
    ];
    // Counter-clockwise seen from outside.
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut mesh = SurfaceMesh::with_capacity(10 * n * n + 2, 20 * n * n);
    // A node is identified by its lattice position: a corner, a point of an edge (by its two
    // corners, ordered, and the step from the lower one), or a face-interior point.
    let mut ids: HashMap<(usize, usize, usize, usize), u64> = HashMap::new();
    let mut next = first_node_tag;
    let mut node = |mesh: &mut SurfaceMesh, f: usize, i: usize, j: usize| -> Result<u64> {
        let [a, b, c] = FACES[f];
        // Barycentric lattice point (n - i - j, i, j) of corners (a, b, c).
        let w = [n - i - j, i, j];
        let key = match w.iter().filter(|&&k| k > 0).count() {
            1 => {
                let k = w.iter().position(|&k| k > 0).expect("one weight");
                (FACES[f][k], usize::MAX, 0, 0)
            }
            2 => {
                let pos: Vec<usize> = (0..3).filter(|&k| w[k] > 0).collect();
                let (p, q) = (FACES[f][pos[0]], FACES[f][pos[1]]);
                let (lo, step) = if p < q {
                    (p, w[pos[1]])
                } else {
                    (q, w[pos[0]])
                };
                (lo, p.max(q), step, usize::MAX)
            }
            _ => (usize::MAX, f, i, j),
        };
        if let Some(&t) = ids.get(&key) {
            return Ok(t);
        }
        let x = (corners[a] * w[0] as f64 + corners[b] * w[1] as f64 + corners[c] * w[2] as f64)
            / n as f64;
        let x = x.normalize() * radius;
        let tag = next;
        next += 1;
        mesh.add_node(tag, [x.x, x.y, x.z])?;
        ids.insert(key, tag);
        Ok(tag)
    };
    for f in 0..20 {
        for i in 0..n {
            for j in 0..n - i {
                let p = node(&mut mesh, f, i, j)?;
                let q = node(&mut mesh, f, i + 1, j)?;
                let r = node(&mut mesh, f, i, j + 1)?;
                let mut tris = vec![[p, q, r]];
                if i + j + 1 < n {
                    let s = node(&mut mesh, f, i + 1, j + 1)?;
                    tris.push([q, s, r]);
                }
                for t in tris {
                    let t = if flip { [t[0], t[2], t[1]] } else { t };
                    mesh.add_face(&TRI3, &t)?;
                }
            }
        }
    }
    Ok(mesh)
}
