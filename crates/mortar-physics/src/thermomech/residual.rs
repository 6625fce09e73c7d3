//! The residual and Jacobian of a [`GapThermoMechanics`]: heat conduction in the bodies,
//! their elasticity (with the axial balance of generalized plane strain), the interfaces,
//! the gas pressure, the prescribed values and the free plane ends.

use mortar_core::linalg::{SparseMatrix, Triplets};

use super::pair::GasSums;
use super::plenum::GasPressure;
use super::problem::{
    Axial, AxialFreedom, GapThermoMechanics, TimedEigenstrain, AXIAL_STRAIN_UNIT,
};
use crate::elastic::GeneralizedPlaneStrain;
use crate::error::PhysicsError;
use crate::heat::{Linearization, StepData};
use crate::laws::ConstraintLaw;

/// The eigenstrains of one body with their factors at a time.
type EigenFactors<'a> = [(&'a TimedEigenstrain, f64)];

/// A body's generalized plane strain, its axial unknown and its axial strain in a state.
type Generalized<'a> = Option<(&'a GeneralizedPlaneStrain, usize, f64)>;

impl<TL: ConstraintLaw, ML: ConstraintLaw> GapThermoMechanics<TL, ML> {
    /// The residual, and the matrix of `lin` if asked (temperature Jacobian of the
    /// conduction exact or Picard; everything else exact).
    pub(crate) fn evaluate(
        &self,
        x: &[f64],
        data: &StepData,
        r: &mut [f64],
        lin: Option<Linearization>,
    ) -> Result<Option<SparseMatrix>, PhysicsError> {
        let o = &self.offsets;
        let n = o.len;
        if x.len() != n || r.len() != n {
            return Err(PhysicsError::WrongLength {
                what: "state vector".into(),
                expected: n,
                got: x.len().min(r.len()),
            });
        }
        let mut trip = Triplets::default();
        // Heat conduction in the bodies.
        self.heat.body_terms(x, data, r, lin, &mut trip)?;
        // The eigenstrains' factors at this time.
        let mut eigen: [Vec<(&TimedEigenstrain, f64)>; 2] = [Vec::new(), Vec::new()];
        for e in &self.eigenstrains {
            eigen[e.body].push((e, self.eigenstrain_scale(e, data.time)?));
        }
        for b in 0..2 {
            self.elastic_terms(b, x, &eigen[b], r, lin.is_some(), &mut trip);
        }
        // The interfaces: the gap, then the contact pairs.
        let mut sums = GasSums::default();
        for view in self.interface_views() {
            self.interface_terms(&view, x, r, lin.is_some(), &mut trip, &mut sums)?;
        }
        self.gas_terms(x, sums, r, lin.is_some(), &mut trip);
        // Prescribed temperatures and displacements.
        self.heat.dirichlet_terms(x, data, r, lin, &mut trip);
        for &(i, v) in &self.pinned_values {
            r[i] = x[i] - v;
            if lin.is_some() {
                trip.push(i as u32, i as u32, 1.0);
            }
        }
        self.plane_end_terms(x, r, lin.is_some().then_some(&mut trip));
        Ok(lin.map(|_| trip.to_csr(n, n)))
    }

