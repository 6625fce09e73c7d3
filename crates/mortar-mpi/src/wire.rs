//! The faces and rows that ranks send each other, as bytes: `Faces` (faces with their nodes'
//! tags and coordinates, free of any mesh's numbering) and the little-endian `Writer` and
//! `Reader` they are written with.

use mortar_core::element::ElementRef;
use mortar_core::mesh::SurfaceMesh;
use mortar_elements::ElementRegistry;

use crate::error::{DistributedError, Result};

/// Marks a message of faces.
const FACES: u32 = 0x4d46_4143;

/// Appends little-endian values to a buffer.
#[derive(Debug, Default)]
pub(crate) struct Writer {
    pub(crate) bytes: Vec<u8>,
}

impl Writer {
    pub(crate) fn u32(&mut self, v: u32) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    pub(crate) fn u64(&mut self, v: u64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    pub(crate) fn f64(&mut self, v: f64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    pub(crate) fn str(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.bytes.extend_from_slice(s.as_bytes());
    }
}

/// Reads what a [`Writer`] wrote; every read checks the length (a short message is an error
/// naming the sender, not a panic).
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    rank: usize,
    from: usize,
}

impl<'a> Reader<'a> {
    /// A reader of `bytes`, which rank `from` sent to rank `rank`.
    pub(crate) fn new(bytes: &'a [u8], rank: usize, from: usize) -> Self {
        Self {
            bytes,
            at: 0,
            rank,
            from,
        }
    }
    pub(crate) fn malformed(&self, what: &'static str) -> DistributedError {
        DistributedError::Malformed {
            rank: self.rank,
            from: self.from,
            what,
        }
    }
    fn take<const N: usize>(&mut self) -> Result<[u8; N]> {
        let end = self.at + N;
        let Some(b) = self.bytes.get(self.at..end) else {
            return Err(self.malformed("truncated"));
        };
        self.at = end;
        Ok(b.try_into().expect("N bytes"))
    }
    pub(crate) fn u32(&mut self) -> Result<u32> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    pub(crate) fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(self.take()?))
    }
    pub(crate) fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(self.take()?))
    }
    pub(crate) fn str(&mut self) -> Result<String> {
        let n = self.u32()? as usize;
        let Some(b) = self.bytes.get(self.at..self.at + n) else {
            return Err(self.malformed("truncated"));
        };
        self.at += n;
        String::from_utf8(b.to_vec()).map_err(|_| self.malformed("a name that is not UTF-8"))
    }
    pub(crate) fn is_done(&self) -> bool {
        self.at == self.bytes.len()
    }
}

/// Faces with their nodes' tags and coordinates, in no mesh's numbering.
#[derive(Debug, Clone, Default)]
pub(crate) struct Faces {
    pub(crate) tags: Vec<u64>,
    pub(crate) elements: Vec<ElementRef>,
    /// Face `f`'s nodes are `offsets[f]..offsets[f + 1]` of `node_tags` and `coords`.
    pub(crate) offsets: Vec<usize>,
    pub(crate) node_tags: Vec<u64>,
    pub(crate) coords: Vec<[f64; 3]>,
}

/// Faces to read and send: a rank's own surface mesh, or faces received.
pub(crate) trait FaceSource {
    /// The number of faces.
    fn len(&self) -> usize;
    /// Face `f`'s tag.
    fn tag(&self, f: usize) -> u64;
    /// Face `f`'s element type.
    fn element(&self, f: usize) -> ElementRef;
    /// Face `f`'s nodes: tags and coordinates.
    fn nodes(&self, f: usize) -> impl Iterator<Item = (u64, [f64; 3])> + '_;

    /// Face `f`'s nodes' bounding box.
    fn face_box(&self, f: usize) -> Bounds {
        let mut b = Bounds::EMPTY;
        for (_, x) in self.nodes(f) {
            b.add(x);
        }
        b
    }

