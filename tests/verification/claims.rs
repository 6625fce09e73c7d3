//! The verification claims: every figure docs/verification.md states, with the bound of the
//! test that guards it, kept in one file (`claims.toml`, next to this one) that the guarding
//! tests read their bounds from and the page is generated from, so that a figure and its
//! guard cannot drift apart.
//!
//! The page is `template.md` (its prose and tables) with placeholders:
//!
//! - `{{id}}`: the claim's figure (a claim with one), `{{id[k]}}`: its `k`-th figure (from 0);
//! - `{{id|bound}}`: the bound its test asserts, for a figure stated with its guard or a
//!   check the page states by its bound;
//! - `{{json:FILE#/POINTER|FORMAT}}`: a number read from a JSON file under `docs/` (written by
//!   an example), `FORMAT` `.3` (fixed, 3 decimals) or `e1` (scientific, 1 decimal); the
//!   pointer may pick array elements by their fields (`/[case=line2d,threads=1]/pairs`), and
//!   the format may reduce, scale and style them (`min`, `/1e6`, `,`, `>=5e6`: see
//!   [`json_figure`]).
//!
//! A figure is a string as the page prints it (`5.8e-16`, `0.04%`) or a JSON reference
//! (`json:FILE#/POINTER|FORMAT`), so that the page prints the JSON's value and the check
//! compares that value with the bound. The page ends with a table of every claim, its
//! figures, its bound, the test that asserts it and the command that runs the test.
//!
//! The performance page, docs/performance.md, is `performance_template.md` (next to this
//! file) filled by the same placeholders, from the benchmarks' JSON files only
//! ([`render_performance`]).
//!
//! Included by each test binary that reads a bound (`claim("id").bound`), by
//! `tests/verification.rs` (the consistency checks), by `examples/verification_doc.rs`
//! (writes the verification page) and by `examples/performance_doc.rs` (writes the
//! performance page).

#![allow(dead_code)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use serde::Deserialize;

/// The data file, compiled in so that a test reads its bound without a path.
const CLAIMS: &str = include_str!("claims.toml");
/// The page's prose and tables, with placeholders.
const TEMPLATE: &str = include_str!("template.md");
/// The performance page's prose and tables, with placeholders (JSON figures only).
const PERFORMANCE_TEMPLATE: &str = include_str!("performance_template.md");

/// How a claim's figures relate to its bound.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// An error relative to a scale the claim names: the figures are at most the bound.
    Relative,
    /// An error in the unit the claim names: the figures are at most the bound.
    Absolute,
    /// A quantity the test requires to be large (a fall of an error, a rate of convergence):
    /// the figures are at least the bound.
    Least,
    /// A convergence rate: the bound is the least rate the test accepts, and the figures lie
    /// within `tolerance` above it.
    Rate,
}

/// One verified figure (or several measured by one check) and the bound of its guard.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Claim {
    /// Key the template and the tests name the claim by.
    pub id: String,
    /// The page's section it belongs to.
    pub section: String,
    /// What is measured, in a few words.
    pub title: String,
    /// The reference the figure is measured against (closed form, literature, computation).
    pub source: String,
    /// The guarding test as `tests/FILE.rs::function` (or `examples/FILE.rs::function`).
    pub test: String,
    /// The command that reproduces the figures, when it is not the test's own command.
    #[serde(default)]
    pub command: Option<String>,
    /// The figures as the page prints them, or JSON references.
    #[serde(default)]
    pub figures: Vec<String>,
    /// The bound the test asserts (the least rate, for a rate).
    pub bound: f64,
    /// How the figures relate to the bound.
    pub kind: Kind,
    /// For a rate: how far above the bound the figures may lie.
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// The bound is asserted by the test with a literal, not read from here (an example's own
    /// check, which the test binaries do not compile with this module).
    #[serde(default)]
    pub literal: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    claim: Vec<Claim>,
}

/// Every claim, in the data file's order.
pub fn claims() -> &'static [Claim] {
    static CELL: OnceLock<Vec<Claim>> = OnceLock::new();
    CELL.get_or_init(|| {
        toml::from_str::<File>(CLAIMS)
            .unwrap_or_else(|e| panic!("tests/verification/claims.toml: {e}"))
            .claim
    })
}

