//! Every key of every scene kind (`tied_heat`, `contact`, `pellet`) has an effect that a test
//! sees.
//!
//! For each kind, the keys the kind accepts are enumerated mechanically: a spec with every
//! optional key set is serialised and flattened to dotted key paths (`bodies.*.conductivity`,
//! `bodies.*.dirichlet[].value`, `interface.search_radius`, `laws.thermal.*` for a law's
//! parameters), and each of its tables is checked against the fields serde accepts there (the
//! list of its error for an unknown field), so that a field with a default that the full spec
//! leaves out is found too. That set must equal the keys of the kind's table of rows (one row
//! per key): a key added without a row, or a row left for a removed key, fails the test.
//!
//! Each row runs a small variant of the kind's base scene with its key changed and asserts
//! that a named output (a `report.json` field, a VTU field, or an error naming the key for a
//! value the scene must refuse) changes the way the key means: against a closed form where
//! there is one (the patch tests, the exponential law's gap), otherwise in the direction the
//! physics gives or, for the integration dials, towards a converged reference. Keys that choose
//! between equivalent formulations show the choice in the report and give the same figures.

use std::collections::{BTreeMap, BTreeSet};
use std::panic::AssertUnwindSafe;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use mortar::core::mesh::VolumeMesh;
use mortar::generate::{
    box_mesh, extrude_mesh, onto_cylinder, quarter_annulus_mesh, rectangle_mesh, second_order_mesh,
    CellShape, SecondOrder,
};
use mortar::io::{msh41_volume_bytes, Integration, MshFormat, Multipliers};
use mortar_scenes::file::contact::{
    Component, ComponentValue, ContactInterfaceSpec, ContactSolveSpec, ContactSpec,
    DisplacementSpec, ElasticBodySpec, LawSpec, TractionSpec,
};
use mortar_scenes::file::tied_heat::{
    BodySpec, DirichletSpec, FormulationSpec, InterfaceSpec, Mode, NeumannSpec, SideSpec,
    SolveSpec, TiedHeatSpec,
};
use mortar_scenes::file::{FileScene, FileSystem};
use mortar_scenes::pellet::{AxialModel, PelletScene};
use mortar_scenes::NamedLaw;
use nalgebra::Vector3;
use serde_json::Value;

use crate::common::{mortar, TempDir};

// ---------------------------------------------------------------------------------------
// The keys of a kind

/// One step of a path into a TOML document.
#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

/// Where a kind's TOML keys are not a struct's fields.
struct Shape {
    /// Tables keyed by names (`bodies`): their entries are one `*`.
    named: &'static [&'static str],
    /// Tables of a law by name: `name`, and the law's parameters as one `*`.
    laws: &'static [&'static str],
    /// Other spellings of a key (serde aliases) and the key they spell, whose row covers them.
    aliases: &'static [(&'static str, &'static str)],
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// The key paths under `table` (at `steps`, generic path `path`) into `keys`, and the tables
/// whose keys are a struct's fields into `structs` (once per generic path).
fn walk(
    table: &toml::Table,
    steps: &[Step],
    path: &str,
    shape: &Shape,
    keys: &mut BTreeSet<String>,
    structs: &mut Vec<(Vec<Step>, String)>,
) {
    if shape.laws.contains(&path) {
        for k in table.keys() {
            keys.insert(join(path, if k == "name" { "name" } else { "*" }));
        }
        return;
    }
    let named = shape.named.contains(&path);
    if !named && !structs.iter().any(|(_, p)| p == path) {
        structs.push((steps.to_vec(), path.to_string()));
    }
    for (k, v) in table {
        let child = join(path, if named { "*" } else { k });
        let mut s = steps.to_vec();
        s.push(Step::Key(k.clone()));
        match v {
            toml::Value::Table(t) => walk(t, &s, &child, shape, keys, structs),
            toml::Value::Array(items)
                if !items.is_empty() && items.iter().all(toml::Value::is_table) =>
            {
                for (i, item) in items.iter().enumerate() {
                    let mut si = s.clone();
                    si.push(Step::Index(i));
                    let t = item.as_table().expect("a table");
                    walk(t, &si, &format!("{child}[]"), shape, keys, structs);
                }
            }
            _ => {
                keys.insert(child);
            }
        }
    }
}

/// The fields serde accepts at the table `steps` of `doc` read as `T`: the list of the error
/// for an unknown field there.
fn accepted_fields<T: serde::de::DeserializeOwned>(
    doc: &toml::Table,
    steps: &[Step],
) -> BTreeSet<String> {
    let mut d = doc.clone();
    table_to(&mut d, steps, "").insert("zz_not_a_key".into(), toml::Value::Integer(0));
    let text = toml::to_string(&d).unwrap();
    let e = match toml::from_str::<T>(&text) {
        Ok(_) => panic!("an unknown key at {steps:?} was accepted"),
        Err(e) => e.message().to_string(),
    };
    assert!(e.contains("unknown field `zz_not_a_key`"), "{e}");
    let list = e.split_once("expected").map_or("", |(_, l)| l);
    list.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The key paths of the spec `full` (every optional key set), after checking that each of
/// its tables holds every field serde accepts there.
fn key_paths<T: serde::de::DeserializeOwned>(
    full: &toml::Table,
    shape: &Shape,
) -> BTreeSet<String> {
    let (mut keys, mut structs) = (BTreeSet::new(), Vec::new());
    walk(full, &[], "", shape, &mut keys, &mut structs);
    for (steps, path) in &structs {
        let mut d = full.clone();
        let present: BTreeSet<String> = table_to(&mut d, steps, path).keys().cloned().collect();
        let mut accepted = accepted_fields::<T>(full, steps);
        for (alias, key) in shape.aliases {
            let (parent, name) = alias.rsplit_once('.').unwrap_or(("", alias));
            if parent == path && accepted.remove(name) {
                assert!(
                    keys.contains(*key),
                    "{alias} spells {key}, which the full spec lacks"
                );
            }
        }
        assert_eq!(
            accepted, present,
            "the fields accepted at `{path}` (left) and those the full spec sets (right): \
             set the missing ones in the full spec"
        );
    }
    keys
}

/// A row: a key and the check of its effect on a fixture.
type Row<F> = (&'static str, fn(&F));

/// Checks that `rows` name exactly `keys` (one row per key), then runs every row and fails
/// naming each row that failed.
fn check_rows<F>(kind: &str, keys: &BTreeSet<String>, rows: &[Row<F>], fixture: &F) {
    let named: BTreeSet<String> = rows.iter().map(|(k, _)| k.to_string()).collect();
    assert_eq!(named.len(), rows.len(), "{kind}: a key has two rows");
    let missing: Vec<&String> = keys.difference(&named).collect();
    let stale: Vec<&String> = named.difference(keys).collect();
    assert!(
        missing.is_empty() && stale.is_empty(),
        "{kind}: keys without a row (add one showing the key's effect): {missing:?}; rows of \
         keys the kind does not accept: {stale:?}"
    );
    let start = Instant::now();
    let mut failed = Vec::new();
    for (key, row) in rows {
        let t = Instant::now();
        if std::panic::catch_unwind(AssertUnwindSafe(|| row(fixture))).is_err() {
            failed.push(*key);
        }
        let seconds = t.elapsed().as_secs_f64();
        if seconds > 0.2 {
            eprintln!("{kind}: {key}: {seconds:.2} s");
        }
    }
    eprintln!(
        "{kind}: {} keys, {:.2} s",
        rows.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(failed.is_empty(), "{kind}: the rows of {failed:?} failed");
}

// ---------------------------------------------------------------------------------------
// Scenes and their outputs

/// `path` (`a.b[0].c`) as steps.
fn steps_of(path: &str) -> Vec<Step> {
    let mut steps = Vec::new();
    for part in path.split('.') {
        match part.split_once('[') {
            Some((k, i)) => {
                steps.push(Step::Key(k.to_string()));
                steps.push(Step::Index(i.trim_end_matches(']').parse().unwrap()));
            }
            None => steps.push(Step::Key(part.to_string())),
        }
    }
    steps
}

/// The table at `steps` of `t`, the tables on the way made as needed (`path` names the key in
/// messages).
fn table_to<'a>(t: &'a mut toml::Table, steps: &[Step], path: &str) -> &'a mut toml::Table {
    match steps {
        [] => t,
        [Step::Key(k), Step::Index(i), rest @ ..] => {
            let item = t
                .get_mut(k)
                .and_then(toml::Value::as_array_mut)
                .and_then(|a| a.get_mut(*i))
                .and_then(toml::Value::as_table_mut)
                .unwrap_or_else(|| panic!("{path}: no table {k}[{i}]"));
            table_to(item, rest, path)
        }
        [Step::Key(k), rest @ ..] => {
            let next = t
                .entry(k.clone())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                .as_table_mut()
                .unwrap_or_else(|| panic!("{path}: {k} is not a table"));
            table_to(next, rest, path)
        }
        [Step::Index(i), ..] => panic!("{path}: index {i} after an index"),
    }
}

/// A copy of `doc` with each `(path, value)` of `changes` set (`value` in TOML syntax), or
/// removed for the value `"-"`.
fn with(doc: &toml::Table, changes: &[(&str, &str)]) -> toml::Table {
    let mut d = doc.clone();
    for (path, value) in changes {
        let steps = steps_of(path);
        let (Some(Step::Key(last)), parent) = (steps.last(), &steps[..steps.len() - 1]) else {
            panic!("{path}: the last step is a key")
        };
        let t = table_to(&mut d, parent, path);
        if *value == "-" {
            t.remove(last);
        } else {
            let v: toml::Table = toml::from_str(&format!("v = {value}")).unwrap();
            t.insert(last.clone(), v["v"].clone());
        }
    }
    d
}

/// `v[a][b]...` for the path `a.b...` (numbers index arrays).
fn at<'a>(v: &'a Value, path: &str) -> &'a Value {
    path.split('.').fold(v, |v, k| match k.parse::<usize>() {
        Ok(i) => &v[i],
        Err(_) => &v[k],
    })
}

/// `v[a][b]...` as a number.
fn num(v: &Value, path: &str) -> f64 {
    let x = at(v, path);
    x.as_f64().unwrap_or_else(|| panic!("{path} = {x}"))
}

/// `v[a][b]...` as a string.
fn text(v: &Value, path: &str) -> String {
    let x = at(v, path);
    x.as_str()
        .unwrap_or_else(|| panic!("{path} = {x}"))
        .to_string()
}

/// `v[a][b]...` as numbers.
fn series(v: &Value, path: &str) -> Vec<f64> {
    let x = at(v, path);
    x.as_array()
        .unwrap_or_else(|| panic!("{path} = {x}"))
        .iter()
        .map(|y| y.as_f64().unwrap())
        .collect()
}

/// The largest difference of two fields over the largest magnitude of the second.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The largest relative distance of `values` from `expected`.
fn off(values: &[f64], expected: f64) -> f64 {
    values
        .iter()
        .map(|v| (v - expected).abs() / expected.abs())
        .fold(0.0, f64::max)
}

/// A face group of a body's Gmsh file: its name, and which boundary faces it holds (by
/// their centroids).
type Group<'a> = (&'a str, &'a dyn Fn(&Vector3<f64>) -> bool);

