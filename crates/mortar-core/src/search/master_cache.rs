//! The master faces of the fast paths (the 1D merge with its fused kernel, the 3D closed form)
//! as those paths read them, kept per worker in a small direct-mapped cache by slot: a master
//! face is met by the searches of several neighbouring slave faces (two or three in the 1D
//! merge, about nine on a 3D interface whose master is finer), and reading it from the mesh
//! each time (its face view, its nodes, its columns, and in 2D its box and its normal through
//! the element type) cost more than the arithmetic done with it.

use nalgebra::{Vector2, Vector3};

use super::bvh::Box3;
use super::candidates::points_box;
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::interface::{Interface, MasterFaces};

/// Entries of a cache: a power of two, more than the master faces a chunk of slave faces
/// meets, so that the faces met by consecutive slave faces rarely evict each other.
const WAYS: usize = 1024;

/// What a cache of master faces keeps of each face, read from the mesh once per worker.
pub(crate) trait MasterRead {
    /// Reads the face in slot `s` of `masters` (built for `interface`).
    fn read(interface: &Interface, masters: &MasterFaces, s: u32) -> Self;

    /// Replaces `self` by the face in slot `s` ([`read`](Self::read) in place: a cache's
    /// entries are refilled without moving a new value into them).
    fn reread(&mut self, interface: &Interface, masters: &MasterFaces, s: u32)
    where
        Self: Sized,
    {
        *self = Self::read(interface, masters, s);
    }
}

/// Master faces by slot, direct-mapped (`slot mod WAYS`): master faces of neighbouring slots
/// (the search's spatial order, or the chain order in 1D) do not collide.
#[derive(Debug, Clone)]
pub(crate) struct MasterCache<T> {
    entries: Vec<Option<(u32, T)>>,
}

impl<T> Default for MasterCache<T> {
    fn default() -> Self {
        Self {
            entries: Vec::new(),
        }
    }
}

impl<T: MasterRead> MasterCache<T> {
    /// The master face in slot `s` of `masters` (built for `interface`), read unless it is
    /// held.
    #[inline]
    pub(crate) fn get(&mut self, interface: &Interface, masters: &MasterFaces, s: u32) -> &T {
        if self.entries.is_empty() {
            self.entries.resize_with(WAYS, || None);
        }
        let e = &mut self.entries[s as usize & (WAYS - 1)];
        match e {
            Some((k, v)) => {
                if *k != s {
                    *k = s;
                    v.reread(interface, masters, s);
                }
            }
            None => *e = Some((s, T::read(interface, masters, s))),
        }
        match e {
            Some((_, v)) => v,
            None => unreachable!("filled above"),
        }
    }
}

/// One master line: what [`MasterFaces`] gives of the face in its slot, and what is computed
/// from that, with the same calls as where it is read uncached (so the same bits).
#[derive(Debug, Clone, Copy)]
pub(crate) struct MasterLine {
    /// The two node coordinates.
    pub nodes: [Vector3<f64>; 2],
    /// The box of the nodes (the search's `points_box`; a two-node line lies in it, so it is
    /// not inflated).
    pub bx: Box3,
    /// The unit normal at the centre, from the element type.
    pub normal: Vector3<f64>,
    /// The columns in M of the two nodes.
    pub cols: [u32; 2],
}

impl MasterRead for MasterLine {
    #[inline(never)]
    fn read(interface: &Interface, masters: &MasterFaces, s: u32) -> Self {
        let mut y = [Vector3::zeros(); MAX_FACE_NODES];
        let (el, k) = masters.coords_into(interface, s as usize, &mut y);
        debug_assert_eq!(k, 2, "a two-node line");
        let mut cols = [0u32; MAX_FACE_NODES];
        masters.columns_into(interface, s as usize, &mut cols);
        Self {
            nodes: [y[0], y[1]],
            bx: points_box(&y[..k], 0.0),
            normal: el.unit_normal(&y[..k], &Vector2::zeros()),
            cols: [cols[0], cols[1]],
        }
    }
}

/// The master lines of the 1D merge, by slot ([`MasterFaces`] in chain order: the lines met
/// by consecutive slave faces have consecutive slots).
pub(crate) type MasterLineCache = MasterCache<MasterLine>;

/// One master face of three or four nodes (a triangle or a quad of the 3D closed forms): its
/// element type, node coordinates and columns in M, as [`MasterFaces`] gives them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MasterCorners {
    /// The element type.
    pub element: ElementRef,
    /// The node count, 3 or 4.
    pub count: usize,
    /// The node coordinates (the first `count`).
    pub nodes: [Vector3<f64>; 4],
    /// The columns in M of the nodes (the first `count`).
    pub cols: [u32; 4],
}

impl MasterRead for MasterCorners {
    #[inline(never)]
    fn read(interface: &Interface, masters: &MasterFaces, s: u32) -> Self {
        let mut nodes = [Vector3::zeros(); 4];
        let mut cols = [0u32; 4];
        let (element, k) = masters.corners_into(interface, s as usize, &mut nodes, &mut cols);
        debug_assert!(k == 3 || k == 4, "a three- or four-node face");
        Self {
            element,
            count: k.min(4),
            nodes,
            cols,
        }
    }

    #[inline(never)]
    fn reread(&mut self, interface: &Interface, masters: &MasterFaces, s: u32) {
        let (element, k) =
            masters.corners_into(interface, s as usize, &mut self.nodes, &mut self.cols);
        debug_assert!(k == 3 || k == 4, "a three- or four-node face");
        self.element = element;
        self.count = k.min(4);
    }
}

/// The master faces of the 3D closed forms, by slot.
pub(crate) type MasterCornersCache = MasterCache<MasterCorners>;