    /// The faces `which` as a message: the element names once, then each face.
    fn write(&self, which: impl Iterator<Item = usize> + Clone) -> Vec<u8> {
        let mut names: Vec<&'static str> = Vec::new();
        for f in which.clone() {
            let name = self.element(f).name();
            if !names.contains(&name) {
                names.push(name);
            }
        }
        let mut w = Writer::default();
        w.u32(FACES);
        w.u32(names.len() as u32);
        for n in &names {
            w.str(n);
        }
        w.u64(which.clone().count() as u64);
        for f in which {
            w.u64(self.tag(f));
            let name = self.element(f).name();
            w.u32(names.iter().position(|n| *n == name).expect("listed") as u32);
            w.u32(self.nodes(f).count() as u32);
            for (t, x) in self.nodes(f) {
                w.u64(t);
                for c in x {
                    w.f64(c);
                }
            }
        }
        w.bytes
    }
}

impl FaceSource for SurfaceMesh {
    fn len(&self) -> usize {
        self.face_count()
    }
    fn tag(&self, f: usize) -> u64 {
        self.face(f).tag
    }
    fn element(&self, f: usize) -> ElementRef {
        self.face(f).element
    }
    fn nodes(&self, f: usize) -> impl Iterator<Item = (u64, [f64; 3])> + '_ {
        self.face(f).nodes.iter().map(|&n| {
            let x = self.coords()[n as usize];
            (self.node_tags()[n as usize], [x.x, x.y, x.z])
        })
    }
}

impl FaceSource for Faces {
    fn len(&self) -> usize {
        self.tags.len()
    }
    fn tag(&self, f: usize) -> u64 {
        self.tags[f]
    }
    fn element(&self, f: usize) -> ElementRef {
        self.elements[f]
    }
    fn nodes(&self, f: usize) -> impl Iterator<Item = (u64, [f64; 3])> + '_ {
        let r = self.offsets[f]..self.offsets[f + 1];
        self.node_tags[r.clone()]
            .iter()
            .copied()
            .zip(self.coords[r].iter().copied())
    }
}

impl Faces {
    pub(crate) fn push(
        &mut self,
        tag: u64,
        element: ElementRef,
        nodes: impl IntoIterator<Item = (u64, [f64; 3])>,
    ) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.tags.push(tag);
        self.elements.push(element);
        for (t, x) in nodes {
            self.node_tags.push(t);
            self.coords.push(x);
        }
        self.offsets.push(self.node_tags.len());
    }

    /// Appends the faces of a message that rank `from` sent to rank `rank`, their element
    /// types looked up by name in `elements`.
    pub(crate) fn read(
        &mut self,
        bytes: &[u8],
        rank: usize,
        from: usize,
        elements: &ElementRegistry,
    ) -> Result<()> {
        if bytes.is_empty() {
            return Ok(());
        }
        let mut r = Reader::new(bytes, rank, from);
        if r.u32()? != FACES {
            return Err(r.malformed("not a message of faces"));
        }
        let kinds = r.u32()? as usize;
        let mut types = Vec::with_capacity(kinds.min(256));
        for _ in 0..kinds {
            let name = r.str()?;
            match elements.by_name(&name) {
                Some(e) => types.push(e),
                None => {
                    return Err(DistributedError::UnknownElement { rank, from, name });
                }
            }
        }
        let count = r.u64()?;
        for _ in 0..count {
            let tag = r.u64()?;
            let kind = r.u32()? as usize;
            let Some(&element) = types.get(kind) else {
                return Err(r.malformed("an element index out of range"));
            };
            let n = r.u32()? as usize;
            if n != element.node_count() {
                return Err(r.malformed("a face whose node count is not its element's"));
            }
            let mut nodes = Vec::with_capacity(n);
            for _ in 0..n {
                let t = r.u64()?;
                nodes.push((t, [r.f64()?, r.f64()?, r.f64()?]));
            }
            self.push(tag, element, nodes);
        }
        if !r.is_done() {
            return Err(r.malformed("bytes after the last face"));
        }
        Ok(())
    }
}

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Bounds {
    pub(crate) lo: [f64; 3],
    pub(crate) hi: [f64; 3],
}