/// A body's Gmsh file: its cells in the group `name`, and `groups`.
fn body_file(mesh: &VolumeMesh, name: &str, groups: &[Group]) -> Vec<u8> {
    let faces = mesh.boundary_faces().unwrap();
    let picked: Vec<Vec<_>> = groups
        .iter()
        .map(|(_, pick)| {
            faces
                .iter()
                .filter(|f| pick(&f.centroid))
                .cloned()
                .collect()
        })
        .collect();
    let refs: Vec<(&[_], &str)> = picked
        .iter()
        .zip(groups)
        .map(|(f, (g, _))| (f.as_slice(), *g))
        .collect();
    msh41_volume_bytes((mesh, name), &refs, MshFormat::Ascii).unwrap()
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// A rectangle body across `0 <= y <= 1`: its file with `end` (its faces on `x = end`), `cut`
/// (on `x = cut`; `cut_low`: those below `y = 1/2`) and `sides` (on `y = 0` and `y = 1`).
fn block_file(mesh: &VolumeMesh, name: &str, end: f64, cut: f64) -> Vec<u8> {
    body_file(
        mesh,
        name,
        &[
            ("end", &|x| near(x.x, end)),
            ("cut", &|x| near(x.x, cut)),
            ("cut_low", &|x| near(x.x, cut) && x.y < 0.5),
            ("sides", &|x| near(x.y, 0.0) || near(x.y, 1.0)),
        ],
    )
}

/// A square body `[0, 1] x [y0, y0 + 1]`: its file with `bottom` (`bottom_left`: its half
/// `x < 1/2`), `top` (`top_left`; `top_most`: those left of `x = 0.9`), `left` (on `x = 0`)
/// and `right` (on `x = 1`).
fn square_file(mesh: &VolumeMesh, name: &str, y0: f64) -> Vec<u8> {
    body_file(
        mesh,
        name,
        &[
            ("bottom", &|x| near(x.y, y0)),
            ("bottom_left", &|x| near(x.y, y0) && x.x < 0.5),
            ("top", &|x| near(x.y, y0 + 1.0)),
            ("top_left", &|x| near(x.y, y0 + 1.0) && x.x < 0.5),
            ("top_most", &|x| near(x.y, y0 + 1.0) && x.x < 0.9),
            ("left", &|x| near(x.x, 0.0)),
            ("right", &|x| near(x.x, 1.0)),
        ],
    )
}

/// A quarter of the annulus `r0 <= r <= r1` (`x >= 0`, `y <= 0`), `around x 1` cells, swept
/// through `0 <= z <= 0.25` and raised to Hex27 with the new nodes of both arcs on their
/// cylinders: its file with `inner` (the faces on `r = r0`) and `outer` (on `r = r1`).
fn annulus_file(name: &str, r0: f64, r1: f64, around: usize) -> Vec<u8> {
    let flat = quarter_annulus_mesh(r0, r1, [around, 1], CellShape::Tensor, 1).unwrap();
    let hex = extrude_mesh(&flat, &[0.0, 0.25], 1).unwrap();
    let (a, b) = (
        onto_cylinder([0.0; 3], [0.0, 0.0, 1.0], r0),
        onto_cylinder([0.0; 3], [0.0, 0.0, 1.0], r1),
    );
    let mesh = second_order_mesh(&hex, SecondOrder::Complete, |x, p| b(&a(x, p), p)).unwrap();
    let r = |x: &Vector3<f64>| x.xy().norm();
    let margin = 0.05 * (r1 - r0);
    body_file(
        &mesh,
        name,
        &[
            ("inner", &|x| r(x) < r0 + margin),
            ("outer", &|x| r(x) > r1 - margin),
        ],
    )
}

/// The box `[0, 1]^2 x [z0, z1]` in `n x n x 2` cells, Hex8 or Tet4; `distort` moves every
/// node by `c (x (1 - x) (2y - 1), y (1 - y) (2x - 1))` in its plane `z = const` (`c = 0.6`),
/// so that the faces on `z = z0` are flat quads that are not parallelograms while the sides
/// stay on their planes. Its file with `bottom`, `top`, `x0` (on `x = 0`), `y0` (on `y = 0`).
fn box_file(name: &str, z: [f64; 2], n: usize, shape: CellShape, distort: bool) -> Vec<u8> {
    let mut mesh = box_mesh([0.0, 0.0, z[0]], [1.0, 1.0, z[1]], [n, n, 2], shape, 1).unwrap();
    if distort {
        let c = 0.6;
        mesh.transform(|p| {
            Vector3::new(
                p.x + c * p.x * (1.0 - p.x) * (2.0 * p.y - 1.0),
                p.y + c * p.y * (1.0 - p.y) * (2.0 * p.x - 1.0),
                p.z,
            )
        })
        .unwrap();
    }
    body_file(
        &mesh,
        name,
        &[
            ("bottom", &|x| near(x.z, z[0])),
            ("top", &|x| near(x.z, z[1])),
            ("x0", &|x| near(x.x, 0.0)),
            ("y0", &|x| near(x.y, 0.0)),
        ],
    )
}

/// Writes every mesh file of the tied-heat and contact rows into `dir`.
fn write_meshes(dir: &TempDir) {
    let rect = |lo: [f64; 2], hi: [f64; 2], n: [usize; 2], shape| {
        rectangle_mesh(lo, hi, n, shape, 1).unwrap()
    };
    let (quads, tris) = (CellShape::Tensor, CellShape::Simplex);
    // Tied heat: the square cut at x = 1/2, a finer right body, the right body 0.05 away.
    let left = rect([0.0, 0.0], [0.5, 1.0], [2, 4], quads);
    dir.file("left.msh", block_file(&left, "left", 0.0, 0.5));
    let right = rect([0.5, 0.0], [1.0, 1.0], [3, 6], tris);
    dir.file("right.msh", block_file(&right, "right", 1.0, 0.5));
    let fine = rect([0.5, 0.0], [1.0, 1.0], [5, 10], tris);
    dir.file("right_fine.msh", block_file(&fine, "right", 1.0, 0.5));
    let apart = rect([0.55, 0.0], [1.05, 1.0], [3, 6], tris);
    dir.file("right_apart.msh", block_file(&apart, "right", 1.05, 0.55));
    // Contact: two stacked squares, a finer lower one, the upper one 0.5 above.
    let square = |y0: f64, n: usize, shape| rect([0.0, y0], [1.0, y0 + 1.0], [n, n], shape);
    dir.file(
        "lower.msh",
        square_file(&square(0.0, 4, quads), "lower", 0.0),
    );
    let lower_fine = square(0.0, 6, quads);
    dir.file("lower_fine.msh", square_file(&lower_fine, "lower", 0.0));
    dir.file(
        "upper.msh",
        square_file(&square(1.0, 5, tris), "upper", 1.0),
    );
    let upper_apart = square(1.5, 5, tris);
    dir.file("upper_apart.msh", square_file(&upper_apart, "upper", 1.5));
    // 3D: Hex27 quarter annuli meeting on the cylinder r = 1; a distorted Hex8 block on a
    // Tet4 (tied heat) or a Hex8 (contact) one.
    dir.file("core.msh", annulus_file("core", 0.5, 1.0, 6));
    dir.file("shell.msh", annulus_file("shell", 1.0, 1.5, 4));
    dir.file("upper_q.msh", box_file("upper", [0.5, 1.0], 3, quads, true));
    dir.file("lower_q.msh", box_file("lower", [0.0, 0.5], 4, tris, false));
    dir.file(
        "lower_h.msh",
        box_file("lower", [0.0, 0.5], 4, quads, false),
    );
}

/// A scene's outputs: `report.json`, and the other files by name.
struct Out {
    report: Value,
    files: Vec<(String, Vec<u8>)>,
}

impl Out {
    fn new(files: Vec<(String, Vec<u8>)>) -> Self {
        let report = files
            .iter()
            .find(|(n, _)| n == "report.json")
            .map(|(_, b)| serde_json::from_slice(b).unwrap())
            .expect("report.json");
        Self { report, files }
    }

    /// The named point data of the VTU file `file`.
    fn field(&self, file: &str, name: &str) -> Vec<f64> {
        let (_, bytes) = self
            .files
            .iter()
            .find(|(n, _)| n == file)
            .unwrap_or_else(|| panic!("no {file}"));
        let vtu = std::str::from_utf8(bytes).unwrap();
        let rest = vtu
            .split(&format!("Name=\"{name}\""))
            .nth(1)
            .unwrap_or_else(|| panic!("no {name} in {file}"));
        rest.split_once('>')
            .unwrap()
            .1
            .split("</DataArray>")
            .next()
            .unwrap()
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect()
    }

    fn num(&self, path: &str) -> f64 {
        num(&self.report, path)
    }

    fn text(&self, path: &str) -> String {
        text(&self.report, path)
    }
}

/// Runs a scene file's text from `dir` (the scene file `dir/scene.toml`): its output files,
/// or the error.
type Runner = fn(&str, &Path, &Path) -> Result<Vec<(String, Vec<u8>)>, String>;

fn run_tied(text: &str, path: &Path, base: &Path) -> Result<Vec<(String, Vec<u8>)>, String> {
    let spec = TiedHeatSpec::parse(text, path).map_err(|e| e.to_string())?;
    let out = spec
        .run(path, base, &FileSystem)
        .map_err(|e| e.to_string())?;
    Ok(out.files)
}

fn run_contact(text: &str, path: &Path, base: &Path) -> Result<Vec<(String, Vec<u8>)>, String> {
    let spec = ContactSpec::parse(text, path).map_err(|e| e.to_string())?;
    let out = spec
        .run(path, base, &FileSystem)
        .map_err(|e| e.to_string())?;
    Ok(out.files)
}

/// The scenes of a file kind: the meshes in `dir`, the base scene, and the 3D scenes of the
/// integration dials (curved second-order faces, non-parallelogram quads).
struct Scenes {
    dir: TempDir,
    base: toml::Table,
    curved: toml::Table,
    quads: toml::Table,
    runner: Runner,
}

impl Scenes {
    fn new(label: &str, texts: [&str; 3], runner: Runner) -> Self {
        let dir = TempDir::new(label);
        write_meshes(&dir);
        let [base, curved, quads] = texts.map(|t| toml::from_str(t).unwrap());
        Self {
            dir,
            base,
            curved,
            quads,
            runner,
        }
    }

    fn run(&self, doc: &toml::Table) -> Result<Out, String> {
        let text = toml::to_string(doc).unwrap();
        let files = (self.runner)(&text, &self.dir.join("scene.toml"), &self.dir.join(""))?;
        Ok(Out::new(files))
    }

    /// The base scene with `changes`, run.
    fn ok(&self, changes: &[(&str, &str)]) -> Out {
        self.ok_on(&self.base, changes)
    }

    /// The scene `doc` with `changes`, run.
    fn ok_on(&self, doc: &toml::Table, changes: &[(&str, &str)]) -> Out {
        self.run(&with(doc, changes))
            .unwrap_or_else(|e| panic!("{changes:?}: {e}"))
    }

    /// The error of the base scene with `changes`.
    fn err(&self, changes: &[(&str, &str)]) -> String {
        match self.run(&with(&self.base, changes)) {
            Ok(_) => panic!("{changes:?} ran"),
            Err(e) => e,
        }
    }

    /// The contact pressure at the slave nodes of the contact scene `doc` with `changes`,
    /// from the solution (so that it does not depend on writing the interface's faces).
    fn pressures(&self, doc: &toml::Table, changes: &[(&str, &str)]) -> Vec<f64> {
        let text = toml::to_string(&with(doc, changes)).unwrap();
        let path = self.dir.join("scene.toml");
        let spec = ContactSpec::parse(&text, &path).unwrap();
        let solved = spec
            .solve(&path, &self.dir.join(""), &FileSystem)
            .unwrap_or_else(|e| panic!("{changes:?}: {e}"));
        solved.solution.pressure
    }
}

/// `mortar run` on the scene `text` written into `dir` as `name`: the report, or the error.
fn cli(dir: &TempDir, name: &str, text: &str) -> Result<Value, String> {
    let scene = dir.file(name, text);
    let out = dir.join(&format!("out-{name}"));
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    if o.status.success() {
        let report = std::fs::read_to_string(out.join("report.json")).unwrap();
        Ok(serde_json::from_str(&report).unwrap())
    } else {
        Err(String::from_utf8_lossy(&o.stderr).into_owned())
    }
}

/// The row of `kind`: `mortar run` runs the base scene's text as its kind, and gives the same
/// text under `kind = "other"` to the other kind's reader, which refuses a key of it.
fn kind_row(dir: &TempDir, base: &str, kind: &str, other: &str) {
    let report = cli(dir, "kind.toml", base).unwrap_or_else(|e| panic!("{e}"));
    let reported = report.get("kind").or_else(|| report.get("scene"));
    assert_eq!(reported, Some(&Value::from(kind)), "{report}");
    let moved = base.replacen(
        &format!("kind = \"{kind}\""),
        &format!("kind = \"{other}\""),
        1,
    );
    assert_ne!(moved, base);
    let e = cli(dir, "other_kind.toml", &moved).unwrap_err();
    assert!(e.contains("unknown field"), "{e}");
}

// ---------------------------------------------------------------------------------------
// tied_heat

/// The base tied-heat scene: the unit square cut at `x = 1/2` (the patch test of
/// `mortar_scenes::file::tied_block`, `n = 4`): `left` (master, 2 x 4 Quad4, k = 1, T = 0 on
/// `x = 0`), `right` (slave, 3 x 6 cells cut into Tri3, k = 2, entering flux 4/3 on
/// `x = 1`); the exact temperature is piecewise linear, 2/3 on the cut and 1 at `x = 1`.
const TIED: &str = r#"kind = "tied_heat"
title = "tied square"
dimension = 2

[bodies.left]
mesh = "left.msh"
group = "left"
conductivity = 1.0
rho_cp = 1.0
dirichlet = [{ group = "end", value = 0.0 }]

[bodies.right]
mesh = "right.msh"
group = "right"
conductivity = 2.0
rho_cp = 1.0
neumann = [{ group = "end", flux = 1.3333333333333333 }]

[interface]
slave = { body = "right", group = "cut" }
master = { body = "left", group = "cut" }
"#;

/// Two Hex27 quarter annuli around the `z` axis tied along the cylinder `r = 1` (curved Quad9
/// faces, 6 slave faces against 4): `core` (`0.5 <= r <= 1`, T = 0 inside), `shell`
/// (`1 <= r <= 1.5`, T = 1 outside).
const TIED_CURVED: &str = r#"kind = "tied_heat"

[bodies.core]
mesh = "core.msh"
group = "core"
conductivity = 1.0
dirichlet = [{ group = "inner", value = 0.0 }]

[bodies.shell]
mesh = "shell.msh"
group = "shell"
conductivity = 1.0
dirichlet = [{ group = "outer", value = 1.0 }]

[interface]
slave = { body = "core", group = "outer" }
master = { body = "shell", group = "inner" }
"#;

/// A distorted Hex8 block (`upper`, `[0, 1]^2 x [1/2, 1]`, 3 x 3 x 2, heated by a source, its
/// bottom faces the slave side: flat quads that are not parallelograms) tied to a Tet4 block
/// (`lower`, 4 x 4 x 2, T = 0 at its bottom) along `z = 1/2`.
const TIED_QUADS: &str = r#"kind = "tied_heat"

[bodies.upper]
mesh = "upper_q.msh"
group = "upper"
conductivity = 1.0
source = 1.0

[bodies.lower]
mesh = "lower_q.msh"
group = "lower"
conductivity = 1.0
dirichlet = [{ group = "bottom", value = 0.0 }]

[interface]
slave = { body = "upper", group = "bottom" }
master = { body = "lower", group = "top" }
"#;

/// A tied-heat scene with every optional key set, as TOML.
fn tied_heat_full() -> toml::Table {
    let side = |body: &str| SideSpec {
        body: body.into(),
        group: "g".into(),
    };
    let body = BodySpec {
        mesh: "b.msh".into(),
        group: "b".into(),
        conductivity: 1.0,
        rho_cp: Some(1.0),
        source: 1.0,
        initial: 1.0,
        dirichlet: vec![DirichletSpec {
            group: "g".into(),
            value: 1.0,
        }],
        neumann: vec![NeumannSpec {
            group: "g".into(),
            flux: 1.0,
        }],
    };
    let spec = TiedHeatSpec {
        kind: "tied_heat".into(),
        title: Some("t".into()),
        dimension: Some(2),
        solve: SolveSpec {
            mode: Mode::Transient,
            dt: Some(1.0),
            steps: Some(1),
            formulation: FormulationSpec::SaddlePoint,
            backend: mortar_scenes::linear_solver::BackendChoice::Direct,
            linear_tolerance: Some(1e-10),
            petsc_options: "-ksp_monitor".into(),
        },
        bodies: BTreeMap::from([("a".into(), body.clone()), ("b".into(), body)]),
        interface: InterfaceSpec {
            slave: side("a"),
            master: side("b"),
            multipliers: Multipliers::Standard,
            integration: Integration::Segment,
            degree: Some(2),
            curved_tolerance: Some(0.1),
            subdivision: Some(2),
            quad_subdivision: Some(2),
            search_radius: Some(1.0),
            require_full_coverage: true,
        },
    };
    toml::from_str(&spec.to_toml().unwrap()).unwrap()
}

/// The temperatures of the right (slave) body.
fn right_t(o: &Out) -> Vec<f64> {
    o.field("right.vtu", "temperature")
}

/// A transient solve of the base scene: one step of 0.05 from T = 0.
const TRANSIENT: [(&str, &str); 3] = [
    ("solve.mode", "\"transient\""),
    ("solve.dt", "0.05"),
    ("solve.steps", "1"),
];

/// The transient base with `changes`.
fn transient<'a>(changes: &[(&'a str, &'a str)]) -> Vec<(&'a str, &'a str)> {
    TRANSIENT
        .iter()
        .copied()
        .chain(changes.iter().copied())
        .collect()
}

