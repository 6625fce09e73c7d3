//! Constraint laws: automatic tangents against finite differences, the limits of the gap
//! conductance, and the overflow safety of the exponential pressure.

mod laws {
    mod gap_limits;
    mod pressure;
    mod tangents;
}