/// The claim `id`.
///
/// # Panics
///
/// When the data file holds no claim `id`.
pub fn claim(id: &str) -> &'static Claim {
    claims()
        .iter()
        .find(|c| c.id == id)
        .unwrap_or_else(|| panic!("no claim {id:?} in tests/verification/claims.toml"))
}

/// The repository's root (the `mortar` package's folder).
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

impl Claim {
    /// The command that runs the guarding test (or the claim's own command): the test binary
    /// filtered to the test function, or to its file's module when the function is a helper.
    pub fn command(&self) -> String {
        if let Some(c) = &self.command {
            return c.clone();
        }
        let (file, function) = self.test.split_once("::").unwrap_or((&self.test, ""));
        let mut parts = file.trim_end_matches(".rs").split('/').skip(1);
        let binary = parts.next().unwrap_or(file);
        let module = parts.next().unwrap_or("");
        let is_test = std::fs::read_to_string(root().join(file)).is_ok_and(|text| {
            text.split(&format!("fn {function}("))
                .next()
                .is_some_and(|before| {
                    before
                        .lines()
                        .rev()
                        .map(str::trim)
                        .find(|l| !l.starts_with("///") && !l.is_empty())
                        .is_some_and(|l| l == "#[test]")
                })
        });
        let filter = if is_test {
            format!("{module}::{function}")
        } else {
            format!("{module}::")
        };
        format!("cargo test --release --test {binary} {filter}")
    }

    /// The `k`-th figure as the page prints it.
    ///
    /// # Errors
    ///
    /// When a JSON reference does not resolve.
    pub fn figure_text(&self, k: usize) -> Result<String, String> {
        let f = self
            .figures
            .get(k)
            .ok_or_else(|| format!("{}: no figure {k}", self.id))?;
        match f.strip_prefix("json:") {
            Some(reference) => json_figure(reference).map(|(text, _)| text),
            None => Ok(f.clone()),
        }
    }

    /// The `k`-th figure's value (a percentage as a fraction).
    ///
    /// # Errors
    ///
    /// When the figure is not a number or a JSON reference does not resolve.
    pub fn figure_value(&self, k: usize) -> Result<f64, String> {
        let text = self.figure_text(k)?;
        let (number, scale) = match text.strip_suffix('%') {
            Some(n) => (n, 0.01),
            None => (text.as_str(), 1.0),
        };
        number
            .trim_start_matches('+')
            .parse::<f64>()
            .map(|v| v * scale)
            .map_err(|e| format!("{}: figure {text:?}: {e}", self.id))
    }

    /// Whether the figures are percentages.
    fn percent(&self) -> bool {
        self.figures.iter().any(|f| f.ends_with('%'))
    }

    /// The bound as the page prints it: a rate as it is, a percentage in percent, anything
    /// else in scientific notation.
    pub fn bound_text(&self) -> String {
        match self.kind {
            Kind::Rate | Kind::Least => format!("{}", self.bound),
            _ if self.percent() => format!("{}%", trim(&format!("{:.6}", self.bound * 100.0))),
            _ => format!("{:e}", self.bound),
        }
    }
}