fn tied_heat_rows() -> Vec<Row<Scenes>> {
    vec![
        ("kind", |f| {
            kind_row(&f.dir, TIED, "tied_heat", "contact");
        }),
        ("title", |f| {
            assert_eq!(f.ok(&[]).text("title"), "tied square");
            assert_eq!(f.ok(&[("title", "\"renamed\"")]).text("title"), "renamed");
        }),
        ("dimension", |f| {
            // A check of the meshes: the 2D bodies run as `dimension = 2` and are refused as 3.
            assert_eq!(f.ok(&[]).num("dimension"), 2.0);
            let e = f.err(&[("dimension", "3")]);
            assert!(e.contains(": dimension: the scene says 3D"), "{e}");
        }),
        ("solve.mode", |f| {
            let (steady, run) = (f.ok(&[]), f.ok(&TRANSIENT));
            assert_eq!(
                (steady.text("mode"), run.text("mode")),
                ("steady".into(), "transient".into())
            );
            // One step from T = 0 heats the right end part of the way to its steady 1.
            let t = run.num("bodies.0.temperature_max");
            assert!(t > 0.01 && t < 0.9, "{t}");
            assert_eq!(run.num("time"), 0.05);
        }),
        ("solve.dt", |f| {
            let (a, b) = (f.ok(&TRANSIENT), f.ok(&transient(&[("solve.dt", "0.1")])));
            assert_eq!(b.num("time"), 0.1);
            assert!(b.num("bodies.0.temperature_max") > a.num("bodies.0.temperature_max"));
        }),
        ("solve.steps", |f| {
            let (a, b) = (f.ok(&TRANSIENT), f.ok(&transient(&[("solve.steps", "2")])));
            assert_eq!((b.num("steps"), b.num("time")), (2.0, 0.1));
            assert!(b.num("bodies.0.temperature_max") > a.num("bodies.0.temperature_max"));
        }),
        ("solve.formulation", |f| {
            let (auto, saddle) = (
                f.ok(&[]),
                f.ok(&[("solve.formulation", "\"saddle_point\"")]),
            );
            assert_eq!(auto.text("formulation.name"), "dual-condensed SPD");
            assert_eq!(saddle.text("formulation.name"), "saddle point");
            assert!(rel_diff(&right_t(&saddle), &right_t(&auto)) < 1e-12);
        }),
        ("solve.backend", |f| {
            // The direct solve below the size where PETSc pays; PETSc when asked for (CG with
            // GAMG on the condensed system, GMRES with the Schur fieldsplit on the saddle
            // point), the same temperatures to its tolerance; in a build without PETSc, an
            // error saying how to get it.
            let auto = f.ok(&[]);
            assert_eq!(auto.text("linear_solver.backend"), "direct");
            assert!(auto.text("linear_solver.why").contains("in 2D"));
            assert_eq!(auto.text("solver.kind"), "sparse direct");
            backend_asked_for(f);
            if mortar::petsc::is_built() {
                let o = f.ok(&[("solve.backend", "\"petsc\"")]);
                assert_eq!(o.text("linear_solver.backend"), "petsc");
                assert_eq!(o.text("linear_solver.methods.0"), "cg+gamg");
                assert_eq!(o.text("solver.kind"), "PETSc Krylov");
                assert!(rel_diff(&right_t(&o), &right_t(&auto)) < 1e-9);
                // The right body is held by the tie alone: its saddle point's primal block is
                // singular, which PETSc's Schur fieldsplit cannot take.
                let e = f.err(&[
                    ("solve.backend", "\"petsc\""),
                    ("solve.formulation", "\"saddle_point\""),
                ]);
                assert!(e.contains("singular primal block"), "{e}");
                // Both bodies of the curved scene are held: its saddle point goes to GMRES
                // with the Schur fieldsplit, the temperatures the direct solve's.
                let t = |o: Out| o.field("core.vtu", "temperature");
                let saddle = [("solve.formulation", "\"saddle_point\"")];
                let direct = f.ok_on(&f.curved, &saddle);
                let petsc = f.ok_on(&f.curved, &[saddle[0], ("solve.backend", "\"petsc\"")]);
                assert_eq!(petsc.text("linear_solver.methods.0"), "gmres+fieldsplit");
                assert!(rel_diff(&t(petsc), &t(direct)) < 1e-9);
            }
        }),
        ("solve.linear_tolerance", |f| {
            linear_tolerance_row(f, "1.5", "1e-3")
        }),
        ("solve.petsc_options", |f| {
            petsc_options_row(f, |f, o| {
                assert!(rel_diff(&right_t(o), &right_t(&f.ok(&[]))) < 1e-9);
            })
        }),
        ("bodies.*.mesh", |f| {
            let (a, b) = (
                f.ok(&[]),
                f.ok(&[("bodies.right.mesh", "\"right_fine.msh\"")]),
            );
            assert_eq!(
                (a.num("bodies.0.nodes"), b.num("bodies.0.nodes")),
                (28.0, 66.0)
            );
            assert!(off(&[b.num("bodies.0.temperature_max")], 1.0) < 1e-10);
        }),
        ("bodies.*.group", |f| {
            // The file has one group of cells: a group of faces is refused, naming the key.
            let e = f.err(&[("bodies.right.group", "\"cut\"")]);
            assert!(
                e.contains("bodies.right.group") && e.contains("\"cut\" has dimension 1"),
                "{e}"
            );
        }),
        ("bodies.*.conductivity", |f| {
            // k_right = 4: T(1) = 2/3 + (4/3)(1/2)/4 = 5/6.
            let o = f.ok(&[("bodies.right.conductivity", "4.0")]);
            assert!(off(&[o.num("bodies.0.temperature_max")], 5.0 / 6.0) < 1e-10);
        }),
        ("bodies.*.rho_cp", |f| {
            let a = f.ok(&TRANSIENT);
            let b = f.ok(&transient(&[("bodies.right.rho_cp", "4.0")]));
            assert!(b.num("bodies.0.temperature_max") < 0.9 * a.num("bodies.0.temperature_max"));
        }),
        ("bodies.*.source", |f| {
            // q = 1 in the left body: T(1/2) = 2/3 + q/8, T(1) = 1 + q/8 (nodally exact).
            let o = f.ok(&[("bodies.left.source", "1.0")]);
            assert!(off(&[o.num("bodies.0.temperature_max")], 1.125) < 1e-10);
        }),
        ("bodies.*.initial", |f| {
            let a = f.ok(&TRANSIENT);
            let b = f.ok(&transient(&[("bodies.right.initial", "1.0")]));
            assert!(b.num("bodies.0.temperature_min") > a.num("bodies.0.temperature_max"));
        }),
        ("bodies.*.dirichlet[].group", |f| {
            // T = 0 on the left body's sides instead of its end.
            let (a, b) = (
                f.ok(&[]),
                f.ok(&[("bodies.left.dirichlet[0].group", "\"sides\"")]),
            );
            assert!(b.num("bodies.1.temperature_min") == 0.0);
            assert!(rel_diff(&right_t(&b), &right_t(&a)) > 1e-2);
        }),
        ("bodies.*.dirichlet[].value", |f| {
            let o = f.ok(&[("bodies.left.dirichlet[0].value", "1.0")]);
            assert!(off(&[o.num("bodies.0.temperature_max")], 2.0) < 1e-10);
            assert!(off(&[o.num("bodies.1.temperature_min")], 1.0) < 1e-10);
        }),
        ("bodies.*.neumann[].group", |f| {
            // The flux enters through the right body's sides instead of its end.
            let (a, b) = (
                f.ok(&[]),
                f.ok(&[("bodies.right.neumann[0].group", "\"sides\"")]),
            );
            assert!(rel_diff(&right_t(&b), &right_t(&a)) > 1e-2);
        }),
        ("bodies.*.neumann[].flux", |f| {
            let o = f.ok(&[("bodies.right.neumann[0].flux", "2.6666666666666665")]);
            assert!(off(&[o.num("bodies.0.temperature_max")], 2.0) < 1e-10);
        }),
        ("interface.slave.body", swap_tied_sides),
        ("interface.slave.group", |f| {
            // Only the lower half of the right body's cut is tied.
            let o = f.ok(&[("interface.slave.group", "\"cut_low\"")]);
            assert!(off(&[o.num("interface.area")], 0.5) < 1e-12);
            assert_eq!(o.num("interface.slave_nodes"), 4.0);
        }),
        ("interface.master.body", swap_tied_sides),
        ("interface.master.group", |f| {
            let o = f.ok(&[("interface.master.group", "\"cut_low\"")]);
            let w = o.report["warnings"].to_string();
            assert!(
                w.contains("uncovered slave area: 5.000e-1 of 1.000e0"),
                "{w}"
            );
        }),
        ("interface.multipliers", |f| {
            let (dual, std) = (
                f.ok(&[]),
                f.ok(&[("interface.multipliers", "\"standard\"")]),
            );
            assert!(std
                .text("interface.coupling")
                .starts_with("standard multipliers"));
            assert_eq!(std.text("formulation.name"), "saddle point");
            assert!(rel_diff(&right_t(&std), &right_t(&dual)) < 1e-12);
        }),
        ("interface.integration", |f| {
            // Element-based integration is not exact on the non-matching interface: the patch
            // test is passed to round-off by segment-based integration only.
            let error = |o: &Out| off(&[o.num("bodies.0.temperature_max")], 1.0);
            let (seg, el) = (f.ok(&[]), f.ok(&[("interface.integration", "\"element\"")]));
            assert!(el.text("interface.coupling").contains("element-based"));
            assert!(
                error(&seg) < 1e-12 && error(&el) > 1e-5,
                "{} {}",
                error(&seg),
                error(&el)
            );
        }),
        ("interface.degree", |f| {
            let element = [("interface.integration", "\"element\"")];
            let auto = f.ok(&element);
            let one = f.ok(&[element[0], ("interface.degree", "1")]);
            assert!(one
                .text("interface.coupling")
                .contains("element-based, degree 1"));
            assert!(rel_diff(&right_t(&one), &right_t(&auto)) > 1e-3);
            let seg = f.ok(&[("interface.degree", "4")]);
            assert!(seg
                .text("interface.coupling")
                .contains("segment-based, degree 4"));
        }),
        ("interface.curved_tolerance", |f| {
            let t = |o: Out| o.field("core.vtu", "temperature");
            let reference = t(f.ok_on(&f.curved, &[("interface.subdivision", "8")]));
            let error = |tol: &str| {
                rel_diff(
                    &t(f.ok_on(&f.curved, &[("interface.curved_tolerance", tol)])),
                    &reference,
                )
            };
            let (coarse, fine) = (error("1.0"), error("1e-3"));
            assert!(fine < coarse / 10.0, "{coarse:e} {fine:e}");
        }),
        ("interface.subdivision", |f| {
            let t = |o: Out| o.field("core.vtu", "temperature");
            let reference = t(f.ok_on(&f.curved, &[("interface.subdivision", "8")]));
            let error = |l: &str| {
                rel_diff(
                    &t(f.ok_on(&f.curved, &[("interface.subdivision", l)])),
                    &reference,
                )
            };
            let (one, four) = (error("1"), error("4"));
            assert!(four < one / 4.0, "{one:e} {four:e}");
        }),
        ("interface.quad_subdivision", |f| {
            let t = |o: &Out| o.field("upper.vtu", "temperature");
            let run = |m: &str| f.ok_on(&f.quads, &[("interface.quad_subdivision", m)]);
            let (one, four, eight) = (run("1"), run("4"), run("8"));
            assert!(four
                .text("interface.coupling")
                .contains("non-parallelogram quads cut 4x4"));
            let (e1, e4) = (
                rel_diff(&t(&one), &t(&eight)),
                rel_diff(&t(&four), &t(&eight)),
            );
            assert!(e4 < e1 / 100.0, "{e1:e} {e4:e}");
        }),
        ("interface.search_radius", |f| {
            // The right body 0.05 away: tied within a search radius of 0.1, not of 0.02.
            let apart = ("bodies.right.mesh", "\"right_apart.msh\"");
            let e = f.err(&[apart, ("interface.search_radius", "0.02")]);
            assert!(e.contains("no overlap"), "{e}");
            let o = f.ok(&[apart, ("interface.search_radius", "0.1")]);
            assert!(off(&[o.num("interface.area")], 1.0) < 1e-12);
            assert!(off(&[o.num("bodies.0.temperature_max")], 1.0) < 1e-10);
        }),
        ("interface.require_full_coverage", |f| {
            let half = ("interface.master.group", "\"cut_low\"");
            assert_eq!(
                f.ok(&[half]).report["warnings"].as_array().map(Vec::len),
                Some(1)
            );
            let e = f.err(&[half, ("interface.require_full_coverage", "true")]);
            assert!(
                e.contains("uncovered slave area") && e.contains("full coverage was required"),
                "{e}"
            );
        }),
    ]
}

