//! The data of a [`GapThermoMechanics`](super::GapThermoMechanics)'s interfaces: a contact
//! pair besides the gap, the view of one interface the residual takes, the gas-filled
//! interfaces' sums, and the gap's nodal values and gas columns.

use crate::contact::{NormalGap, SlaveSurfaceMeasures};
use crate::tied::Tie;

/// A contact pair between parts of the problem's bodies other than the gap
/// ([`GapThermoMechanics::with_contact_pair`]): its tie, normal gap, slave surface measures
/// and laws. The gas does not fill it: its surfaces carry the contact law's pressure alone,
/// and its volume is not the plenum's.
#[derive(Debug, Clone)]
pub(crate) struct ContactPair<TL, ML> {
    pub tie: Tie,
    pub gap: NormalGap,
    pub surface: SlaveSurfaceMeasures,
    pub thermal_law: TL,
    pub contact_law: ML,
    /// The bodies of the slave and master sides (0 or 1).
    pub bodies: [usize; 2],
}

/// One interface as the residual sees it.
pub(crate) struct InterfaceView<'a, TL, ML> {
    pub tie: &'a Tie,
    pub gap: &'a NormalGap,
    pub surface: &'a SlaveSurfaceMeasures,
    pub thermal_law: &'a TL,
    pub contact_law: &'a ML,
    pub bodies: [usize; 2],
    /// The row weights `w_j` (row sums of D).
    pub weights: &'a [f64],
    /// Whether the gas fills it (its volume and temperature in the plenum's law).
    pub gas: bool,
    /// The first flux and the first pressure unknown.
    pub offsets: [usize; 2],
}

/// The gas-filled interfaces' sums: length `L = sum w_j`, volume, `sum w_j Tbar_j`, and the
/// sparse derivatives of the volume (displacements) and of the temperature sum.
#[derive(Debug, Default)]
pub(crate) struct GasSums {
    pub length: f64,
    pub volume: f64,
    pub t_sum: f64,
    pub dvolume: Vec<(usize, f64)>,
    pub dtemp: Vec<(usize, f64)>,
}

/// The nodal gaps `(g~_0 - N u)_j / w_j` (m) of `gap` at the displacements `u` (in the
/// state's unit `unit`).
pub(crate) fn nodal_gaps(gap: &NormalGap, u: &[f64], unit: f64) -> Vec<f64> {
    gap.matrix
        .outer_iterator()
        .enumerate()
        .map(|(j, row)| {
            let nu: f64 = row.iter().map(|(k, v)| v * (u[k] * unit)).sum();
            (gap.initial[j] - nu) / gap.weights[j]
        })
        .collect()
}

/// The gas volume over a slave node of weight `w`, nodal gap `g` and curvature `kappa`:
/// `w g (1 + kappa g / 2)` where open, zero where closed.
pub(crate) fn gap_column(w: f64, g: f64, kappa: f64) -> f64 {
    if g > 0.0 {
        w * g * (1.0 + 0.5 * kappa * g)
    } else {
        0.0
    }
}