/// A decimal without its trailing zeros.
fn trim(s: &str) -> String {
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Reads `FILE#POINTER|FORMAT` from `docs/FILE`: the figure as printed and its value (after
/// any scales; NaN for a string).
///
/// `POINTER` is a JSON pointer whose segments may also be selectors, `[KEY=V,KEY!=V,KEY>=V,
/// KEY<=V]`, which keep the elements of an array that meet every condition (`KEY` a pointer
/// within the element without its leading slash, numbers compared as numbers; `[]` keeps
/// every element). `FORMAT` is words separated by spaces: first, where the pointer selects
/// several values, `min`, `max` or `count`; then any scales, `*K` or `/K` (`K` a number, or
/// `json:FILE#POINTER` for one value); last the style: `.N` (fixed, `N` decimals), `eN`
/// (scientific, `N` decimals), `,` (a whole number with thousands separators), `text` (a
/// string as it is), or `>=K` / `<=K` (`met` or `not met`).
fn json_figure(reference: &str) -> Result<(String, f64), String> {
    let (location, format) = reference
        .split_once('|')
        .ok_or_else(|| format!("json:{reference}: no |FORMAT"))?;
    json_values(location)
        .and_then(|values| format_values(&values, format))
        .map_err(|e| format!("json:{reference}: {e}"))
}

/// The values `FILE#POINTER` selects in `docs/FILE`.
fn json_values(location: &str) -> Result<Vec<serde_json::Value>, String> {
    let (file, pointer) = location
        .split_once('#')
        .ok_or_else(|| "no #POINTER".to_string())?;
    static CACHE: OnceLock<std::sync::Mutex<BTreeMap<String, serde_json::Value>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    let mut cache = cache.lock().unwrap_or_else(|e| e.into_inner());
    if !cache.contains_key(file) {
        let path = root().join("docs").join(file);
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        cache.insert(file.to_string(), value);
    }
    Ok(select(&cache[file], pointer)?
        .into_iter()
        .cloned()
        .collect())
}

/// The values `pointer` reaches from `root`: one through plain segments, any number through
/// a selector (see [`json_figure`]).
///
/// # Errors
///
/// When a plain segment names no member or index, or a selector meets what is not an array.
pub fn select<'a>(
    root: &'a serde_json::Value,
    pointer: &str,
) -> Result<Vec<&'a serde_json::Value>, String> {
    let rest = pointer
        .strip_prefix('/')
        .ok_or_else(|| format!("pointer {pointer:?} does not start with /"))?;
    // Split at the slashes outside brackets: a selector's keys are pointers too.
    let mut segments = Vec::new();
    let (mut depth, mut from) = (0usize, 0);
    for (i, c) in rest.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            '/' if depth == 0 => {
                segments.push(&rest[from..i]);
                from = i + 1;
            }
            _ => {}
        }
    }
    segments.push(&rest[from..]);
    let mut values = vec![root];
    for segment in segments {
        let mut next = Vec::new();
        for value in values {
            if let Some(conditions) = segment.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
                let items = value
                    .as_array()
                    .ok_or_else(|| format!("{segment}: not an array"))?;
                for item in items {
                    if meets(item, conditions)? {
                        next.push(item);
                    }
                }
            } else {
                let key = segment.replace("~1", "/").replace("~0", "~");
                let child = match value {
                    serde_json::Value::Array(items) => {
                        key.parse::<usize>().ok().and_then(|k| items.get(k))
                    }
                    other => other.get(&key),
                };
                next.push(child.ok_or_else(|| format!("nothing at {segment:?}"))?);
            }
        }
        values = next;
    }
    Ok(values)
}

/// Whether `item` meets every condition of a selector's `KEY=V,KEY>=V,...`.
fn meets(item: &serde_json::Value, conditions: &str) -> Result<bool, String> {
    for condition in conditions.split(',').filter(|c| !c.trim().is_empty()) {
        let (key, op, wanted) = ["!=", ">=", "<=", "="]
            .iter()
            .find_map(|op| condition.split_once(op).map(|(k, v)| (k, *op, v.trim())))
            .ok_or_else(|| format!("[{conditions}]: {condition:?} is not KEY=V, !=, >= or <="))?;
        let Some(found) = item.pointer(&format!("/{}", key.trim())) else {
            return Ok(false);
        };
        let numbers = found.as_f64().zip(wanted.parse::<f64>().ok());
        let equal = match (numbers, found) {
            (Some((a, b)), _) => a == b,
            (None, serde_json::Value::String(s)) => s == wanted,
            (None, serde_json::Value::Bool(b)) => wanted.parse() == Ok(*b),
            (None, serde_json::Value::Null) => wanted == "null",
            (None, _) => false,
        };
        let holds = match op {
            "=" => equal,
            "!=" => !equal,
            ">=" => numbers.is_some_and(|(a, b)| a >= b),
            _ => numbers.is_some_and(|(a, b)| a <= b),
        };
        if !holds {
            return Ok(false);
        }
    }
    Ok(true)
}