/// What the row of `solve.backend` checks alike in either scene kind: `"direct"` says it was
/// asked for; in a build without PETSc, `"petsc"` is an error naming the key and saying how
/// to get it.
fn backend_asked_for(f: &Scenes) {
    let direct = f.ok(&[("solve.backend", "\"direct\"")]);
    assert!(direct.text("linear_solver.why").contains("asked for"));
    if !mortar::petsc::is_built() {
        let e = f.err(&[("solve.backend", "\"petsc\"")]);
        assert!(
            e.contains("solve.backend") && e.contains("--features petsc"),
            "{e}"
        );
    }
}

/// The row of `solve.linear_tolerance`, either scene kind: a tolerance `bad`, outside
/// (0, 1), is refused naming the key; through PETSc the tolerance `loose` takes fewer
/// iterations than 1e-12.
fn linear_tolerance_row(f: &Scenes, bad: &str, loose: &str) {
    let e = f.err(&[("solve.linear_tolerance", bad)]);
    assert!(
        e.contains("solve.linear_tolerance") && e.contains("not in (0, 1)"),
        "{e}"
    );
    if mortar::petsc::is_built() {
        let its = |tol: &str| {
            f.ok(&[
                ("solve.backend", "\"petsc\""),
                ("solve.linear_tolerance", tol),
            ])
            .num("linear_solver.iterations.0")
        };
        let (tight, loose) = (its("1e-12"), its(loose));
        assert!(loose < tight, "{loose} {tight}");
    }
}

/// The row of `solve.petsc_options`, either scene kind: read after the picked method's
/// options, they override it (`-ksp_type minres` runs MINRES), and `check` finds the solution
/// the direct one's; in a build without PETSc, an error saying how to get it.
fn petsc_options_row(f: &Scenes, check: fn(&Scenes, &Out)) {
    let changes = [
        ("solve.backend", "\"petsc\""),
        ("solve.petsc_options", "\"-ksp_type minres\""),
    ];
    if mortar::petsc::is_built() {
        let o = f.ok(&changes);
        assert_eq!(o.text("linear_solver.methods.0"), "minres+gamg");
        check(f, &o);
    } else {
        let e = f.err(&changes);
        assert!(e.contains("--features petsc"), "{e}");
    }
}

/// The rows of `interface.slave.body` and `interface.master.body`: the sides swap (both keys
/// change together: one body cannot be both sides); the left body's 5 nodes carry the
/// multipliers instead of the right body's 7, and the patch test still holds.
fn swap_tied_sides(f: &Scenes) {
    let o = f.ok(&[
        ("interface.slave.body", "\"left\""),
        ("interface.master.body", "\"right\""),
    ]);
    assert_eq!(o.text("bodies.0.name"), "left");
    assert_eq!(
        (
            o.num("interface.slave_nodes"),
            o.num("interface.master_nodes")
        ),
        (5.0, 7.0)
    );
    assert!(off(&[o.num("bodies.1.temperature_max")], 1.0) < 1e-10);
}

/// Every key of `kind = "tied_heat"` (crates/mortar-scenes/src/file/tied_heat.rs). Sources: the base
/// scene's exact solution, conduction through two slabs in series (Fourier's law, one
/// dimension): `T(1) = 2/3 + (4/3)(1/2) / k_right` (5/6 for `k_right = 4`), `T(1) = 1 + q/8`
/// with a source `q` in the left slab (linear elements are exact at the nodes in one
/// dimension), the field shifted by a prescribed value and scaled by the flux; the patch test
/// for the search radius, the swapped sides and the finer mesh. The integration dials against a
/// converged reference, measured (largest difference of the temperatures over their largest
/// value): curved faces 8.3e-4 at level 1 (and `curved_tolerance = 1`), 5.0e-5 at level 4,
/// 5.6e-6 at `curved_tolerance = 1e-3`, against level 8; non-parallelogram quads 8.0e-5 uncut,
/// 2.9e-7 cut 4x4, against 8x8. Element-based integration is 4.1e-5 off `T(1) = 1`
/// (segment-based to round-off), its degree 1 6.1e-3 off the automatic degree.
#[test]
fn every_tied_heat_key_has_an_effect() {
    let shape = Shape {
        named: &["bodies"],
        laws: &[],
        aliases: &[],
    };
    let keys = key_paths::<TiedHeatSpec>(&tied_heat_full(), &shape);
    let f = Scenes::new("scene-keys-tied", [TIED, TIED_CURVED, TIED_QUADS], run_tied);
    check_rows("tied_heat", &keys, &tied_heat_rows(), &f);
}

// ---------------------------------------------------------------------------------------
// contact

/// The pressure of the contact patch tests (Pa).
const SIGMA: f64 = 50e6;

/// The base contact scene: the patch test of tests/integration/contact_scene.rs, two stacked
/// unit squares meshed independently (`upper`, the slave, 5 x 5 cells cut into Tri3; `lower`,
/// 4 x 4 Quad4), the upper one pressed by `sigma = 50 MPa` on its top and held in x on its
/// left side, the lower one held in y at its bottom and in x on its left side: exact contact
/// carries `sigma` at every slave node, and the upper body's top moves down by
/// `sigma (1 - nu^2) (1 / E_upper + 1 / E_lower)` (uniaxial plane strain, free sides).
const CONTACT: &str = r#"kind = "contact"
title = "stacked blocks"

[bodies.upper]
mesh = "upper.msh"
group = "upper"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [{ group = "left", component = "x", value = 0.0 }]
traction = [{ group = "top", value = [0.0, -50e6] }]

[bodies.lower]
mesh = "lower.msh"
group = "lower"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    { group = "bottom", component = "y", value = 0.0 },
    { group = "left", component = "x", value = 0.0 },
]

[contact]
slave = { body = "upper", group = "bottom" }
master = { body = "lower", group = "top" }
"#;

/// The Hex27 quarter annuli of [`TIED_CURVED`] in contact along `r = 1`: `core` held on its
/// inside, `shell` moved by 1 mm towards the axis (along the quadrant's bisector) on its
/// outside.
const CONTACT_CURVED: &str = r#"kind = "contact"

[bodies.core]
mesh = "core.msh"
group = "core"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [{ group = "inner", component = "all", value = 0.0 }]

[bodies.shell]
mesh = "shell.msh"
group = "shell"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [{ group = "outer", component = "all", value = [-7.0710678118654757e-4, 7.0710678118654757e-4, 0.0] }]

[contact]
slave = { body = "core", group = "outer" }
master = { body = "shell", group = "inner" }
"#;

/// The 3D contact patch test: the distorted Hex8 block of [`TIED_QUADS`] (`upper`, its bottom
/// faces the slave side) pressed by `sigma` on its top onto a Hex8 block (`lower`, 4 x 4 x 2)
/// held in z at its bottom; both held in x on `x = 0` and in y on `y = 0`: exact contact
/// carries `sigma` at every slave node.
const CONTACT_QUADS: &str = r#"kind = "contact"

[bodies.upper]
mesh = "upper_q.msh"
group = "upper"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    { group = "x0", component = "x", value = 0.0 },
    { group = "y0", component = "y", value = 0.0 },
]
traction = [{ group = "top", value = [0.0, 0.0, -50e6] }]

[bodies.lower]
mesh = "lower_h.msh"
group = "lower"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    { group = "bottom", component = "z", value = 0.0 },
    { group = "x0", component = "x", value = 0.0 },
    { group = "y0", component = "y", value = 0.0 },
]

[contact]
slave = { body = "upper", group = "bottom" }
master = { body = "lower", group = "top" }
"#;

