//! The interfaces of a [`GapThermoMechanics`]: the gap between its two bodies, and further
//! contact pairs between parts of them (the lands of the pellets of a stack, one body): each
//! row's thermal and mechanical law, its heat flux into the bodies, its pressure onto the
//! surfaces, and (where the gas fills it) its share of the gas volume and temperature.

use mortar_core::linalg::Triplets;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::{CouplingOptions, Interface, Tolerances};
use sprs::CsVecView;

use super::pair::{gap_column, nodal_gaps, ContactPair, GasSums, InterfaceView};
use super::problem::GapThermoMechanics;
use crate::contact::{slave_surface_measures, NormalGap};
use crate::error::PhysicsError;
use crate::laws::{evaluate, ConstraintLaw, LawPoint, LawTangent};
use crate::tied::Tie;

impl<TL: ConstraintLaw, ML: ConstraintLaw> GapThermoMechanics<TL, ML> {
    /// The problem with a further contact pair: `slave_surface` of body `bodies[0]` against
    /// `master_surface` of body `bodies[1]` (0 slave body, 1 master body; both the same for
    /// two parts of one body, the lands of the pellets of a stack), coupled with `coupling`
    /// and `tolerances` (a search radius above the pair's gap), with its own thermal and
    /// contact laws. Its rows add a heat flux and a contact pressure unknown per slave node
    /// (before the gas pressure); the gas does not fill it (its surfaces carry the contact
    /// law's pressure alone: the pellets bear on each other there).
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a body not 0 or 1 or a coupling geometry that
    /// differs from the problem's; the errors of the coupling, of [`NormalGap`] and of the
    /// surface measures.
    #[allow(clippy::too_many_arguments)]
    pub fn with_contact_pair(
        mut self,
        slave_surface: SurfaceMesh,
        master_surface: SurfaceMesh,
        bodies: [usize; 2],
        coupling: &CouplingOptions,
        tolerances: Tolerances,
        thermal_law: TL,
        contact_law: ML,
    ) -> Result<Self, PhysicsError> {
        if bodies.iter().any(|&b| b > 1) {
            return Err(PhysicsError::InvalidInput {
                body: "options".into(),
                what: format!("contact pair between bodies {bodies:?} of a two-body problem"),
            });
        }
        crate::field::cells::check_same_geometry(coupling.geometry, self.options.heat.geometry)?;
        let meshes = [&self.heat.bodies()[0].mesh, &self.heat.bodies()[1].mesh];
        let interface = Interface::with_tolerances(slave_surface, master_surface, tolerances)?;
        let tie = Tie::on_interface(meshes[bodies[0]], meshes[bodies[1]], interface, coupling)?;
        let dim = self.elastic[0].components();
        let o = &self.offsets;
        let body_offset = |b: usize| o.u[b] - o.u[0];
        let gap = NormalGap::with_offsets(
            &tie,
            dim,
            [body_offset(bodies[0]), body_offset(bodies[1])],
            o.u[2] - o.u[0],
        )?;
        let surface = slave_surface_measures(
            tie.interface(),
            tie.coupling(),
            coupling.geometry,
            tie.slave_nodes(),
            dim,
            self.axis(),
        )?;
        let rows = gap.weights.len();
        self.pairs.push(ContactPair {
            tie,
            gap,
            surface,
            thermal_law,
            contact_law,
            bodies,
        });
        self.offsets.add_pair(rows);
        Ok(self)
    }

    /// The number of contact pairs besides the gap
    /// ([`with_contact_pair`](Self::with_contact_pair)).
    pub fn contact_pairs(&self) -> usize {
        self.pairs.len()
    }

    /// The normal gap operator of contact pair `k` (its nodal weights, its reference gaps).
    ///
    /// # Panics
    /// If there is no pair `k` (see [`contact_pairs`](Self::contact_pairs)).
    pub fn pair_normal_gap(&self, k: usize) -> &NormalGap {
        &self.pairs[k].gap
    }