/// `values` as `format` prints them (see [`json_figure`]), and the value printed.
///
/// # Errors
///
/// When the format is not understood, or the values are not one number (or several, reduced).
pub fn format_values(values: &[serde_json::Value], format: &str) -> Result<(String, f64), String> {
    let words: Vec<&str> = format.split_whitespace().collect();
    let (style, steps) = words
        .split_last()
        .ok_or_else(|| "empty format".to_string())?;
    let (reducer, scales) = match steps.split_first() {
        Some((&r @ ("min" | "max" | "count"), scales)) => (Some(r), scales),
        _ => (None, steps),
    };
    let number = |v: &serde_json::Value| v.as_f64().ok_or_else(|| format!("{v} is not a number"));
    // A scale's or a verdict's K: a number, or one number from a JSON file.
    let operand = |k: &str| match k.strip_prefix("json:") {
        Some(location) => match json_values(location)?.as_slice() {
            [v] => number(v),
            vs => Err(format!("{k}: {} values, not one", vs.len())),
        },
        None => k
            .parse::<f64>()
            .map_err(|_| format!("{k:?} is not a number")),
    };
    if *style == "text" {
        return match (reducer, scales, values) {
            (None, [], [serde_json::Value::String(s)]) => Ok((s.clone(), f64::NAN)),
            _ => Err("text: one string, without min, max, count or scales".to_string()),
        };
    }
    let mut value = match (reducer, values) {
        (Some("count"), _) => values.len() as f64,
        (Some(r), [first, rest @ ..]) => rest.iter().try_fold(number(first)?, |acc, v| {
            let v = number(v)?;
            Ok::<_, String>(if r == "min" { acc.min(v) } else { acc.max(v) })
        })?,
        (Some(r), []) => return Err(format!("{r} of nothing: the selector keeps no element")),
        (None, [v]) => number(v)?,
        (None, _) => {
            return Err(format!(
                "{} values: select one, or reduce them with min, max or count",
                values.len()
            ))
        }
    };
    for scale in scales {
        let (multiply, k) = match (scale.strip_prefix('*'), scale.strip_prefix('/')) {
            (Some(k), _) => (true, k),
            (_, Some(k)) => (false, k),
            _ => return Err(format!("{scale:?}: neither a reducer nor a scale *K or /K")),
        };
        let k = operand(k)?;
        value = if multiply { value * k } else { value / k };
    }
    let digits = |d: &str| d.parse::<usize>().map_err(|_| format!("style {style:?}"));
    let text = if let Some(d) = style.strip_prefix('.') {
        let d = digits(d)?;
        format!("{value:.d$}")
    } else if let Some(d) = style.strip_prefix('e') {
        let d = digits(d)?;
        format!("{value:.d$e}")
    } else if *style == "," {
        grouped(value)
    } else if let Some((at_least, k)) = style
        .strip_prefix(">=")
        .map(|k| (true, k))
        .or_else(|| style.strip_prefix("<=").map(|k| (false, k)))
    {
        let k = operand(k)?;
        let met = if at_least { value >= k } else { value <= k };
        if met { "met" } else { "not met" }.to_string()
    } else {
        return Err(format!("style {style:?}"));
    };
    Ok((text, value))
}

/// `value` rounded to a whole number, with commas between thousands.
fn grouped(value: f64) -> String {
    let digits = format!("{:.0}", value.abs());
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    if value.round() < 0.0 {
        format!("-{out}")
    } else {
        out
    }
}

/// A placeholder of the template: what it prints.
enum Slot<'a> {
    Figure(&'a Claim, usize),
    Bound(&'a Claim),
    Json(&'a str),
}

fn slot(key: &str) -> Result<Slot<'_>, String> {
    if let Some(reference) = key.strip_prefix("json:") {
        return Ok(Slot::Json(reference));
    }
    let find = |id: &str| {
        claims()
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("{{{{{key}}}}}: no claim {id:?}"))
    };
    if let Some(id) = key.strip_suffix("|bound") {
        return Ok(Slot::Bound(find(id)?));
    }
    if let Some((id, k)) = key.strip_suffix(']').and_then(|k| k.split_once('[')) {
        let k = k.parse().map_err(|_| format!("{{{{{key}}}}}: index"))?;
        return Ok(Slot::Figure(find(id)?, k));
    }
    let c = find(key)?;
    if c.figures.len() != 1 {
        return Err(format!(
            "{{{{{key}}}}}: {} figures, name one as {key}[k]",
            c.figures.len()
        ));
    }
    Ok(Slot::Figure(c, 0))
}

/// A template's placeholders, in order.
fn placeholders(template: &str) -> Result<Vec<(std::ops::Range<usize>, &str)>, String> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(start) = template[from..].find("{{") {
        let start = from + start;
        let end = template[start..]
            .find("}}")
            .map(|e| start + e + 2)
            .ok_or_else(|| format!("unclosed {{{{ at byte {start}"))?;
        out.push((start..end, &template[start + 2..end - 2]));
        from = end;
    }
    Ok(out)
}