/// A contact scene with every optional key set, as TOML.
fn contact_full() -> toml::Table {
    let side = |body: &str| SideSpec {
        body: body.into(),
        group: "g".into(),
    };
    let body = ElasticBodySpec {
        mesh: "b.msh".into(),
        group: "b".into(),
        youngs_modulus: 1.0,
        poisson_ratio: 0.3,
        dirichlet: vec![DisplacementSpec {
            group: "g".into(),
            component: Component::X,
            value: ComponentValue::Number(0.0),
        }],
        traction: vec![TractionSpec {
            group: "g".into(),
            value: vec![0.0, 1.0],
        }],
    };
    let spec = ContactSpec {
        kind: "contact".into(),
        title: Some("t".into()),
        solve: ContactSolveSpec {
            load_steps: 2,
            max_newton_steps: 10,
            tolerance: 1e-8,
            backend: mortar_scenes::linear_solver::BackendChoice::Direct,
            linear_tolerance: Some(1e-10),
            petsc_options: "-ksp_monitor".into(),
        },
        bodies: BTreeMap::from([("a".into(), body.clone()), ("b".into(), body)]),
        contact: ContactInterfaceSpec {
            slave: side("a"),
            master: side("b"),
            law: LawSpec::Exponential,
            named_law: Some(NamedLaw {
                name: "contact_complementarity".into(),
                parameters: BTreeMap::from([("c".into(), 1e12)]),
            }),
            base_pressure: Some(1.0),
            stiffness: Some(1.0),
            onset: Some(1.0),
            multipliers: Multipliers::Standard,
            integration: Integration::Segment,
            degree: Some(2),
            curved_tolerance: Some(0.1),
            subdivision: Some(2),
            quad_subdivision: Some(2),
            search_radius: Some(1.0),
            require_full_coverage: true,
        },
    };
    toml::from_str(&spec.to_toml().unwrap()).unwrap()
}

/// The exponential law of the contact rows: `P_o = 1e5 Pa`, `S = 1e12 /m^2`, `xi = 1e-5 m`.
const EXPONENTIAL: [(&str, &str); 4] = [
    ("contact.law", "\"exponential\""),
    ("contact.base_pressure", "1e5"),
    ("contact.stiffness", "1e12"),
    ("contact.onset", "1e-5"),
];

/// The exponential base with `changes`.
fn exponential<'a>(changes: &[(&'a str, &'a str)]) -> Vec<(&'a str, &'a str)> {
    let mut all: Vec<(&str, &str)> = EXPONENTIAL.to_vec();
    for c in changes {
        all.retain(|(k, _)| *k != c.0);
        all.push(*c);
    }
    all
}

/// The gap at which `P_o exp(S (xi - g)^2)` is `p` (`g < xi`): the exponential pressure law
/// solved for the gap.
fn exponential_gap(p: f64, po: f64, s: f64, xi: f64) -> f64 {
    xi - ((p / po).ln() / s).sqrt()
}

/// The gaps of a contact run, and their largest distance from `expected` (m).
fn gaps_off(o: &Out, expected: f64) -> f64 {
    o.field("interface.vtu", "gap")
        .iter()
        .map(|g| (g - expected).abs())
        .fold(0.0, f64::max)
}

fn pressures(o: &Out) -> Vec<f64> {
    o.field("interface.vtu", "contact_pressure")
}

/// The largest displacement of the upper (slave) body.
fn upper_u(o: &Out) -> f64 {
    o.num("bodies.0.displacement_max")
}

/// The upper body's largest displacement in the base scene: the top's, `sigma (1 - nu^2)
/// (1 / E_u + 1 / E_l)`.
fn upper_top_u(e_upper: f64) -> f64 {
    SIGMA * (1.0 - 0.09) * (1.0 / e_upper + 1.0 / 210e9)
}

fn contact_rows() -> Vec<Row<Scenes>> {
    vec![
        ("kind", |f| {
            kind_row(&f.dir, CONTACT, "contact", "tied_heat");
        }),
        ("title", |f| {
            assert_eq!(f.ok(&[]).text("title"), "stacked blocks");
            assert_eq!(f.ok(&[("title", "\"renamed\"")]).text("title"), "renamed");
        }),
        ("solve.load_steps", |f| {
            let o = f.ok(&[("solve.load_steps", "2")]);
            let factors: Vec<f64> = (0..2)
                .map(|k| o.num(&format!("load_steps.{k}.load_factor")))
                .collect();
            assert_eq!(factors, [0.5, 1.0]);
            assert!(off(&pressures(&o), SIGMA) < 1e-8);
        }),
        ("solve.max_newton_steps", |f| {
            // The exponential law takes more Newton steps than 2: allowed 2, the load step
            // fails, naming the key of the load steps and Newton.
            let o = f.ok(&EXPONENTIAL);
            assert!(o.num("load_steps.0.newton_steps") > 2.0);
            let e = f.err(&exponential(&[("solve.max_newton_steps", "2")]));
            assert!(
                e.contains("solve.load_steps: load step 1 of 1") && e.contains("after 2 step(s)"),
                "{e}"
            );
        }),
        ("solve.tolerance", |f| {
            let steps = |o: Out| o.num("load_steps.0.newton_steps");
            let tight = steps(f.ok(&EXPONENTIAL));
            let loose = steps(f.ok(&exponential(&[("solve.tolerance", "1e-4")])));
            assert!(loose < tight, "{loose} {tight}");
        }),
        ("solve.backend", |f| {
            // The default (auto) is the direct solve at this size, as "direct" is; "petsc"
            // gives the patch test's pressure through CG and GAMG, or, in a build without
            // PETSc, an error saying how to get it.
            assert_eq!(f.ok(&[]).text("linear_solver.backend"), "direct");
            backend_asked_for(f);
            if mortar::petsc::is_built() {
                let o = f.ok(&[("solve.backend", "\"petsc\"")]);
                assert_eq!(o.text("linear_solver.backend"), "petsc");
                assert_eq!(o.text("linear_solver.methods.0"), "cg+gamg");
                assert!(off(&pressures(&o), SIGMA) < 1e-10);
            }
        }),
        ("solve.linear_tolerance", |f| {
            linear_tolerance_row(f, "0.0", "1e-4")
        }),
        ("solve.petsc_options", |f| {
            petsc_options_row(f, |_, o| assert!(off(&pressures(o), SIGMA) < 1e-8))
        }),
        ("bodies.*.mesh", |f| {
            let o = f.ok(&[("bodies.lower.mesh", "\"lower_fine.msh\"")]);
            assert_eq!(
                (f.ok(&[]).num("bodies.1.nodes"), o.num("bodies.1.nodes")),
                (25.0, 49.0)
            );
            assert!(off(&pressures(&o), SIGMA) < 1e-8);
        }),
        ("bodies.*.group", |f| {
            let e = f.err(&[("bodies.upper.group", "\"top\"")]);
            assert!(
                e.contains("bodies.upper.group") && e.contains("\"top\" has dimension 1"),
                "{e}"
            );
        }),
        ("bodies.*.youngs_modulus", |f| {
            let (a, b) = (f.ok(&[]), f.ok(&[("bodies.upper.youngs_modulus", "105e9")]));
            assert!(
                off(&[upper_u(&a)], upper_top_u(210e9)) < 1e-8,
                "{}",
                upper_u(&a)
            );
            assert!(
                off(&[upper_u(&b)], upper_top_u(105e9)) < 1e-8,
                "{}",
                upper_u(&b)
            );
        }),
        ("bodies.*.poisson_ratio", |f| {
            // Plane strain under sigma_yy = -sigma, sigma_xx = 0: sigma_zz = -nu sigma.
            let szz = |o: Out| o.field("upper.vtu", "stress_zz");
            assert!(off(&szz(f.ok(&[])), -0.3 * SIGMA) < 1e-8);
            assert!(
                off(
                    &szz(f.ok(&[("bodies.upper.poisson_ratio", "0.2")])),
                    -0.2 * SIGMA
                ) < 1e-8
            );
        }),
        ("bodies.*.dirichlet[].group", |f| {
            // The upper block held in x on its top instead of its left side: its lateral
            // expansion is held there, and the contact pressure is no longer uniform.
            let o = f.ok(&[("bodies.upper.dirichlet[0].group", "\"top\"")]);
            assert!(off(&pressures(&o), SIGMA) > 1e-3);
        }),
        ("bodies.*.dirichlet[].component", |f| {
            // The lower block's bottom held in x and y: its lateral expansion is held.
            let o = f.ok(&[("bodies.lower.dirichlet[0].component", "\"all\"")]);
            assert!(off(&pressures(&o), SIGMA) > 1e-3);
        }),
        ("bodies.*.dirichlet[].value", |f| {
            // The lower block's bottom moved down by 1 mm: both blocks follow it rigidly.
            let o = f.ok(&[("bodies.lower.dirichlet[0].value", "-1e-3")]);
            assert!(off(&[upper_u(&o)], upper_top_u(210e9) + 1e-3) < 1e-8);
            assert!(off(&pressures(&o), SIGMA) < 1e-8);
        }),
        ("bodies.*.traction[].group", |f| {
            // The same load on the upper block's right side: carried to the interface, but
            // not uniformly.
            let o = f.ok(&[("bodies.upper.traction[0].group", "\"right\"")]);
            assert!(off(&[o.num("contact_force")], SIGMA) < 1e-8);
            assert!(off(&pressures(&o), SIGMA) > 1e-2);
        }),
        ("bodies.*.traction[].value", |f| {
            let o = f.ok(&[("bodies.upper.traction[0].value", "[0.0, -100e6]")]);
            assert!(off(&[o.num("contact_force")], 2.0 * SIGMA) < 1e-8);
            assert!(off(&pressures(&o), 2.0 * SIGMA) < 1e-8);
        }),
        ("contact.slave.body", swap_contact_sides),
        ("contact.slave.group", |f| {
            // Only the upper block's bottom faces left of x = 1/2 (x <= 0.4) may touch: they
            // carry the whole load.
            let o = f.ok(&[("contact.slave.group", "\"bottom_left\"")]);
            assert_eq!(o.num("interface.slave_nodes"), 3.0);
            assert!(off(&[o.num("contact_force")], SIGMA) < 1e-8);
            assert!(o.num("pressure_max") > 2.0 * SIGMA);
        }),
        ("contact.master.body", swap_contact_sides),
        ("contact.master.group", |f| {
            // The lower block's top left of x = 1/2 only: the upper block's right part has
            // no contact area.
            let e = f.err(&[("contact.master.group", "\"top_left\"")]);
            assert!(
                e.contains("has no contact area")
                    && e.contains("the master surface does not cover it"),
                "{e}"
            );
            let o = f.ok(&PARTLY_COVERED);
            let w = o.report["warnings"].to_string();
            assert!(
                w.contains("uncovered slave area: 1.667e-1 of 1.000e0"),
                "{w}"
            );
        }),
        ("contact.law", |f| {
            let o = f.ok(&EXPONENTIAL);
            assert!(o.text("law").starts_with("exponential pressure"));
            assert!(gaps_off(&o, exponential_gap(SIGMA, 1e5, 1e12, 1e-5)) < 1e-13);
            assert!(gaps_off(&f.ok(&[]), 0.0) < 1e-13);
        }),
        ("contact.named_law.name", |f| {
            let named = |law: &str| f.ok(&[("contact.named_law", law)]);
            let c = named("{ name = \"contact_complementarity\", c = 1e12 }");
            let e = named(
                "{ name = \"exponential_pressure\", base_pressure = 1e5, stiffness = 1e12, onset = 1e-5 }",
            );
            assert!(c
                .text("law")
                .starts_with("contact_complementarity (by name)"));
            assert!(e.text("law").starts_with("exponential_pressure (by name)"));
            assert!(gaps_off(&c, 0.0) < 1e-13);
            assert!(gaps_off(&e, exponential_gap(SIGMA, 1e5, 1e12, 1e-5)) < 1e-13);
        }),
        ("contact.named_law.*", |f| {
            let law = |onset: &str| {
                format!("{{ name = \"exponential_pressure\", base_pressure = 1e5, stiffness = 1e12, onset = {onset} }}")
            };
            let o = f.ok(&[("contact.named_law", &law("2e-5"))]);
            assert!(gaps_off(&o, exponential_gap(SIGMA, 1e5, 1e12, 2e-5)) < 1e-13);
        }),
        ("contact.base_pressure", |f| {
            let o = f.ok(&exponential(&[("contact.base_pressure", "1e6")]));
            assert!(gaps_off(&o, exponential_gap(SIGMA, 1e6, 1e12, 1e-5)) < 1e-13);
        }),
        ("contact.stiffness", |f| {
            let o = f.ok(&exponential(&[("contact.stiffness", "4e12")]));
            assert!(gaps_off(&o, exponential_gap(SIGMA, 1e5, 4e12, 1e-5)) < 1e-13);
        }),
        ("contact.onset", |f| {
            let o = f.ok(&exponential(&[("contact.onset", "2e-5")]));
            assert!(gaps_off(&o, exponential_gap(SIGMA, 1e5, 1e12, 2e-5)) < 1e-13);
        }),
        ("contact.multipliers", |f| {
            let o = f.ok(&[("contact.multipliers", "\"standard\"")]);
            assert!(o
                .text("interface.coupling")
                .starts_with("standard multipliers"));
            assert!(
                o.text("formulation").starts_with("saddle"),
                "{}",
                o.text("formulation")
            );
            assert!(f
                .ok(&[])
                .text("formulation")
                .starts_with("pressures condensed out"));
            assert!(off(&pressures(&o), SIGMA) < 1e-8);
        }),
        ("contact.integration", |f| {
            // Element-based integration is not exact on the non-matching interface.
            let o = f.ok(&[("contact.integration", "\"element\"")]);
            assert!(o.text("interface.coupling").contains("element-based"));
            assert!(off(&pressures(&f.ok(&[])), SIGMA) < 1e-8);
            assert!(off(&pressures(&o), SIGMA) > 1e-3);
        }),
        ("contact.degree", |f| {
            let element = ("contact.integration", "\"element\"");
            let auto = f.ok(&[element]);
            let one = f.ok(&[element, ("contact.degree", "1")]);
            assert!(one
                .text("interface.coupling")
                .contains("element-based, degree 1"));
            assert!(rel_diff(&pressures(&one), &pressures(&auto)) > 1e-2);
        }),
        ("contact.curved_tolerance", |f| {
            let reference = f.pressures(&f.curved, &[("contact.subdivision", "8")]);
            let error = |tol: &str| {
                rel_diff(
                    &f.pressures(&f.curved, &[("contact.curved_tolerance", tol)]),
                    &reference,
                )
            };
            let (coarse, fine) = (error("1.0"), error("1e-3"));
            assert!(fine < coarse / 5.0, "{coarse:e} {fine:e}");
        }),
        ("contact.subdivision", |f| {
            let reference = f.pressures(&f.curved, &[("contact.subdivision", "8")]);
            let error = |l: &str| {
                rel_diff(
                    &f.pressures(&f.curved, &[("contact.subdivision", l)]),
                    &reference,
                )
            };
            let (one, four) = (error("1"), error("4"));
            assert!(four < one / 2.0, "{one:e} {four:e}");
        }),
        ("contact.quad_subdivision", |f| {
            // The patch test on non-parallelogram slave quads: the pressure error falls from
            // 1.5e-5 (uncut) to 6.9e-8 with each clip triangle cut into 16.
            let run = |m: &str| f.ok_on(&f.quads, &[("contact.quad_subdivision", m)]);
            let (one, four) = (run("1"), run("4"));
            assert!(four
                .text("interface.coupling")
                .contains("non-parallelogram quads cut 4x4"));
            let (e1, e4) = (off(&pressures(&one), SIGMA), off(&pressures(&four), SIGMA));
            assert!(e1 > 1e-6 && e4 < 1e-6, "{e1:e} {e4:e}");
        }),
        ("contact.search_radius", |f| {
            // The upper block 0.5 above the lower one, its top pushed down by 0.5 + delta:
            // coupled within a search radius of 0.6, with the pressure of two equal blocks in
            // series, E delta / (2 (1 - nu^2)); no overlap within 0.4.
            let delta = 1e-3;
            let apart = [
                ("bodies.upper.mesh", "\"upper_apart.msh\""),
                ("bodies.upper.traction", "-"),
                ("bodies.upper.dirichlet", "[{ group = \"left\", component = \"x\", value = 0.0 }, { group = \"top\", component = \"y\", value = -0.501 }]"),
            ];
            let e = f.err(&[
                apart[0],
                apart[1],
                apart[2],
                ("contact.search_radius", "0.4"),
            ]);
            assert!(e.contains("no overlap"), "{e}");
            let o = f.ok(&[
                apart[0],
                apart[1],
                apart[2],
                ("contact.search_radius", "0.6"),
            ]);
            assert!(off(&pressures(&o), 210e9 * delta / (2.0 * 0.91)) < 1e-8);
        }),
        ("contact.require_full_coverage", |f| {
            assert_eq!(
                f.ok(&PARTLY_COVERED).report["warnings"]
                    .as_array()
                    .map(Vec::len),
                Some(1)
            );
            let mut required = PARTLY_COVERED.to_vec();
            required.push(("contact.require_full_coverage", "true"));
            let e = f.err(&required);
            assert!(
                e.contains("uncovered slave area") && e.contains("full coverage was required"),
                "{e}"
            );
        }),
    ]
}

