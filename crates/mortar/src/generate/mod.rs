//! Built-in meshes: structured surfaces for the default scene, tests and benchmarks, and
//! volume meshes of bodies for the physics.
//!
//! Every surface generator numbers nodes from `first_node_tag` and faces from 1, and orients
//! faces so that the normal points along `normal` (for planes) or outward (for cylinders);
//! `flip` reverses it, as the master side of a tied interface usually wants.
//!
//! Volume generators ([`rectangle_mesh`], [`box_mesh`], and the O-grids [`ball_mesh`] and
//! [`box_with_hole_mesh`] of a curved inclusion, [`grid_rectangle_mesh`] and
//! [`grid_box_mesh`] on given (e.g. [`graded_points`]) coordinates, [`quarter_disc_mesh`], a
//! quarter disc refined towards a point of its rim for a cylinder in contact,
//! [`ball_octant_mesh`], its 3D counterpart for a sphere, [`quarter_annulus_mesh`], and
//! [`extrude_mesh`], a Quad4 mesh swept along z into Hex8; [`second_order_mesh`] raises any of
//! them to second order, curving the cells onto a sphere with [`onto_sphere`] or a cylinder
//! with [`onto_cylinder`])
//! number nodes from `first_node_tag` and cells from 1, all cells positively oriented; their
//! boundary surfaces come from
//! [`VolumeMesh::boundary_surface`](mortar_fem::VolumeMesh::boundary_surface).

mod ball_octant;
mod cylinder;
mod disc;
mod extrude;
mod inclusion;
mod line;
mod plane;
mod second_order;
mod sphere;
mod volume;

pub use ball_octant::ball_octant_mesh;
pub use cylinder::cylinder_surface;
pub use disc::{quarter_annulus_mesh, quarter_disc_mesh};
pub use extrude::extrude_mesh;
pub use inclusion::{ball_mesh, box_with_hole_mesh, Inclusion};
pub use line::{half_circle_mesh, line_mesh};
pub use plane::{square_quads, square_triangles, Diagonal};
pub use second_order::{onto_cylinder, onto_sphere, second_order_mesh, SecondOrder};
pub use sphere::sphere_surface;
pub use volume::{
    box_mesh, graded_points, grid_box_mesh, grid_rectangle_mesh, rectangle_mesh, CellShape,
};
