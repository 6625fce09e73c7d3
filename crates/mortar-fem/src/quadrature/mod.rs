//! Quadrature rules of the volume elements, [`VolumeQuadratureRule`], on triangles and
//! quadrilaterals (those of `mortar-core` in three coordinates), tetrahedra and hexahedra,
//! with their exact polynomial degree.

mod volume;

pub use volume::{max_volume_degree, VolumeQuadratureRule};