    /// The nodal gaps `g_j` (m) of contact pair `k` in a state, one per slave node of the
    /// pair.
    ///
    /// # Panics
    /// If there is no pair `k`.
    pub fn pair_gaps(&self, k: usize, x: &[f64]) -> Vec<f64> {
        let o = &self.offsets;
        nodal_gaps(
            &self.pairs[k].gap,
            &x[o.u[0]..o.u[2]],
            self.options.displacement_unit,
        )
    }

    /// The contact pressures (Pa) of contact pair `k` in a state, one per slave node of the
    /// pair: the whole pressure there (the gas does not fill a pair).
    ///
    /// # Panics
    /// If there is no pair `k`.
    pub fn pair_contact_pressures(&self, k: usize, x: &[f64]) -> Vec<f64> {
        let [_, p] = self.offsets.pairs[k];
        let rows = self.pairs[k].gap.weights.len();
        x[p..p + rows]
            .iter()
            .map(|v| v * self.options.pressure_unit)
            .collect()
    }

    /// The interfaces: the gap first, then the contact pairs.
    pub(crate) fn interface_views(&self) -> Vec<InterfaceView<'_, TL, ML>> {
        let o = &self.offsets;
        let mut views = vec![InterfaceView {
            tie: self.heat.tie(),
            gap: &self.gap,
            surface: &self.surface,
            thermal_law: self.heat.law(),
            contact_law: &self.contact_law,
            bodies: [0, 1],
            weights: self.heat.weights(),
            gas: true,
            offsets: [o.flux, o.pressure],
        }];
        for (p, pair) in self.pairs.iter().enumerate() {
            views.push(InterfaceView {
                tie: &pair.tie,
                gap: &pair.gap,
                surface: &pair.surface,
                thermal_law: &pair.thermal_law,
                contact_law: &pair.contact_law,
                bodies: pair.bodies,
                weights: &pair.gap.weights,
                gas: false,
                offsets: o.pairs[p],
            });
        }
        views
    }

    /// The slave's nodal areas of `view` as it moved, `W_j(u) = w_j + (A u)_j` (first order).
    pub(crate) fn moved_areas_of(&self, view: &InterfaceView<'_, TL, ML>, x: &[f64]) -> Vec<f64> {
        let o = &self.offsets;
        let b = view.bodies[0];
        let (us, uu) = (&x[o.u[b]..o.u[b + 1]], self.options.displacement_unit);
        view.surface
            .area_change
            .outer_iterator()
            .zip(&view.gap.weights)
            .map(|(row, w)| w + uu * row.iter().map(|(k, v)| v * us[k]).sum::<f64>())
            .collect()
    }

    /// The rows of one interface: each slave node's thermal law (flux row) and contact law
    /// (pressure row), the flux into the bodies' heat balances (`+D^T q` on the slave side,
    /// `-M^T q` on the master side), the pressure onto their equilibrium (`N^T p`), their
    /// Jacobian entries when `lin` ([`row_jacobian`](Self::row_jacobian)), and the
    /// gas-filled interfaces' sums ([`gas_derivatives`](Self::gas_derivatives)).
    ///
    /// # Errors
    /// The errors of the laws.
    pub(crate) fn interface_terms(
        &self,
        view: &InterfaceView<'_, TL, ML>,
        x: &[f64],
        r: &mut [f64],
        lin: bool,
        trip: &mut Triplets,
        sums: &mut GasSums,
    ) -> Result<(), PhysicsError> {
        let o = &self.offsets;
        let (uu, pu, fu) = (
            self.options.displacement_unit,
            self.options.pressure_unit,
            self.options.flux_unit,
        );
        let su = self.row_scale;
        let c = view.tie.coupling();
        let (sn, mn) = (view.tie.slave_nodes(), view.tie.master_nodes());
        let [bs, bm] = view.bodies;
        let (ts, tm) = (&x[o.t[bs]..o.t[bs + 1]], &x[o.t[bm]..o.t[bm + 1]]);
        let u = &x[o.u[0]..o.u[2]];
        let gas = x[o.gas] * pu;
        let areas = self.moved_areas_of(view, x);
        for (j, ((d, m), n)) in
            c.d.outer_iterator()
                .zip(c.m.outer_iterator())
                .zip(view.gap.matrix.outer_iterator())
                .enumerate()
        {
            let row = InterfaceRow {
                j,
                d,
                m,
                n,
                w: view.weights[j],
                rq: view.offsets[0] + j,
                rp: view.offsets[1] + j,
            };
            let (w, rq, rp) = (row.w, row.rq, row.rp);
            let gs: f64 = row.d.iter().map(|(k, v)| v * ts[sn[k] as usize]).sum();
            let gm: f64 = row.m.iter().map(|(l, v)| v * tm[mn[l] as usize]).sum();
            let nu: f64 = row.n.iter().map(|(k, v)| v * u[k]).sum::<f64>() * uu;
            let g = (view.gap.initial[j] - nu) / w;
            let (dt, tbar) = ((gs - gm) / w, 0.5 * (gs + gm) / w);
            let q = fu * x[rq];
            let p = pu * x[rp];
            let point = LawPoint::new(dt, q, tbar).with_mechanics(g, p, gas);
            let th = evaluate(view.thermal_law, point)?;
            let mpoint = LawPoint::new(g, p, tbar).with_mechanics(g, p, gas);
            let me = evaluate(view.contact_law, mpoint)?;
            r[rq] = w * th.value;
            r[rp] = su * w * me.value;
            // Heat flux into the bodies, pressure onto the surfaces.
            for (k, v) in row.d.iter() {
                r[o.t[bs] + sn[k] as usize] += v * q;
            }
            for (l, v) in row.m.iter() {
                r[o.t[bm] + mn[l] as usize] -= v * q;
            }
            // The contact pressure is an interaction: -p n on the slave, +p n on the master.
            for (k, v) in row.n.iter() {
                r[o.u[0] + k] += su * v * p;
            }
            let kappa = view.surface.curvature[j];
            if view.gas {
                sums.length += w;
                sums.t_sum += w * tbar;
                sums.volume += gap_column(areas[j], g, kappa);
            }
            if !lin {
                continue;
            }
            self.row_jacobian(view, &row, &th, &me, trip);
            if view.gas {
                self.gas_derivatives(view, &row, g, areas[j], sums);
            }
        }
        Ok(())
    }

    /// The Jacobian entries of `row` of `view`, the thermal law's tangent `th` and the
    /// contact law's `me` there: its flux row, its pressure row, and its flux's and
    /// pressure's columns in the heat and equilibrium rows of the bodies.
    fn row_jacobian(
        &self,
        view: &InterfaceView<'_, TL, ML>,
        row: &InterfaceRow<'_>,
        th: &LawTangent,
        me: &LawTangent,
        trip: &mut Triplets,
    ) {
        let o = &self.offsets;
        let (uu, pu, fu) = (
            self.options.displacement_unit,
            self.options.pressure_unit,
            self.options.flux_unit,
        );
        let su = self.row_scale;
        let (sn, mn) = (view.tie.slave_nodes(), view.tie.master_nodes());
        let [bs, bm] = view.bodies;
        let (w, rq, rp) = (row.w, row.rq, row.rp);
        // Flux row.
        self.temperature_columns(view, row, rq, th.d_gap, th.d_temperature, trip);
        trip.push(rq as u32, rq as u32, w * th.d_multiplier * fu);
        for (k, v) in row.n.iter() {
            trip.push(rq as u32, (o.u[0] + k) as u32, -th.d_normal_gap * v * uu);
        }
        trip.push(rq as u32, rp as u32, w * th.d_contact_pressure * pu);
        trip.push(rq as u32, o.gas as u32, w * th.d_gas_pressure * pu);
        // Pressure row.
        let dg = me.d_gap + me.d_normal_gap;
        let dp = me.d_multiplier + me.d_contact_pressure;
        self.temperature_columns(view, row, rp, 0.0, su * me.d_temperature, trip);
        for (k, v) in row.n.iter() {
            trip.push(rp as u32, (o.u[0] + k) as u32, -su * dg * v * uu);
        }
        trip.push(rp as u32, rp as u32, su * w * dp * pu);
        trip.push(rp as u32, o.gas as u32, su * w * me.d_gas_pressure * pu);
        // The heat rows' flux columns, the equilibrium rows' pressure columns.
        for (k, v) in row.d.iter() {
            let gi = o.t[bs] + sn[k] as usize;
            if !self.heat.is_dirichlet(gi) {
                trip.push(gi as u32, rq as u32, v * fu);
            }
        }
        for (l, v) in row.m.iter() {
            let gi = o.t[bm] + mn[l] as usize;
            if !self.heat.is_dirichlet(gi) {
                trip.push(gi as u32, rq as u32, -v * fu);
            }
        }
        for (k, v) in row.n.iter() {
            if !self.pinned[k] {
                let gi = (o.u[0] + k) as u32;
                trip.push(gi, rp as u32, su * v * pu);
            }
        }
    }

    /// The entries of Jacobian row `target` in the temperatures of `row`'s slave and master
    /// nodes, of a law with derivatives `dg` in the temperature jump and `dtb` in the mean
    /// temperature.
    fn temperature_columns(
        &self,
        view: &InterfaceView<'_, TL, ML>,
        row: &InterfaceRow<'_>,
        target: usize,
        dg: f64,
        dtb: f64,
        trip: &mut Triplets,
    ) {
        let o = &self.offsets;
        let (sn, mn) = (view.tie.slave_nodes(), view.tie.master_nodes());
        let [bs, bm] = view.bodies;
        for (k, v) in row.d.iter() {
            trip.push(
                target as u32,
                (o.t[bs] + sn[k] as usize) as u32,
                (dg + 0.5 * dtb) * v,
            );
        }
        for (l, v) in row.m.iter() {
            trip.push(
                target as u32,
                (o.t[bm] + mn[l] as usize) as u32,
                (-dg + 0.5 * dtb) * v,
            );
        }
    }

    /// The gas equation's derivatives of `row` of a gas-filled `view` (nodal gap `g`, moved
    /// area `area`) into `sums`: its gap volume's in the displacements, its temperature's.
    fn gas_derivatives(
        &self,
        view: &InterfaceView<'_, TL, ML>,
        row: &InterfaceRow<'_>,
        g: f64,
        area: f64,
        sums: &mut GasSums,
    ) {
        let o = &self.offsets;
        let uu = self.options.displacement_unit;
        let (sn, mn) = (view.tie.slave_nodes(), view.tie.master_nodes());
        let [bs, bm] = view.bodies;
        let (j, w) = (row.j, row.w);
        let kappa = view.surface.curvature[j];
        let area_offset = o.u[bs];
        // (Zero entries where the gap is closed: the pattern stays the same.)
        // dV_j = (A du)_j G(g_j) + W_j G'(g_j) dg_j, G(g) = g (1 + kappa g / 2).
        let open = if g > 0.0 {
            area / w * (1.0 + kappa * g)
        } else {
            0.0
        };
        sums.dvolume
            .extend(row.n.iter().map(|(k, v)| (o.u[0] + k, -open * v * uu)));
        let column = gap_column(1.0, g, kappa);
        if column != 0.0 {
            if let Some(arow) = view.surface.area_change.outer_view(j) {
                sums.dvolume
                    .extend(arow.iter().map(|(k, v)| (area_offset + k, column * v * uu)));
            }
        }
        for (k, v) in row.d.iter() {
            sums.dtemp.push((o.t[bs] + sn[k] as usize, 0.5 * v));
        }
        for (l, v) in row.m.iter() {
            sums.dtemp.push((o.t[bm] + mn[l] as usize, 0.5 * v));
        }
    }
}

/// One row `j` of an interface: its rows of D, M and N, its weight `w_j`, and its flux and
/// pressure unknowns `rq`, `rp`.
struct InterfaceRow<'m> {
    j: usize,
    d: CsVecView<'m, f64>,
    m: CsVecView<'m, f64>,
    n: CsVecView<'m, f64>,
    w: f64,
    rq: usize,
    rp: usize,
}