/// The base contact scene on the finer lower block, whose top faces left of `x = 0.9` (up to
/// `x = 5/6`) are the master side: the upper block's last face (`0.8 <= x <= 1`) is covered
/// in part; standard multipliers, so that its nodes keep a positive area.
const PARTLY_COVERED: [(&str, &str); 3] = [
    ("bodies.lower.mesh", "\"lower_fine.msh\""),
    ("contact.master.group", "\"top_most\""),
    ("contact.multipliers", "\"standard\""),
];

/// The rows of `contact.slave.body` and `contact.master.body`: the sides swap (with their
/// groups); the lower block's 5 top nodes carry the pressure, still `sigma`.
fn swap_contact_sides(f: &Scenes) {
    let o = f.ok(&[
        ("contact.slave", "{ body = \"lower\", group = \"top\" }"),
        ("contact.master", "{ body = \"upper\", group = \"bottom\" }"),
    ]);
    assert_eq!(o.text("bodies.0.name"), "lower");
    assert_eq!(o.num("interface.slave_nodes"), 5.0);
    assert!(off(&pressures(&o), SIGMA) < 1e-8);
}

/// Every key of `kind = "contact"` (crates/mortar-scenes/src/file/contact.rs). Sources: uniaxial plane
/// strain (Hooke's law with `eps_zz = 0`, free sides): `sigma_zz = -nu sigma`, the upper
/// block's top down by `sigma (1 - nu^2) (1 / E_u + 1 / E_l)`; two equal blocks in series
/// squeezed by `delta`: `E delta / (2 (1 - nu^2))`; the exponential law `P_o exp(S (xi -
/// g)^2) = sigma` solved for the gap, `g = xi - sqrt(ln(sigma / P_o) / S)`, at every slave
/// node; the patch tests (`sigma` at every slave node). Measured: curved faces (the pressures
/// against level 8) 1.2e-1 at level 1 and `curved_tolerance = 1`, 3.0e-2 at level 4, 5.9e-3
/// at `curved_tolerance = 1e-3`; the 3D patch test on non-parallelogram quads 1.5e-5 uncut,
/// 6.9e-8 cut 4x4; element-based integration 2.3e-2 off `sigma`; the exponential law 12
/// Newton steps at `tolerance = 1e-10`, 11 at 1e-4.
#[test]
fn every_contact_key_has_an_effect() {
    let shape = Shape {
        named: &["bodies"],
        laws: &["contact.named_law"],
        aliases: &[],
    };
    let keys = key_paths::<ContactSpec>(&contact_full(), &shape);
    let f = Scenes::new(
        "scene-keys-contact",
        [CONTACT, CONTACT_CURVED, CONTACT_QUADS],
        run_contact,
    );
    check_rows("contact", &keys, &contact_rows(), &f);
}

// ---------------------------------------------------------------------------------------
// pellet

/// The base pellet scene: the default pellet (`mortar_scenes::pellet`) on the coarsest mesh,
/// its power ramped to 20 kW/m in 1 s, two backward Euler steps of 1 s (the gap closes at
/// about 1.9 s), then the steady state at full power; one snapshot.
const PELLET: &str = r#"kind = "pellet"

[mesh]
refinement = 1

[time]
step = 1.0
end = 2.0
snapshots = 1

[power]
ramp_time = 1.0

# Plane strain: its gap closes within the two steps, so that the keys' effects on the contact
# show (with free axial expansion it stays above the pressure law's onset).
[model]
axial = "plane_strain"
"#;

/// A pellet scene with every optional key set, as TOML.
fn pellet_full() -> toml::Table {
    let law = |name: &str, key: &str, value: f64| NamedLaw {
        name: name.into(),
        parameters: BTreeMap::from([(key.into(), value)]),
    };
    let mut s = PelletScene {
        scene: Some("pellet".into()),
        ..PelletScene::default()
    };
    s.gap.gas_conductivity = Some(0.3);
    s.model.axial = Some(AxialModel::Generalized);
    s.mesh.file = Some("pellet_rz.msh".into());
    s.laws.thermal = Some(law(
        "mechanical_gap_conductance",
        "contact_conductance",
        1e-4,
    ));
    s.laws.contact = Some(law("exponential_contact", "onset", 5e-6));
    s.solver.backend = mortar_scenes::linear_solver::BackendChoice::Direct;
    s.solver.linear_tolerance = Some(1e-10);
    toml::from_str(&toml::to_string(&s).unwrap()).unwrap()
}

struct Pellet {
    dir: TempDir,
    base: toml::Table,
    /// The base scene's report.
    report: Value,
    runs: AtomicUsize,
}

impl Pellet {
    fn new() -> Self {
        let base: toml::Table = toml::from_str(PELLET).unwrap();
        let mut p = Self {
            dir: TempDir::new("scene-keys-pellet"),
            base,
            report: Value::Null,
            runs: AtomicUsize::new(0),
        };
        p.report = p.ok(&[]);
        p
    }

    /// The report of the base scene with `changes`; or the error, and the report the run
    /// wrote of its failure (if any).
    fn run(&self, changes: &[(&str, &str)]) -> Result<Value, (String, Option<Value>)> {
        let text = toml::to_string(&with(&self.base, changes)).unwrap();
        let out = self.dir.join(&format!(
            "run-{}",
            self.runs.fetch_add(1, Ordering::Relaxed)
        ));
        let report = mortar_scenes::pellet::run_from_toml(&text, &out, false);
        let written = std::fs::read_to_string(out.join("report.json"))
            .ok()
            .map(|t| serde_json::from_str(&t).unwrap());
        let _ = std::fs::remove_dir_all(&out);
        report.map_err(|e| (e.to_string(), written))
    }

    fn ok(&self, changes: &[(&str, &str)]) -> Value {
        self.run(changes)
            .unwrap_or_else(|(e, _)| panic!("{changes:?}: {e}"))
    }

    fn err(&self, changes: &[(&str, &str)]) -> String {
        self.failure_or_error(changes).0
    }

    /// The error of a run that fails, and the report it wrote.
    fn failure(&self, changes: &[(&str, &str)]) -> (String, Value) {
        let (e, report) = self.failure_or_error(changes);
        (e, report.expect("the report of the failure"))
    }

    fn failure_or_error(&self, changes: &[(&str, &str)]) -> (String, Option<Value>) {
        match self.run(changes) {
            Ok(_) => panic!("{changes:?} ran"),
            Err(e) => e,
        }
    }

    /// `steady.KEY` of the base scene and of the variant `changes`.
    fn steady(&self, changes: &[(&str, &str)], key: &str) -> (f64, f64) {
        let key = format!("steady.{key}");
        (num(&self.report, &key), num(&self.ok(changes), &key))
    }
}

/// The gap closure time of a report (infinite when the gap stays open).
fn closure(r: &Value) -> f64 {
    r["gap_closure_time"].as_f64().unwrap_or(f64::INFINITY)
}

/// `history.KEY` at `t = 1 s` (the second row).
fn at_one_second(r: &Value, key: &str) -> f64 {
    assert_eq!(series(r, "history.time")[1], 1.0);
    series(r, &format!("history.{key}"))[1]
}

/// The Ross-Stoute law by name with the default `[gap]` values and `contact_conductance`.
fn thermal_law(contact_conductance: &str) -> String {
    format!(
        "{{ name = \"mechanical_gap_conductance\", roughness_fuel = 2e-6, roughness_cladding = \
         1e-6, jump_distance = 10e-6, contact_conductance = {contact_conductance} }}"
    )
}

/// The exponential contact law by name with `S = 1e12 /m^2` and `onset`.
fn contact_law(onset: &str) -> String {
    format!("{{ name = \"exponential_contact\", stiffness = 1e12, onset = {onset} }}")
}

/// The rows of keys that make the pellet hotter (a larger steady centre temperature).
fn hotter(f: &Pellet, changes: &[(&str, &str)]) {
    let (a, b) = f.steady(changes, "center_temperature");
    assert!(b > a + 1.0, "{changes:?}: {a} -> {b}");
}

