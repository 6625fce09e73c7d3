//! The master lines of the 1D merge as the walk and the fused 2D kernel read them, kept per
//! worker in a small direct-mapped cache: each master line is met by the walks of two or
//! three consecutive slave faces and then by the kernel, and reading it from the mesh (its
//! face view, its nodes, its columns, its normal through the element type) each time cost
//! more than the arithmetic done with it.

use nalgebra::{Vector2, Vector3};

use super::bvh::Box3;
use super::candidates::points_box;
use crate::element::MAX_FACE_NODES;
use crate::interface::{Interface, MasterFaces};

/// One master line: what [`MasterFaces`] gives of the face in its slot, and what is computed
/// from that, with the same calls as where it is read uncached (so the same bits).
#[derive(Debug, Clone, Copy)]
pub(crate) struct MasterLine {
    /// The two node coordinates.
    pub nodes: [Vector3<f64>; 2],
    /// The inflated box of the nodes (the search's `points_box`).
    pub bx: Box3,
    /// The unit normal at the centre, from the element type.
    pub normal: Vector3<f64>,
    /// The columns in M of the two nodes.
    pub cols: [u32; 2],
}

/// Entries of the cache: a power of two, more than the master lines a chunk of slave faces
/// meets at a few master faces per slave face, so that a walk along the chains rarely
/// evicts a line it will read again.
const WAYS: usize = 1024;

/// Master lines by slot, direct-mapped (`slot mod WAYS`). Slots of one chain are consecutive
/// ([`MasterFaces`] in chain order), so the lines met by consecutive slave faces do not
/// collide.
#[derive(Debug, Clone, Default)]
pub(crate) struct MasterLineCache {
    /// Per entry, the slot it holds (`u32::MAX`: none).
    slot: Vec<u32>,
    line: Vec<MasterLine>,
}

impl MasterLineCache {
    /// The master line in slot `s` of `masters` (built for `interface`, every face a two-node
    /// line).
    #[inline]
    pub(crate) fn get(
        &mut self,
        interface: &Interface,
        masters: &MasterFaces,
        s: u32,
    ) -> &MasterLine {
        if self.slot.is_empty() {
            self.slot = vec![u32::MAX; WAYS];
            self.line = vec![
                MasterLine {
                    nodes: [Vector3::zeros(); 2],
                    bx: (Vector3::zeros(), Vector3::zeros()),
                    normal: Vector3::zeros(),
                    cols: [0; 2],
                };
                WAYS
            ];
        }
        let i = s as usize & (WAYS - 1);
        if self.slot[i] != s {
            self.line[i] = Self::read(interface, masters, s);
            self.slot[i] = s;
        }
        &self.line[i]
    }

    /// Reads the line in slot `s` from the mesh.
    #[inline(never)]
    fn read(interface: &Interface, masters: &MasterFaces, s: u32) -> MasterLine {
        let mut y = [Vector3::zeros(); MAX_FACE_NODES];
        let (el, k) = masters.coords_into(interface, s as usize, &mut y);
        debug_assert_eq!(k, 2, "a two-node line");
        let mut cols = [0u32; MAX_FACE_NODES];
        masters.columns_into(interface, s as usize, &mut cols);
        MasterLine {
            nodes: [y[0], y[1]],
            bx: points_box(&y[..k], interface.tolerances()),
            normal: el.unit_normal(&y[..k], &Vector2::zeros()),
            cols: [cols[0], cols[1]],
        }
    }
}
