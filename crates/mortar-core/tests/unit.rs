//! Unit tests of the element-free kernels of `mortar-core`: quadrature exactness, polygon
//! operations, convex clipping and the auxiliary plane (one binary, a folder of modules).

mod unit {
    mod clipping;
    mod plane;
    mod polygon;
    mod quadrature;
    pub mod strategies;
}