/// `template` (the file `name` next to this one) with its placeholders filled.
///
/// # Errors
///
/// When a placeholder names no claim or figure, or a JSON reference does not resolve: the
/// template's line and the reason.
fn fill(name: &str, template: &str) -> Result<String, String> {
    let mut page = String::new();
    let mut at = 0;
    let slots = placeholders(template).map_err(|e| format!("tests/verification/{name}: {e}"))?;
    for (range, key) in slots {
        page.push_str(&template[at..range.start]);
        let text = slot(key).and_then(|s| match s {
            Slot::Figure(c, k) => c.figure_text(k),
            Slot::Bound(c) => Ok(c.bound_text()),
            Slot::Json(reference) => json_figure(reference).map(|(text, _)| text),
        });
        page.push_str(&text.map_err(|e| {
            let line = template[..range.start].matches('\n').count() + 1;
            format!("tests/verification/{name}:{line}: {e}")
        })?);
        at = range.end;
    }
    page.push_str(&template[at..]);
    Ok(page)
}

/// The verification page: the template with its placeholders filled, then the table of
/// every claim.
///
/// # Errors
///
/// When a placeholder names no claim or figure, or a JSON reference does not resolve.
pub fn render() -> Result<String, String> {
    Ok(fill("template.md", TEMPLATE)? + &table()?)
}

/// The performance page: its template with the benchmarks' figures filled in from their JSON
/// files under `docs/`.
///
/// # Errors
///
/// When a placeholder does not resolve.
pub fn render_performance() -> Result<String, String> {
    fill("performance_template.md", PERFORMANCE_TEMPLATE)
}

/// The closing table: every claim with its figures, bound, test and command.
fn table() -> Result<String, String> {
    let mut out = String::from(
        "\n## Every figure and its guard\n\n\
         Generated with the page from `tests/verification/claims.toml`, which the tests read \
         their bounds from: each claim's figures (as above), the bound its test asserts \
         (relative or absolute errors at most the bound; for a rate, the least rate \
         accepted), the test, and the command that runs it. `cargo run --example \
         verification_doc` writes this page; `cargo test --release --test verification` \
         fails when it differs from the data, or a bound strays from its figures.\n\n\
         | claim | figures | bound | test | command |\n| --- | --- | --- | --- | --- |\n",
    );
    for c in claims() {
        let figures = (0..c.figures.len())
            .map(|k| c.figure_text(k))
            .collect::<Result<Vec<_>, _>>()?;
        let figures = if figures.is_empty() {
            "—".to_string()
        } else {
            figures.join(", ")
        };
        let kind = match c.kind {
            Kind::Relative => "",
            Kind::Absolute => " (absolute)",
            Kind::Least => " (least)",
            Kind::Rate => " (least rate)",
        };
        let (file, function) = c.test.split_once("::").unwrap_or((&c.test, ""));
        out.push_str(&format!(
            "| {} | {figures} | {}{kind} | `{file}` `{function}` | `{}` |\n",
            cell(&c.title),
            c.bound_text(),
            cell(&c.command())
        ));
    }
    Ok(out)
}

/// Text for a table cell: its pipes escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// Everything wrong with the claims: a figure above its bound (below it, for a rate), a bound
/// more than 100 times its largest figure that the page does not state, a rate further above
/// its bound than its tolerance, a test that does not exist or does not read its bound from
/// here, a claim the page does not print, duplicate ids. Empty when all is well.
pub fn problems() -> Vec<String> {
    let mut out = Vec::new();
    let mut ids = BTreeSet::new();
    let slots = match placeholders(TEMPLATE) {
        Ok(p) => p,
        Err(e) => return vec![e],
    };
    let mut printed: BTreeSet<(String, Option<usize>)> = BTreeSet::new();
    for (_, key) in &slots {
        match slot(key) {
            Ok(Slot::Figure(c, k)) => {
                if k >= c.figures.len() {
                    out.push(format!(
                        "{{{{{key}}}}}: {} has {} figures",
                        c.id,
                        c.figures.len()
                    ));
                }
                printed.insert((c.id.clone(), Some(k)));
            }
            Ok(Slot::Bound(c)) => {
                printed.insert((c.id.clone(), None));
            }
            Ok(Slot::Json(_)) => {}
            Err(e) => out.push(e),
        }
    }
    for c in claims() {
        if !ids.insert(c.id.as_str()) {
            out.push(format!("{}: duplicate id", c.id));
        }
        let states_bound = printed.contains(&(c.id.clone(), None));
        if c.figures.is_empty() && !states_bound {
            out.push(format!(
                "{}: no figure and the page does not state its bound",
                c.id
            ));
        }
        for k in 0..c.figures.len() {
            if !printed.contains(&(c.id.clone(), Some(k))) {
                out.push(format!("{}: the page does not print figure {k}", c.id));
            }
        }
        out.extend(problems_of(c, states_bound));
    }
    out
}