/// The rows of keys that lower the gap conductance (a hotter pellet surface).
fn insulates(f: &Pellet, changes: &[(&str, &str)]) {
    let (a, b) = f.steady(changes, "pellet_surface_temperature");
    assert!(b > a + 1.0, "{changes:?}: {a} -> {b}");
}

/// The steady interface pressure rises (`up`) or falls with `changes`, by over 1 %.
fn pressure(f: &Pellet, changes: &[(&str, &str)], up: bool) {
    let (a, b) = f.steady(changes, "interface_pressure");
    assert!(
        if up { b > 1.01 * a } else { b < 0.99 * a },
        "{changes:?}: {a} -> {b}"
    );
}

/// The gap closes later (or not at all) with `changes`, and the steady gap is wider.
fn opens(f: &Pellet, changes: &[(&str, &str)]) {
    let (a, b) = f.steady(changes, "gap");
    assert!(b > a, "{changes:?}: steady gap {a} -> {b}");
    let (t0, t1) = (closure(&f.report), closure(&f.ok(changes)));
    assert!(t1 > t0, "{changes:?}: closure {t0} -> {t1}");
}

fn pellet_rows() -> Vec<Row<Pellet>> {
    vec![
        ("scene", |f| {
            // `kind = "pellet"` (or `scene = "pellet"`): `mortar run` runs the pellet.
            kind_row(&f.dir, PELLET, "pellet", "tied_heat");
            let spelled = PELLET.replacen("kind =", "scene =", 1);
            let report = cli(&f.dir, "scene.toml", &spelled).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(report["scene"], "pellet");
            let e = f.err(&[("kind", "\"contact\"")]);
            assert!(e.contains("scene = \"contact\" is not \"pellet\""), "{e}");
        }),
        ("pellet.radius", |f| {
            opens(f, &[("pellet.radius", "4.095e-3")])
        }),
        ("pellet.conductivity_a", |f| {
            hotter(f, &[("pellet.conductivity_a", "0.05")])
        }),
        ("pellet.conductivity_b", |f| {
            hotter(f, &[("pellet.conductivity_b", "3e-4")])
        }),
        ("pellet.heat_capacity", |f| {
            // Slower heating; the same steady state.
            let r = f.ok(&[("pellet.heat_capacity", "6.6e6")]);
            let key = "center_temperature";
            assert!(at_one_second(&r, key) < at_one_second(&f.report, key) - 1.0);
            assert!(
                off(
                    &[num(&r, "steady.center_temperature")],
                    num(&f.report, "steady.center_temperature")
                ) < 1e-6
            );
        }),
        ("pellet.youngs_modulus", |f| {
            pressure(f, &[("pellet.youngs_modulus", "100e9")], false)
        }),
        ("pellet.poisson_ratio", |f| {
            pressure(f, &[("pellet.poisson_ratio", "0.2")], false)
        }),
        ("pellet.thermal_expansion", |f| {
            pressure(f, &[("pellet.thermal_expansion", "1.2e-5")], true)
        }),
        ("cladding.inner_radius", |f| {
            opens(f, &[("cladding.inner_radius", "4.125e-3")])
        }),
        ("cladding.outer_radius", |f| {
            let (a, b) = f.steady(
                &[("cladding.outer_radius", "4.85e-3")],
                "cladding_inner_temperature",
            );
            assert!(b > a + 1.0, "{a} -> {b}");
        }),
        ("cladding.conductivity", |f| {
            let (a, b) = f.steady(
                &[("cladding.conductivity", "8.0")],
                "cladding_inner_temperature",
            );
            assert!(b > a + 1.0, "{a} -> {b}");
        }),
        ("cladding.outer_temperature", |f| {
            let (a, b) = f.steady(
                &[("cladding.outer_temperature", "600.0")],
                "cladding_inner_temperature",
            );
            assert!((b - a - 20.0).abs() < 1.0, "{a} -> {b}");
        }),
        ("cladding.heat_capacity", |f| {
            let r = f.ok(&[("cladding.heat_capacity", "8e6")]);
            let key = "cladding_inner_temperature";
            assert!(at_one_second(&r, key) < at_one_second(&f.report, key) - 0.1);
        }),
        ("cladding.youngs_modulus", |f| {
            pressure(f, &[("cladding.youngs_modulus", "160e9")], true)
        }),
        ("cladding.poisson_ratio", |f| {
            pressure(f, &[("cladding.poisson_ratio", "0.3")], true)
        }),
        ("cladding.thermal_expansion", |f| {
            opens(f, &[("cladding.thermal_expansion", "1.2e-5")])
        }),
        ("cladding.coolant_pressure", |f| {
            pressure(f, &[("cladding.coolant_pressure", "0.0")], false)
        }),
        ("gap.roughness_pellet", |f| {
            insulates(f, &[("gap.roughness_pellet", "4e-6")])
        }),
        ("gap.roughness_cladding", |f| {
            insulates(f, &[("gap.roughness_cladding", "3e-6")])
        }),
        ("gap.jump_distance", |f| {
            insulates(f, &[("gap.jump_distance", "20e-6")])
        }),
        ("gap.gas_conductivity", |f| {
            insulates(f, &[("gap.gas_conductivity", "0.1")])
        }),
        ("gap.contact_conductance", |f| {
            // Conductance through the contact pressure: a cooler pellet surface.
            let (a, b) = f.steady(
                &[("gap.contact_conductance", "1e-4")],
                "pellet_surface_temperature",
            );
            assert!(b < a - 1.0, "{a} -> {b}");
        }),
        ("contact.law", |f| {
            let r = f.ok(&[("contact.law", "\"exact\"")]);
            assert_eq!(r["models"]["contact_law"], "exact");
            assert!(num(&r, "steady.gap").abs() < 0.1e-6 && num(&f.report, "steady.gap") > 1e-6);
        }),
        ("contact.stiffness_exponent", |f| {
            // A stiffer law holds the surfaces further apart at the same pressure.
            let (a, b) = f.steady(&[("contact.stiffness_exponent", "4e12")], "gap");
            assert!(b > a + 0.5e-6, "{a} -> {b}");
        }),
        ("contact.onset_gap", |f| {
            let (a, b) = f.steady(&[("contact.onset_gap", "6e-6")], "gap");
            assert!(b > a + 0.5e-6, "{a} -> {b}");
        }),
        ("plenum.fill_pressure", |f| {
            // Fixed moles of ideal gas: P_o = P_fill (V_p + V_gap0) T_gap / ((V_p + V_gap)
            // T_fill), in proportion to P_fill but for the gap's response (0.3 % here).
            let (a, b) = f.steady(&[("plenum.fill_pressure", "3e6")], "plenum_pressure");
            assert!(off(&[b / a], 1.5) < 0.01, "{a} -> {b}");
        }),
        ("plenum.fill_temperature", |f| {
            // Filled hotter at the same pressure: fewer moles, P_o in proportion to 1 / T_fill.
            let (a, b) = f.steady(&[("plenum.fill_temperature", "400.0")], "plenum_pressure");
            assert!(off(&[b / a], 293.0 / 400.0) < 0.01, "{a} -> {b}");
        }),
        ("plenum.volume", |f| {
            // A larger plenum takes up more of the gap's closing: a smaller rise.
            let (a, b) = f.steady(&[("plenum.volume", "4e-6")], "plenum_pressure");
            assert!(b < 0.95 * a, "{a} -> {b}");
        }),
        ("model.mechanics", |f| {
            // Heat only: the gap held at its as-built width, a hotter pellet.
            let r = f.ok(&[("model.mechanics", "false")]);
            assert_eq!(r["models"]["mechanics"], false);
            assert!(
                num(&r, "center_temperature") > num(&f.report, "steady.center_temperature") + 10.0
            );
        }),
        ("model.geometry", |f| {
            // The r-z model of a segment: the same physics on another mesh.
            let r = f.ok(&[("model.geometry", "\"axisymmetric\"")]);
            assert_eq!(r["models"]["geometry"], "axisymmetric");
            assert_ne!(r["mesh"]["pellet"], f.report["mesh"]["pellet"]);
            let key = "steady.center_temperature";
            assert!(off(&[num(&r, key)], num(&f.report, key)) < 0.01);
        }),
        ("model.reference_temperature", |f| {
            opens(f, &[("model.reference_temperature", "400.0")])
        }),
        ("model.axial", |f| {
            // Free axial expansion: the pellet expands less radially (by 1 + nu for free
            // expansion) than in the base's plane strain, the gap stays wider.
            let r = f.ok(&[("model.axial", "\"generalized\"")]);
            assert_eq!(r["models"]["axial"], "generalized");
            assert_eq!(f.report["models"]["axial"], "plane_strain");
            let key = "steady.pellet_surface_displacement";
            assert!(1.1 * num(&r, key) < num(&f.report, key));
            assert!(num(&r, "steady.gap") > num(&f.report, "steady.gap"));
        }),
        ("model.relocation", |f| {
            // FRAPCON's relocation of fresh fuel: 5.5 % of the cold gap moves the pellet out.
            let r = f.ok(&[("model.relocation", "\"frapcon\"")]);
            assert_eq!(r["models"]["relocation"], "frapcon");
            assert_eq!(f.report["models"]["relocation"], "none");
            let strain = num(&r, "steady.relocation_strain");
            let (a, b) = (4.1e-3, 4.12e-3);
            assert!(off(&[strain], 0.055 * (b - a) / a) < 1e-12, "{strain}");
            assert_eq!(num(&f.report, "steady.relocation_strain"), 0.0);
            assert!(num(&r, "steady.gap") < num(&f.report, "steady.gap"));
        }),
        ("model.burnup", |f| {
            // At 10 MWd/kgU and up to 20 kW/m FRAPCON's relocation is 40 % of the gap, not
            // the fresh 5.5 %.
            let fresh = f.ok(&[("model.relocation", "\"frapcon\"")]);
            let burnt = f.ok(&[
                ("model.relocation", "\"frapcon\""),
                ("model.burnup", "10.0"),
            ]);
            assert_eq!(burnt["models"]["burnup"], 10.0);
            let key = "steady.relocation_strain";
            assert!(off(&[num(&burnt, key) / num(&fresh, key)], 0.4 / 0.055) < 1e-12);
        }),
        ("model.segment_height", |f| {
            // The r-z segment: the power and heat flow scale with its height, the
            // temperatures do not.
            let rz = ("model.geometry", "\"axisymmetric\"");
            let (a, b) = (f.ok(&[rz]), f.ok(&[rz, ("model.segment_height", "2e-3")]));
            assert!(off(&[num(&a, "steady.power_in")], 20.0) < 1e-12);
            assert!(off(&[num(&b, "steady.power_in")], 40.0) < 1e-12);
            assert!(off(&[num(&b, "steady.heat_out")], 40.0) < 1e-9);
            let key = "steady.center_temperature";
            assert!(off(&[num(&b, key)], num(&a, key)) < 1e-6);
        }),
        ("power.linear_power", |f| {
            let r = f.ok(&[("power.linear_power", "25e3")]);
            assert!(off(&[num(&r, "steady.power_in")], 25e3) < 1e-12);
            assert!(
                num(&r, "steady.center_temperature")
                    > num(&f.report, "steady.center_temperature") + 10.0
            );
        }),
        ("power.ramp_time", |f| {
            let r = f.ok(&[("power.ramp_time", "2.0")]);
            assert_eq!(at_one_second(&f.report, "linear_power"), 20e3);
            assert_eq!(at_one_second(&r, "linear_power"), 10e3);
        }),
        ("time.step", |f| {
            let r = f.ok(&[("time.step", "0.5")]);
            assert_eq!(series(&r, "history.time"), [0.0, 0.5, 1.0, 1.5, 2.0]);
            assert_eq!(series(&f.report, "history.time"), [0.0, 1.0, 2.0]);
        }),
        ("time.end", |f| {
            let r = f.ok(&[("time.end", "3.0")]);
            assert_eq!(series(&r, "history.time"), [0.0, 1.0, 2.0, 3.0]);
        }),
        ("time.snapshots", |f| {
            let count = |r: &Value| r["vtu"].as_array().unwrap().len();
            let r = f.ok(&[("time.snapshots", "2")]);
            assert_eq!((count(&f.report), count(&r)), (2, 3));
        }),
        ("solver.method", |f| {
            // The base asks for "auto", which picks JFNK for the coupled scene.
            let r = f.ok(&[("solver.method", "\"newton\"")]);
            assert_eq!(
                (text(&f.report, "method"), text(&r, "method")),
                ("jfnk".into(), "newton".into())
            );
            assert_eq!(text(&f.report, "solver_choice.asked"), "auto");
            assert_eq!(text(&r, "solver_choice.asked"), "newton");
            let its =
                |r: &Value| num(r, "solver.linear_iterations") - num(r, "solver.newton_iterations");
            assert!(its(&f.report) > 0.0 && its(&r) == 0.0);
            let key = "steady.center_temperature";
            assert!(off(&[num(&r, key)], num(&f.report, key)) < 1e-8);
        }),
        ("solver.backend", |f| {
            assert_eq!(text(&f.report, "linear_solver.backend"), "direct");
            assert!(text(&f.report, "linear_solver.why").contains("auto"));
            let r = f.ok(&[("solver.backend", "\"direct\"")]);
            assert!(text(&r, "linear_solver.why").contains("asked for"));
            let petsc = [("solver.backend", "\"petsc\"")];
            if !mortar::petsc::is_built() {
                assert!(f.err(&petsc).contains("--features petsc"));
                return;
            }
            // PETSc takes Newton's Jacobians: the picked JFNK becomes Newton.
            let r = f.ok(&petsc);
            assert_eq!(text(&r, "linear_solver.backend"), "petsc");
            assert_eq!(text(&r, "method"), "newton");
            assert!(text(&r, "solver_choice.why").contains("PETSc"));
            let key = "steady.center_temperature";
            assert!(off(&[num(&r, key)], num(&f.report, key)) < 1e-8);
            let jfnk = [petsc[0], ("solver.method", "\"jfnk\"")];
            assert!(f.err(&jfnk).contains("solver.backend"));
        }),
        ("solver.linear_tolerance", |f| {
            assert!(f
                .err(&[("solver.linear_tolerance", "2")])
                .contains("solver.linear_tolerance"));
            if !mortar::petsc::is_built() {
                return;
            }
            let iterations = |tol: &str| {
                let r = f.ok(&[
                    ("solver.backend", "\"petsc\""),
                    ("solver.linear_tolerance", tol),
                ]);
                num(&r, "linear_solver.iterations.0")
            };
            assert!(iterations("1e-6") < iterations("1e-12"));
        }),
        ("solver.relative_tolerance", |f| {
            let r = f.ok(&[("solver.relative_tolerance", "1e-4")]);
            let key = "solver.newton_iterations";
            assert!(
                num(&r, key) < num(&f.report, key),
                "{} {}",
                num(&r, key),
                num(&f.report, key)
            );
        }),
        ("solver.max_iterations", |f| {
            // The steady solve takes more Newton steps than any time step: allowed one step
            // fewer than it takes, the transient runs and the steady solve stops, the report
            // of the failure keeping the transient.
            let r = &f.report;
            let steady =
                num(r, "solver.newton_iterations") - num(r, "solver.transient_newton_iterations");
            let per_step = series(r, "history.newton_iterations")
                .into_iter()
                .fold(0.0, f64::max);
            assert!(steady > per_step + 1.0, "{steady} {per_step}");
            let cap = format!("{}", steady as usize - 1);
            let (e, failed) = f.failure(&[("solver.max_iterations", &cap)]);
            assert!(
                e.contains(&format!("(MaxIterations) after {cap} step(s)")),
                "{e}"
            );
            assert_eq!(failed["status"], "failed");
            assert_eq!(
                failed["valid_steps"].as_u64(),
                Some(series(r, "history.time").len() as u64)
            );
        }),
        ("solver.gmres_restart", |f| {
            let jfnk = ("solver.method", "\"jfnk\"");
            // A restart of 2 (the default 30) costs more GMRES iterations (85 against 605
            // when measured; at 5 the two are within a few of each other either way).
            let (a, b) = (f.ok(&[jfnk]), f.ok(&[jfnk, ("solver.gmres_restart", "2")]));
            let key = "solver.linear_iterations";
            assert!(
                num(&b, key) > num(&a, key),
                "{} {}",
                num(&a, key),
                num(&b, key)
            );
        }),
        ("mesh.refinement", |f| {
            let r = f.ok(&[("mesh.refinement", "2")]);
            assert_eq!(
                num(&r, "mesh.pellet.cells"),
                4.0 * num(&f.report, "mesh.pellet.cells")
            );
        }),
        ("mesh.file", |f| {
            // The r-z section from the shipped Gmsh file: its height and radii replace the
            // scene's, its cells the generated ones.
            let rz = ("model.geometry", "\"axisymmetric\"");
            let file = format!(
                "\"{}/examples/scenes/pellet_rz.msh\"",
                env!("CARGO_MANIFEST_DIR")
            );
            let (a, b) = (f.ok(&[rz]), f.ok(&[rz, ("mesh.file", file.as_str())]));
            assert_eq!(num(&b, "mesh.file.height"), 4.9e-3);
            assert_ne!(num(&a, "mesh.pellet.cells"), num(&b, "mesh.pellet.cells"));
        }),
        ("mesh.axial_layers", |f| {
            let rz = ("model.geometry", "\"axisymmetric\"");
            let (a, b) = (f.ok(&[rz]), f.ok(&[rz, ("mesh.axial_layers", "3")]));
            assert_eq!(
                2.0 * num(&b, "mesh.pellet.cells"),
                3.0 * num(&a, "mesh.pellet.cells")
            );
        }),
        ("laws.thermal.name", |f| {
            // The built-in law by name: the same run; the fixed-gap law instead: the gap's
            // closing no longer helps, a hotter pellet.
            let same = f.ok(&[("laws.thermal", &thermal_law("0.0"))]);
            assert_eq!(
                same["models"]["gap_conductance"],
                "mechanical_gap_conductance"
            );
            let key = "steady.center_temperature";
            assert!(off(&[num(&same, key)], num(&f.report, key)) < 1e-9);
            let fixed = "{ name = \"gap_conductance\", gap_width = 20e-6, roughness_fuel = 2e-6, \
                         roughness_cladding = 1e-6, jump_distance = 10e-6 }";
            let r = f.ok(&[("laws.thermal", fixed)]);
            assert_eq!(r["models"]["gap_conductance"], "gap_conductance");
            assert!(num(&r, key) > num(&f.report, key) + 10.0);
        }),
        ("laws.thermal.*", |f| {
            let (a, b) = (
                f.ok(&[("laws.thermal", &thermal_law("0.0"))]),
                f.ok(&[("laws.thermal", &thermal_law("1e-4"))]),
            );
            let key = "steady.pellet_surface_temperature";
            assert!(num(&b, key) < num(&a, key) - 1.0);
        }),
        ("laws.contact.name", |f| {
            let same = f.ok(&[("laws.contact", &contact_law("5e-6"))]);
            assert_eq!(same["models"]["contact_law"], "exponential_contact");
            let key = "steady.gap";
            assert!(off(&[num(&same, key)], num(&f.report, key)) < 1e-9);
            let r = f.ok(&[(
                "laws.contact",
                "{ name = \"contact_complementarity\", c = 1e14 }",
            )]);
            assert_eq!(r["models"]["contact_law"], "contact_complementarity");
            assert!(num(&r, key).abs() < 0.1e-6);
        }),
        ("laws.contact.*", |f| {
            let (a, b) = (
                f.ok(&[("laws.contact", &contact_law("5e-6"))]),
                f.ok(&[("laws.contact", &contact_law("6e-6"))]),
            );
            assert!(num(&b, "steady.gap") > num(&a, "steady.gap") + 0.5e-6);
        }),
    ]
}

