//! Helpers shared by the integration tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use mortar::io::{msh41_bytes, MshFormat};
use mortar::SurfaceMesh;

/// A fresh directory under the system temp dir, removed when dropped.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(label: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("mortar-it-{label}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        Self(dir)
    }

    pub fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Writes `bytes` to `name` in the directory and returns its path as a string.
    pub fn file(&self, name: &str, bytes: impl AsRef<[u8]>) -> String {
        let p = self.join(name);
        std::fs::write(&p, bytes).expect("write test file");
        p.to_string_lossy().into_owned()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs the `mortar` binary.
pub fn mortar(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mortar"))
        .args(args)
        .output()
        .expect("run the mortar binary")
}

/// A copy of `mesh` with node tags moved by `node_offset` and face tags by `face_offset`.
pub fn offset_tags(mesh: &SurfaceMesh, node_offset: u64, face_offset: u64) -> SurfaceMesh {
    let mut out = SurfaceMesh::new();
    append_offset(&mut out, mesh, node_offset, face_offset);
    out
}

/// Adds the nodes and faces of `mesh` to `out`, node tags moved by `node_offset` and face
/// tags by `face_offset`.
pub fn append_offset(
    out: &mut SurfaceMesh,
    mesh: &SurfaceMesh,
    node_offset: u64,
    face_offset: u64,
) {
    for (tag, x) in mesh.node_tags().iter().zip(mesh.coords()) {
        out.add_node(tag + node_offset, [x.x, x.y, x.z]).unwrap();
    }
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let nodes: Vec<u64> = face
            .nodes
            .iter()
            .map(|&n| mesh.node_tags()[n as usize] + node_offset)
            .collect();
        out.add_face_with_tag(face.tag + face_offset, face.element, &nodes)
            .unwrap();
    }
}

/// The Gmsh 4.1 ASCII text of one surface in physical group `name`.
pub fn ascii_text(mesh: &SurfaceMesh, name: &str) -> String {
    String::from_utf8(msh41_bytes(&[(mesh, name)], MshFormat::Ascii).unwrap()).unwrap()
}

/// The 1-based number of the first line of `text` equal to `line`.
pub fn line_number(text: &str, line: &str) -> usize {
    1 + text
        .lines()
        .position(|l| l == line)
        .unwrap_or_else(|| panic!("no line {line:?} in\n{text}"))
}

/// Replaces the first line of `text` equal to `old` by `new`.
pub fn replace_line(text: &str, old: &str, new: &str) -> String {
    let n = line_number(text, old);
    text.lines()
        .enumerate()
        .map(|(i, l)| if i + 1 == n { new } else { l })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

/// A hand-written file in the style Gmsh writes: a unit cube's bottom face (two triangles,
/// physical surface "face", tag 20), one bottom edge (physical curve "edge", tag 10), a point
/// element, a hexahedron (physical volume "vol", tag 30), a parametric node block and a
/// `$Comments` section. `surface_type` 2 gives Tri3 faces, 21 one cubic 10-node triangle (a type not shipped).
pub fn gmsh_style_file(with_volume: bool, surface_type: u32) -> String {
    let (volumes, vol_names) = if with_volume { (1, 3) } else { (0, 2) };
    let mut s = String::new();
    s.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    s.push_str(&format!(
        "$PhysicalNames\n{vol_names}\n1 10 \"edge\"\n2 20 \"face\"\n"
    ));
    if with_volume {
        s.push_str("3 30 \"vol\"\n");
    }
    s.push_str("$EndPhysicalNames\n");
    s.push_str("$Comments\nwritten by hand, in the style of Gmsh 4.13\n$EndComments\n");
    s.push_str(&format!("$Entities\n1 1 1 {volumes}\n"));
    s.push_str("1 0 0 0 0\n");
    s.push_str("1 0 0 0 1 0 0 1 10 2 1 -2\n");
    s.push_str("1 0 0 0 1 1 0 1 20 1 1\n");
    if with_volume {
        s.push_str("1 0 0 0 1 1 1 1 30 1 1\n");
    }
    s.push_str("$EndEntities\n");
    let nodes = if with_volume { 8 } else { 4 };
    let blocks = if with_volume { 4 } else { 3 };
    s.push_str(&format!("$Nodes\n{blocks} {nodes} 1 {nodes}\n"));
    s.push_str("0 1 0 1\n1\n0 0 0\n");
    s.push_str("1 1 1 1\n2\n1 0 0\n1\n");
    s.push_str("2 1 0 2\n3\n4\n1 1 0\n0 1 0\n");
    if with_volume {
        s.push_str("3 1 0 4\n5\n6\n7\n8\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n");
    }
    s.push_str("$EndNodes\n");
    let elements = if with_volume { 5 } else { 4 };
    let surface_elements = if surface_type == 21 { 1 } else { 2 };
    let elements = elements - 2 + surface_elements;
    s.push_str(&format!("$Elements\n{blocks} {elements} 1 5\n"));
    s.push_str("0 1 15 1\n1 1\n");
    s.push_str("1 1 1 1\n2 1 2\n");
    if surface_type == 21 {
        s.push_str("2 1 21 1\n3 1 2 3 4 5 6 7 8 1 2\n");
    } else {
        s.push_str("2 1 2 2\n3 1 2 3\n4 1 3 4\n");
    }
    if with_volume {
        s.push_str("3 1 5 1\n5 1 2 3 4 5 6 7 8\n");
    }
    s.push_str("$EndElements\n");
    s
}

/// The matrix of a Matrix Market file, as dense rows.
pub fn read_mtx(path: &Path) -> Vec<Vec<f64>> {
    let tri: sprs::TriMat<f64> =
        sprs::io::read_matrix_market(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut dense = vec![vec![0.0; tri.cols()]; tri.rows()];
    for (v, (r, c)) in tri.triplet_iter() {
        dense[r][c] += *v;
    }
    dense
}

/// Row sums of a dense matrix.
pub fn row_sums(m: &[Vec<f64>]) -> Vec<f64> {
    m.iter().map(|r| r.iter().sum()).collect()
}