/// What is wrong with one claim's figures, bound and test; `states_bound` says whether the
/// page prints the bound.
pub fn problems_of(c: &Claim, states_bound: bool) -> Vec<String> {
    let mut out = check_test(c);
    if !(c.bound.is_finite() && c.bound > 0.0) {
        out.push(format!("{}: bound {} not positive", c.id, c.bound));
    }
    let mut largest = 0.0f64;
    for k in 0..c.figures.len() {
        let v = match c.figure_value(k) {
            Ok(v) => v.abs(),
            Err(e) => {
                out.push(e);
                continue;
            }
        };
        largest = largest.max(v);
        match c.kind {
            Kind::Relative | Kind::Absolute => {
                if v > c.bound {
                    out.push(format!(
                        "{}: figure {v:e} above its bound {:e}",
                        c.id, c.bound
                    ));
                }
            }
            Kind::Least => {
                if v < c.bound {
                    out.push(format!("{}: figure {v} below its bound {}", c.id, c.bound));
                }
                if v > 100.0 * c.bound && !states_bound {
                    out.push(format!(
                        "{}: figure {v} more than 100 times its bound {}, and the page \
                         does not state the bound",
                        c.id, c.bound
                    ));
                }
            }
            Kind::Rate => {
                let tol = c.tolerance.unwrap_or(0.0);
                if v < c.bound || v > c.bound + tol {
                    out.push(format!(
                        "{}: rate {v} not within [{}, {} + {tol}]",
                        c.id, c.bound, c.bound
                    ));
                }
            }
        }
    }
    match c.kind {
        Kind::Rate => {
            if c.tolerance.is_none_or(|t| !(t > 0.0 && t <= 0.2)) {
                out.push(format!("{}: a rate needs a tolerance in (0, 0.2]", c.id));
            }
        }
        Kind::Least => {
            if c.tolerance.is_some() {
                out.push(format!(
                    "{}: a tolerance on a claim that is not a rate",
                    c.id
                ));
            }
        }
        Kind::Relative | Kind::Absolute => {
            if c.tolerance.is_some() {
                out.push(format!(
                    "{}: a tolerance on a claim that is not a rate",
                    c.id
                ));
            }
            if !c.figures.is_empty() && c.bound > 100.0 * largest && !states_bound {
                out.push(format!(
                    "{}: bound {:e} more than 100 times the largest figure {largest:e}, and \
                     the page does not state it",
                    c.id, c.bound
                ));
            }
        }
    }
    out
}

/// The claim's test exists, and reads its bound from here unless it is marked literal.
fn check_test(c: &Claim) -> Vec<String> {
    let Some((file, function)) = c.test.split_once("::") else {
        return vec![format!("{}: test {:?} is not FILE::function", c.id, c.test)];
    };
    let path: &Path = file.as_ref();
    let Ok(text) = std::fs::read_to_string(root().join(path)) else {
        return vec![format!("{}: no file {file}", c.id)];
    };
    let mut out = Vec::new();
    if !text.contains(&format!("fn {function}(")) {
        out.push(format!("{}: no fn {function} in {file}", c.id));
    }
    if c.literal && !text.contains(&c.bound_text()) {
        out.push(format!(
            "{}: {file} does not assert {}",
            c.id,
            c.bound_text()
        ));
    }
    let reads = text.contains(&format!("claim(\"{}\")", c.id));
    if reads == c.literal {
        out.push(if c.literal {
            format!("{}: marked literal, but {file} reads it", c.id)
        } else {
            format!(
                "{}: {file} does not read its bound (claim(\"{}\"))",
                c.id, c.id
            )
        });
    }
    out
}