/// Every key of `kind = "pellet"` (crates/mortar-scenes/src/pellet/mod.rs), on the base scene of [`PELLET`]
/// (70 ms a run): each key moves a named figure of `report.json` the way the physics of
/// docs/models.md (sections 3 to 6) gives, measured against the base (steady centre 1010 K,
/// gap 3.83 um, interface pressure 20.3 MPa, plenum 5.21 MPa): a less conductive pellet is
/// hotter (`conductivity_a` 0.05: 1034 K), a wider as-built gap or a more expanding cladding
/// stays wider (4.41 um, 8.18 um), a stiffer or more expanding pellet presses harder
/// (`thermal_expansion` 1.2e-5: 35.7 MPa), the coolant's pressure presses too (6.9 MPa
/// without it), a poorer gas insulates (`gas_conductivity` 0.1: pellet surface 750 K against
/// 664 K), the contact conductance cools (659 K); the plenum's gas is ideal with fixed moles
/// (`P_o` in proportion to `P_fill` and `1 / T_fill`, within 1 %).
#[test]
fn every_pellet_key_has_an_effect() {
    let shape = Shape {
        named: &[],
        laws: &["laws.thermal", "laws.contact"],
        aliases: &[("kind", "scene")],
    };
    let keys = key_paths::<PelletScene>(&pellet_full(), &shape);
    let f = Pellet::new();
    check_rows("pellet", &keys, &pellet_rows(), &f);
}

// ---------------------------------------------------------------------------------------
// Keys that were accepted and passed over

/// Regression: with `named_law`, the exponential law's `base_pressure`, `stiffness` and
/// `onset` were accepted and passed over (the named law's own parameters apply). They are
/// refused, naming the key.
#[test]
fn a_named_contact_law_refuses_the_built_in_law_keys() {
    let base: toml::Table = toml::from_str(CONTACT).unwrap();
    let named = (
        "contact.named_law",
        "{ name = \"exponential_pressure\", base_pressure = 1e5, stiffness = 1e12, onset = 1e-5 }",
    );
    let path = Path::new("scene.toml");
    let parse = |doc: toml::Table| ContactSpec::parse(&toml::to_string(&doc).unwrap(), path);
    assert!(parse(with(&base, &[named])).is_ok());
    for (key, value) in [
        ("contact.onset", "2e-5"),
        ("contact.stiffness", "1e12"),
        ("contact.base_pressure", "1e5"),
    ] {
        let e = parse(with(&base, &[named, (key, value)]))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("{key}: only the exponential law")) && e.contains("named_law"),
            "{e}"
        );
    }
}

/// Regression: a parameter a shipped law does not take (`named_law`, `[laws.*]`) was passed
/// over, so that a misspelt one left its default in place (`gas_conductivty = 0.3`: helium).
/// It is refused, naming it, in both file kinds that name laws.
#[test]
fn laws_by_name_refuse_parameters_they_do_not_take() {
    let contact = Scenes::new(
        "scene-keys-law-params",
        [CONTACT, CONTACT_CURVED, CONTACT_QUADS],
        run_contact,
    );
    let e = contact.err(&[(
        "contact.named_law",
        "{ name = \"contact_complementarity\", c = 1e12, onset = 1e-5 }",
    )]);
    assert!(
        e.contains("contact.named_law") && e.contains("unknown parameter \"onset\""),
        "{e}"
    );
    let pellet = Pellet::new();
    let law = thermal_law("0.0").replace(" }", ", gas_conductivty = 0.3 }");
    let e = pellet.err(&[("laws.thermal", &law)]);
    assert!(e.contains("unknown parameter \"gas_conductivty\""), "{e}");
}

/// Regression: `[laws.thermal]` (and `[laws.contact]`) in a thermal-only pellet scene
/// (`[model] mechanics = false`) were passed over: the scene ran with the gap conductance of
/// `[gap]`. They are refused, naming the table.
#[test]
fn the_thermal_pellet_refuses_laws_by_name() {
    let base = PELLET.replace("[model]\n", "[model]\nmechanics = false\n");
    assert!(PelletScene::from_toml(&base).is_ok());
    for (table, law) in [
        ("thermal", thermal_law("1e-4")),
        ("contact", contact_law("5e-6")),
    ] {
        let text = format!("{base}\n[laws]\n{table} = {law}\n");
        let e = PelletScene::from_toml(&text).unwrap_err().to_string();
        assert!(
            e.contains(&format!("laws.{table} with model.mechanics = false")),
            "{e}"
        );
    }
    // Regression: the heat-only scene took `[solver] backend = "petsc"` and solved directly.
    let text = format!("{base}\n[solver]\nbackend = \"petsc\"\n");
    let e = PelletScene::from_toml(&text).unwrap_err().to_string();
    // (A build without PETSc may refuse the backend itself first.)
    let without = !mortar::petsc::is_built() && e.contains("--features petsc");
    assert!(
        without || e.contains("solver.backend = \"petsc\" with model.mechanics = false"),
        "{e}"
    );
    let text = format!("{base}\n[solver]\nbackend = \"direct\"\n");
    assert!(PelletScene::from_toml(&text).is_ok());
}