    /// Body `b`'s elasticity, `s_u (K u - G (T - T_ref) - f)` with the gas pressure on its
    /// surfaces, its eigenstrains `eigen` and (generalized plane strain) `c e` in its rows,
    /// and its axial balance ([`generalized_balance`](Self::generalized_balance)); the
    /// Jacobian entries when `lin`.
    fn elastic_terms(
        &self,
        b: usize,
        x: &[f64],
        eigen: &EigenFactors<'_>,
        r: &mut [f64],
        lin: bool,
        trip: &mut Triplets,
    ) {
        let o = &self.offsets;
        let (uu, pu) = (self.options.displacement_unit, self.options.pressure_unit);
        let su = self.row_scale;
        let (k, g) = (&self.stiffness[b], &self.thermal_load[b]);
        let t_ref = self.elastic[b].material.reference_temperature;
        let ub = &x[o.u[b]..o.u[b + 1]];
        let tb = &x[o.t[b]..o.t[b + 1]];
        // Generalized plane strain: the in-plane rows gain c e.
        let gps: Generalized<'_> = match (&self.axial[b], o.axial[b]) {
            (
                Some(Axial {
                    freedom: AxialFreedom::Generalized(gps),
                    ..
                }),
                Some(ia),
            ) => Some((gps, ia, x[ia] * AXIAL_STRAIN_UNIT)),
            _ => None,
        };
        for (i, (krow, grow)) in k.outer_iterator().zip(g.outer_iterator()).enumerate() {
            let gi = o.u[b] + i;
            let ku: f64 = krow.iter().map(|(c, v)| v * ub[c]).sum::<f64>() * uu;
            let gt: f64 = grow.iter().map(|(c, v)| v * (tb[c] - t_ref)).sum();
            // The gas pressure on the interface surface: nodal forces -P_o int N n.
            let gas_force = x[o.gas] * pu * self.gas_load[b][i];
            let axial = gps.map_or(0.0, |(gps, _, e)| gps.coupling[i] * e);
            let eigen_force = eigen.iter().fold(0.0, |f, (e, s)| f + s * e.load[i]);
            r[gi] = su * (ku - gt - self.load[b][i] + gas_force + axial - eigen_force);
            if lin && !self.pinned[gi - o.u[0]] {
                for (c, v) in krow.iter() {
                    trip.push(gi as u32, (o.u[b] + c) as u32, su * uu * v);
                }
                for (c, v) in grow.iter() {
                    trip.push(gi as u32, (o.t[b] + c) as u32, -su * v);
                }
                if self.gas_load[b][i] != 0.0 {
                    trip.push(gi as u32, o.gas as u32, su * pu * self.gas_load[b][i]);
                }
                if let Some((gps, ia, _)) = gps {
                    if gps.coupling[i] != 0.0 {
                        let v = su * gps.coupling[i] * AXIAL_STRAIN_UNIT;
                        trip.push(gi as u32, ia as u32, v);
                    }
                }
            }
        }
        if let (Some(gps), Some(ax)) = (gps, &self.axial[b]) {
            self.generalized_balance(b, x, gps, ax, eigen, r, lin, trip);
        }
    }

    /// The axial balance of body `b`'s generalized plane strain `gps` (its axial unknown
    /// `ia`, axial strain `e`; `ax` the force it balances),
    /// `s_u (c . u + k e - h . (T - T_ref) - F(P_o))` less its eigenstrains' share; the
    /// Jacobian entries when `lin`.
    #[allow(clippy::too_many_arguments)]
    fn generalized_balance(
        &self,
        b: usize,
        x: &[f64],
        (gps, ia, e): (&GeneralizedPlaneStrain, usize, f64),
        ax: &Axial,
        eigen: &EigenFactors<'_>,
        r: &mut [f64],
        lin: bool,
        trip: &mut Triplets,
    ) {
        let o = &self.offsets;
        let (uu, pu) = (self.options.displacement_unit, self.options.pressure_unit);
        let su = self.row_scale;
        let t_ref = self.elastic[b].material.reference_temperature;
        let ub = &x[o.u[b]..o.u[b + 1]];
        let tb = &x[o.t[b]..o.t[b + 1]];
        let dt: Vec<f64> = tb.iter().map(|t| t - t_ref).collect();
        let u_si: Vec<f64> = ub.iter().map(|v| v * uu).collect();
        let force = ax.force.at(x[o.gas] * pu);
        let eigen_force = eigen.iter().fold(0.0, |f, (e, s)| f + s * e.axial);
        r[ia] = su * (gps.axial_force(&u_si, e, &dt) - eigen_force - force);
        if lin {
            for (c, &v) in gps.coupling.iter().enumerate() {
                if v != 0.0 {
                    trip.push(ia as u32, (o.u[b] + c) as u32, su * uu * v);
                }
            }
            for (c, &v) in gps.thermal.iter().enumerate() {
                if v != 0.0 {
                    trip.push(ia as u32, (o.t[b] + c) as u32, -su * v);
                }
            }
            let (ia32, kzz) = (ia as u32, gps.stiffness * AXIAL_STRAIN_UNIT);
            trip.push(ia32, ia32, su * kzz);
            let dgas = -su * ax.force.per_gas_pressure * pu;
            trip.push(ia32, o.gas as u32, dgas);
        }
    }

    /// The gas pressure's row, from the gas-filled interfaces' sums `sums`: the given
    /// pressure, or the plenum's ideal gas over its volume and the gap's; the Jacobian
    /// entries when `lin`.
    fn gas_terms(&self, x: &[f64], sums: GasSums, r: &mut [f64], lin: bool, trip: &mut Triplets) {
        let o = &self.offsets;
        let pu = self.options.pressure_unit;
        let su = self.row_scale;
        let gas = x[o.gas] * pu;
        let GasSums {
            length,
            volume,
            t_sum,
            dvolume,
            dtemp,
        } = sums;
        let rg = o.gas;
        match self.options.gas {
            GasPressure::Fixed(p) => {
                r[rg] = su * length * (gas - p);
                if lin {
                    trip.push(rg as u32, rg as u32, su * length * pu);
                }
            }
            GasPressure::Plenum(plenum) => {
                let t_gap = t_sum / length;
                let v = plenum.volume + volume;
                r[rg] = su * length * (gas - plenum.gas_amount * t_gap / v);
                if lin {
                    trip.push(rg as u32, rg as u32, su * length * pu);
                    // d/dT: -n R / V dT_gap/dT, dT_gap/dT = dtemp / L.
                    for (i, d) in dtemp {
                        trip.push(rg as u32, i as u32, -su * plenum.gas_amount / v * d);
                    }
                    // d/du: n R T_gap / V^2 dV/du.
                    let f = su * length * plenum.gas_amount * t_gap / (v * v);
                    for (i, d) in dvolume {
                        trip.push(rg as u32, i as u32, f * d);
                    }
                }
            }
        }
    }

    /// A free plane end (r-z, 3D): its nodes' axial equilibrium rows summed into the axial
    /// unknown's row, the balance of the end's axial force, `sum_d r_d - s_u F(P_o)`; each of
    /// those rows becomes `x_d - w` (the end stays plane, moving by `w`).
    fn plane_end_terms(&self, x: &[f64], r: &mut [f64], trip: Option<&mut Triplets>) {
        let o = &self.offsets;
        let su = self.row_scale;
        let pu = self.options.pressure_unit;
        // (row, axial unknown) of each end's axial rows, and (axial unknown, its force's
        // derivative in the gas pressure) of each end.
        let mut rows: Vec<(usize, usize)> = Vec::new();
        let mut ends: Vec<(usize, f64)> = Vec::new();
        for b in 0..2 {
            let (Some(ax), Some(ia)) = (&self.axial[b], o.axial[b]) else {
                continue;
            };
            let AxialFreedom::PlaneEnd(dofs) = &ax.freedom else {
                continue;
            };
            let mut sum = 0.0;
            for &d in dofs {
                let gi = o.u[b] + d;
                sum += r[gi];
                r[gi] = x[gi] - x[ia];
                rows.push((gi, ia));
            }
            r[ia] = sum - su * ax.force.at(x[o.gas] * pu);
            ends.push((ia, -su * pu * ax.force.per_gas_pressure));
        }
        let Some(trip) = trip else {
            return;
        };
        if ends.is_empty() {
            return;
        }
        // The end's rows move into the axial unknown's row.
        let mut target: Vec<u32> = (0..o.len as u32).collect();
        for &(gi, ia) in &rows {
            target[gi] = ia as u32;
        }
        trip.map_rows(|row| target[row as usize]);
        for (gi, ia) in rows {
            trip.push(gi as u32, gi as u32, 1.0);
            trip.push(gi as u32, ia as u32, -1.0);
        }
        for (ia, dgas) in ends {
            trip.push(ia as u32, o.gas as u32, dgas);
        }
    }
}