impl Bounds {
    /// The box of no point.
    pub(crate) const EMPTY: Bounds = Bounds {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    pub(crate) fn add(&mut self, x: [f64; 3]) {
        for k in 0..3 {
            self.lo[k] = self.lo[k].min(x[k]);
            self.hi[k] = self.hi[k].max(x[k]);
        }
    }

    pub(crate) fn union(&mut self, other: &Bounds) {
        self.add(other.lo);
        self.add(other.hi);
    }

    pub(crate) fn is_empty(&self) -> bool {
        (0..3).any(|k| self.lo[k] > self.hi[k])
    }

    /// The box grown by `by` on every side (an empty box stays empty).
    pub(crate) fn inflated(&self, by: f64) -> Bounds {
        if self.is_empty() {
            return *self;
        }
        Bounds {
            lo: self.lo.map(|v| v - by),
            hi: self.hi.map(|v| v + by),
        }
    }

    pub(crate) fn meets(&self, other: &Bounds) -> bool {
        !self.is_empty()
            && !other.is_empty()
            && (0..3).all(|k| self.lo[k] <= other.hi[k] && other.lo[k] <= self.hi[k])
    }

    /// The diagonal's length (0 for an empty box).
    pub(crate) fn diagonal(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        (0..3)
            .map(|k| (self.hi[k] - self.lo[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    pub(crate) fn write(&self, w: &mut Writer) {
        for v in self.lo.iter().chain(&self.hi) {
            w.f64(*v);
        }
    }

    pub(crate) fn read(r: &mut Reader<'_>) -> Result<Bounds> {
        let mut b = Bounds::EMPTY;
        for k in 0..3 {
            b.lo[k] = r.f64()?;
        }
        for k in 0..3 {
            b.hi[k] = r.f64()?;
        }
        Ok(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_elements::{LINE2, TRI3};

    fn two_faces() -> Faces {
        let mut f = Faces::default();
        f.push(
            7,
            &TRI3,
            [(1, [0.0; 3]), (2, [1.0, 0.0, 0.0]), (3, [0.0, 1.0, 0.0])],
        );
        f.push(9, &LINE2, [(4, [2.0; 3]), (5, [3.0; 3])]);
        f
    }

    #[test]
    fn faces_come_back_as_they_were_sent() {
        let sent = two_faces();
        let mut got = Faces::default();
        assert_eq!(sent.len(), 2);
        got.read(&sent.write(0..2), 1, 0, &ElementRegistry::new())
            .expect("read");
        assert_eq!(got.tags, sent.tags);
        assert_eq!(got.node_tags, sent.node_tags);
        assert_eq!(got.coords, sent.coords);
        assert_eq!(got.elements[1].name(), "Line2");
    }

    #[test]
    fn a_truncated_message_is_an_error_naming_its_sender() {
        let bytes = two_faces().write(0..2);
        for cut in [3, 12, bytes.len() - 1] {
            let err = Faces::default()
                .read(&bytes[..cut], 1, 2, &ElementRegistry::new())
                .expect_err("truncated");
            assert!(
                matches!(
                    err,
                    DistributedError::Malformed {
                        rank: 1,
                        from: 2,
                        ..
                    }
                ),
                "{err}"
            );
        }
    }

    #[test]
    fn an_element_the_registry_lacks_is_named() {
        // The sender's Tri3 renamed to an element no registry holds.
        let mut bytes = two_faces().write(0..2);
        let at = bytes.windows(4).position(|w| w == b"Tri3").expect("named");
        bytes[at + 3] = b'9';
        let err = Faces::default()
            .read(&bytes, 0, 3, &ElementRegistry::new())
            .expect_err("no Tri9");
        assert!(
            matches!(&err, DistributedError::UnknownElement { from: 3, name, .. } if name == "Tri9"),
            "{err}"
        );
    }
}
