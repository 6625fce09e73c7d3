//! How far the search's boxes reach beyond their faces' nodes.
//!
//! A master face must be a candidate of every slave face it overlaps in the strategy's
//! projection, with a projection distance within the search radius. Two facts make a box
//! computed from the nodes alone enough:
//!
//! - A face whose shape functions are non-negative and sum to one (the two-node line, the
//!   linear triangle, the bilinear quad, warped or not) lies in the convex hull of its nodes,
//!   so in their box. A higher-order face bulges out of its nodes' hull (its shape functions
//!   change sign).
//! - The strategies move a slave point `x` of the face to a master point `y` along a direction
//!   of the projector's field on the face (the 2D segmentation and the element-based
//!   integration at `x` itself, the 3D auxiliary plane at the face's centre), by a distance
//!   of at most the search radius `r`. Where each such direction is that of a convex
//!   combination `d` of the face's nodal normals `n_i`
//!   ([`ProjectorFastPaths::within_nodal_normals`]), `d` is no shorter than
//!   `c = min_i n_i . u` (`u` the normals' mean direction; 1 where they are one), so
//!   `y = x + t d` with `|t| <= r / c`: `y` lies in `hull(x_i) + (r / c) hull(+-n_i)`, whose
//!   box is the box of the nodes widened on each axis by `(r / c) max_i |n_i|` on that axis
//!   (and by at most `r`); in 2D, where `d` is taken at `x` itself with the same weights, in
//!   the smaller `hull(x_i +- (r / c) n_i)`. (Normals that fan out by a right angle or more
//!   bound nothing: the nodes' box is widened by `r` on every axis.)
//!
//! Where both hold for every face type of a side, that side's boxes get no inflation, only a
//! margin for the rounding of their own arithmetic; elsewhere they are inflated by
//! [`Tolerances::search_inflation`] of the face's diameter, as a heuristic margin for the
//! bulge of curved faces and the directions of a projector that does not bound them. The
//! coupling reports which ([`CouplingStats::slave_box_inflation`]).
//!
//! [`ProjectorFastPaths::within_nodal_normals`]:
//!     crate::projector::ProjectorFastPaths::within_nodal_normals
//! [`Tolerances::search_inflation`]: crate::tolerances::Tolerances::search_inflation
//! [`CouplingStats::slave_box_inflation`]: crate::CouplingStats::slave_box_inflation

use crate::element::flat::{is_bilinear_quad, is_linear_triangle};
use crate::element::ElementRef;
use crate::integration::segments_2d::is_linear_line;
use crate::interface::Interface;
use crate::projector::Projector;

/// Whether every face of type `element` lies in the convex hull of its nodes: its shape
/// functions are those of the two-node line, the linear triangle or the bilinear quad
/// (non-negative, summing to one), checked at sample points.
pub fn in_hull_of_nodes(element: ElementRef) -> bool {
    is_linear_line(element) || is_linear_triangle(element) || is_bilinear_quad(element)
}

/// The inflation of the search's boxes, as fractions of each face's diameter: zero on a side
/// whose nodes bound what the search must find (see the module's documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Padding {
    /// Of the slave faces' search boxes.
    pub slave: f64,
    /// Of the master faces' boxes.
    pub master: f64,
}

impl Padding {
    /// The padding of `interface`'s search for a coupling that projects with `projector`.
    /// Without a projector (a search on its own, [`MasterTree::build`](super::MasterTree::build)),
    /// the slave side is inflated.
    pub fn of(interface: &Interface, projector: Option<&dyn Projector>) -> Self {
        let inflation = interface.tolerances().search_inflation;
        let (slave, master) = (interface.slave(), interface.master());
        let master_bound = master.element_types().iter().all(|&e| in_hull_of_nodes(e));
        let slave_bound = projector.and_then(Projector::fast_paths).is_some_and(|p| {
            slave
                .element_types()
                .iter()
                .all(|&e| in_hull_of_nodes(e) && p.within_nodal_normals(e))
        });
        Self {
            slave: if slave_bound { 0.0 } else { inflation },
            master: if master_bound { 0.0 } else { inflation },
        }
    }
}
