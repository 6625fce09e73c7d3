//! The thermomechanical gap problem: the state's blocks, the residual and Jacobian of heat,
//! elasticity (with the bodies' axial unknowns when their axial direction is free), the
//! interface laws and the gas pressure.

use std::collections::HashSet;
use std::sync::Arc;

use mortar_core::element::MAX_FACE_NODES;
use mortar_core::linalg::SparseMatrix;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::{CouplingOptions, ModelGeometry, Side, Tolerances};
use nalgebra::Vector3;

use super::pair::{gap_column, nodal_gaps, ContactPair};
use super::plenum::GasPressure;
use crate::contact::{slave_surface_measures, NormalGap, SlaveSurfaceMeasures};
use crate::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, assemble_thermal_load_matrix, AxialForce,
    ElasticBody, ElasticOptions, GeneralizedPlaneStrain,
};
use crate::error::PhysicsError;
use crate::heat::{Conductivity, GapHeat, HeatBody, HeatOptions};
use crate::laws::ConstraintLaw;

/// One body of a thermomechanical problem: its heat conduction (mesh, capacity, source,
/// temperature conditions, `k(T)`) and its elasticity (the same mesh, material with thermal
/// expansion, displacement conditions, tractions). The elastic body's own temperature field is
/// not used: the temperature is an unknown.
#[derive(Debug, Clone)]
pub struct ThermoElasticBody {
    /// Heat conduction.
    pub heat: HeatBody,
    /// `k(T)`.
    pub conductivity: Conductivity,
    /// Elasticity, on a mesh with the same nodes as `heat`'s.
    pub elastic: ElasticBody,
}

/// Settings of [`GapThermoMechanics`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermoMechOptions {
    /// Heat assembly.
    pub heat: HeatOptions,
    /// Elastic assembly.
    pub elastic: ElasticOptions,
    /// The gap (m) of the reference configuration at every slave node, when given: the
    /// as-built gap of a design, in place of the distance between the meshes. A polygonal
    /// mesh of two coaxial circles measures their gap short by up to the sagitta of a master
    /// edge, `R (1 - cos(pi / n))` (5 um for 64 edges of a 4 mm circle, a quarter of a 20 um
    /// gap): give the design gap so that the discretisation of the curved surfaces does not
    /// change it. `None`: the mortar gap of the meshes.
    pub nominal_gap: Option<f64>,
    /// The gas pressure in the gap.
    pub gas: GasPressure,
    /// The unit of the displacement unknowns (m): the state holds `u / displacement_unit`.
    pub displacement_unit: f64,
    /// The unit of the contact and gas pressure unknowns (Pa).
    pub pressure_unit: f64,
    /// The unit of the heat flux unknowns (W/m^2): with a gap conductance of the order of
    /// it, the flux unknowns are kelvin-like.
    pub flux_unit: f64,
    /// Per body `[slave, master]`: `None` holds the axial direction as the bodies' own
    /// conditions say (plane strain in 2D); `Some(force)` frees it with one axial unknown
    /// whose balance is `int sigma_zz dA = force.at(P_gas)` over the body's cross-section:
    /// in 2D (Cartesian) the uniform axial strain of generalized plane strain
    /// ([`GeneralizedPlaneStrain`]); in the axisymmetric geometry and in 3D the axial
    /// displacement of the body's top end (the nodes at its largest `y` in r-z, `z` in 3D),
    /// kept plane, loaded by the force and otherwise free (the bottom held by the body's own
    /// conditions: a segment of a long stack).
    pub axial: [Option<AxialForce>; 2],
}

impl Default for ThermoMechOptions {
    /// Default assembly, the mesh gap, no gas; micrometres, megapascals and 1e4 W/m^2; the
    /// axial direction as the bodies' conditions say.
    fn default() -> Self {
        Self {
            heat: HeatOptions::default(),
            elastic: ElasticOptions::default(),
            nominal_gap: None,
            gas: GasPressure::Fixed(0.0),
            displacement_unit: 1e-6,
            pressure_unit: 1e6,
            flux_unit: 1e4,
            axial: [None, None],
        }
    }
}

/// The offsets of the blocks of the state vector.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Offsets {
    /// Temperatures: slave, master.
    pub t: [usize; 3],
    /// Displacements: slave, master.
    pub u: [usize; 3],
    /// Heat fluxes, one per slave interface node.
    pub flux: usize,
    /// Contact pressures, one per slave interface node.
    pub pressure: usize,
    /// Per contact pair ([`GapThermoMechanics::with_contact_pair`]), its first flux and
    /// pressure unknowns (after the gap's, before the gas pressure).
    pub pairs: Vec<[usize; 2]>,
    /// The gas pressure.
    pub gas: usize,
    /// Per body, its axial unknown (after the gas pressure), if it has one.
    pub axial: [Option<usize>; 2],
    /// The size.
    pub len: usize,
}

impl Offsets {
    /// The offsets of bodies of `nodes = [slave, master]` nodes with `dim` displacement
    /// components, `rows` slave interface nodes, and an axial unknown per body with `axial`.
    pub(crate) fn new(
        nodes: [usize; 2],
        dim: usize,
        rows: usize,
        axial: &[Option<Axial>; 2],
    ) -> Self {
        let [ns, nm] = nodes;
        let nt = ns + nm;
        let u = [nt, nt + dim * ns, nt + dim * (ns + nm)];
        let gas = u[2] + 2 * rows;
        let mut len = gas + 1;
        let axial = [0, 1].map(|b| {
            axial[b].as_ref().map(|_| {
                len += 1;
                len - 1
            })
        });
        Self {
            t: [0, ns, nt],
            u,
            flux: u[2],
            pressure: u[2] + rows,
            pairs: Vec::new(),
            gas,
            axial,
            len,
        }
    }

    /// Adds a contact pair of `rows` slave nodes: its fluxes and pressures before the gas
    /// pressure, which and the axial unknowns move up.
    pub(crate) fn add_pair(&mut self, rows: usize) {
        self.pairs.push([self.gas, self.gas + rows]);
        self.gas += 2 * rows;
        for a in self.axial.iter_mut().flatten() {
            *a += 2 * rows;
        }
        self.len += 2 * rows;
    }

    /// Whether unknown `i` is a heat flux (of the gap or of a contact pair).
    pub(crate) fn is_flux(&self, i: usize) -> bool {
        (self.flux..self.pressure).contains(&i)
            || self.pairs.iter().any(|&[f, p]| (f..p).contains(&i))
    }

    /// Whether unknown `i` is a contact pressure (of the gap or of a contact pair).
    pub(crate) fn is_pressure(&self, i: usize) -> bool {
        let gap = self.pressure..self.pressure + (self.pressure - self.flux);
        gap.contains(&i)
            || self
                .pairs
                .iter()
                .any(|&[f, p]| (p..p + (p - f)).contains(&i))
    }
}

/// The state unit of the axial strain of generalized plane strain (a microstrain).
pub(crate) const AXIAL_STRAIN_UNIT: f64 = 1e-6;

/// How a body's axial direction is freed ([`ThermoMechOptions::axial`]).
#[derive(Debug, Clone)]
pub(crate) enum AxialFreedom {
    /// 2D: the uniform axial strain (in [`AXIAL_STRAIN_UNIT`]).
    Generalized(GeneralizedPlaneStrain),
    /// r-z and 3D: the axial displacement (in the displacement unit) of these unknowns of
    /// the body (its top end's axial components), all equal to it.
    PlaneEnd(Vec<usize>),
}

/// A body's axial unknown: how it frees the body and the force it balances.
#[derive(Debug, Clone)]
pub(crate) struct Axial {
    pub freedom: AxialFreedom,
    pub force: AxialForce,
    /// The body's axial extent (m; 1 in 2D): a free end's axial strain is its displacement
    /// over it.
    pub length: f64,
}

/// A uniform eigenstrain of one body that follows time, `eps*(t) = scale(t) unit`
/// ([`GapThermoMechanics::with_eigenstrain`]).
#[derive(Clone)]
pub(crate) struct TimedEigenstrain {
    /// The body (0 slave, 1 master).
    pub body: usize,
    /// The eigenstrain of `scale = 1`, Voigt order ([`ElasticBody::eigenstrain`]).
    pub unit: [f64; 6],
    /// Its factor at a time (s).
    pub scale: Arc<dyn Fn(f64) -> f64 + Send + Sync>,
    /// The nodal forces of `unit`, `int B^T C unit` (the body's layout).
    pub load: Vec<f64>,
    /// `(C unit)_zz A`, the unit's share of the axial balance of generalized plane strain
    /// (zero without).
    pub axial: f64,
}

impl std::fmt::Debug for TimedEigenstrain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TimedEigenstrain")
            .field("body", &self.body)
            .field("unit", &self.unit)
            .field("axial", &self.axial)
            .finish()
    }
}

/// Two bodies in thermomechanical contact across a gap: transient heat conduction with `k(T)`
/// and small-strain thermoelasticity in both, and across the interface a thermal law (heat
/// flux against temperature jump, seeing the mechanical gap and contact pressure) and a
/// mechanical law (contact pressure against normal gap, seeing the gas pressure), with the
/// gas pressure given or following a plenum. Small deformation: D, M and the normals are
/// those of the reference configuration.
///
/// Unknowns, in this order: temperatures (slave, master; K), displacements (slave, master,
/// `node * dim + k`, in `displacement_unit`), heat fluxes leaving the slave (`flux_unit`),
/// contact pressures (`pressure_unit`), one per slave interface node (row of D), the gas
/// pressure (`pressure_unit`), and per body whose axial direction is free
/// ([`ThermoMechOptions::axial`]) its axial unknown: the axial strain of generalized plane
/// strain (in microstrain; the in-plane rows gain `c e` and its row is the axial balance
/// `c . u + k e - h . (T - T_ref) - F(P_o)`, [`GeneralizedPlaneStrain`]), or a free end's
/// axial displacement `w` (`displacement_unit`; the end's axial rows become `u_d - w` and
/// their sum, less `F(P_o)`, is its row). Residual (each body's rows; `G` the thermal load matrix,
/// `N` the weighted normal gap operator, `g_j = (g~_0 - N u)_j / w_j` the nodal gap, `a` the
/// integrals `int N n` of each body's interface surface with its outward normal `n`: the gas
/// pressure acts on each surface over its own area, the contact pressure is an interaction
/// transferred from the slave to the master by the mortar operators):
///
/// ```text
/// heat:       f_int(T) + C (T - T_old)/dt - F  +  D^T q  (slave)  -  M^T q  (master)
/// mechanics: (K u - G (T - T_ref) - f  +  N^T p  +  P_o a) s_u
/// flux j:     w_j C_th(dT_j, q_j; Tbar_j, g_j, p_j, P_o)
/// pressure j: w_j C_mech(g_j, p_j; Tbar_j, g_j, p_j, P_o) s_u
/// gas:        (P_o - n R T_gap / (V_plenum + V_gap)) L s_u      (plenum; P_o - P_given else)
/// ```
///
/// with `V_gap = sum_j W_j(u) g_j (1 + kappa_j g_j / 2)` over the open nodes (`g_j > 0`):
/// Steiner's formula to second order in the gap over the slave surface as it moved,
/// `W_j(u) = w_j + (A u)_j` the nodal areas to first order in the displacement across the
/// rod's axis (the volumes are per as-built length: the plenum's is held) and
/// `kappa_j` the surface's curvature ([`SlaveSurfaceMeasures`]). For coaxial cylinders it is
/// the annulus `pi ((a + u + g)^2 - (a + u)^2)` to `O(g u / a^2)`; the first order
/// `sum_j w_j g_j` alone misses `g / 2a + u / a`, 1.5 % of the volume of a 40 um gap around
/// a pellet of 4.1 mm that moved out by 44 um. `T_gap = sum_j w_j Tbar_j / L` and `L = sum_j w_j`; Dirichlet rows replaced by
/// `x - g`. `s_u = k / (E u_unit)` (slave conductivity and Young's modulus) weighs a
/// micrometre of displacement error as a kelvin of temperature error in Newton's norms.
#[derive(Debug, Clone)]
pub struct GapThermoMechanics<TL, ML> {
    pub(crate) heat: GapHeat<TL>,
    pub(crate) elastic: [ElasticBody; 2],
    pub(crate) contact_law: ML,
    pub(crate) stiffness: [SparseMatrix; 2],
    pub(crate) thermal_load: [SparseMatrix; 2],
    pub(crate) load: [Vec<f64>; 2],
    pub(crate) gap: NormalGap,
    /// The slave surface's curvature and the change of its nodal areas with its displacement
    /// (the gap volume's second-order terms).
    pub(crate) surface: SlaveSurfaceMeasures,
    /// Per body, `int N_a n` over its interface surface (`n` its outward normal): the nodal
    /// forces of a unit gas pressure are `-gas_load`.
    pub(crate) gas_load: [Vec<f64>; 2],
    pub(crate) pinned: Vec<bool>,
    pub(crate) pinned_values: Vec<(usize, f64)>,
    pub(crate) options: ThermoMechOptions,
    pub(crate) row_scale: f64,
    pub(crate) offsets: Offsets,
    /// Per body, its axial unknown ([`ThermoMechOptions::axial`]).
    pub(crate) axial: [Option<Axial>; 2],
    /// The eigenstrains that follow time ([`with_eigenstrain`](Self::with_eigenstrain)).
    pub(crate) eigenstrains: Vec<TimedEigenstrain>,
    /// The contact pairs besides the gap ([`with_contact_pair`](Self::with_contact_pair)).
    pub(crate) pairs: Vec<ContactPair<TL, ML>>,
}

impl<TL: ConstraintLaw, ML: ConstraintLaw> GapThermoMechanics<TL, ML> {
    /// Builds the problem: the heat problem of the two bodies across the interface of
    /// `slave_surface` and `master_surface` (node tags of the bodies'), the stiffness and
    /// thermal load matrices, and the normal gap.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for bodies whose heat and elastic meshes differ in
    /// size, a coupling, heat and elastic geometry that differ ([`ModelGeometry`]: give all
    /// three the axisymmetric one for an r-z model), units that are not positive and finite,
    /// a nominal gap that is not finite, and
    /// the errors of [`GapHeat::new`], of the elastic assembly and of [`NormalGap::new`].
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        slave: ThermoElasticBody,
        master: ThermoElasticBody,
        slave_surface: SurfaceMesh,
        master_surface: SurfaceMesh,
        coupling: &CouplingOptions,
        tolerances: Tolerances,
        thermal_law: TL,
        contact_law: ML,
        options: &ThermoMechOptions,
    ) -> Result<Self, PhysicsError> {
        check_bodies([&slave, &master])?;
        // Heat, elasticity and the coupling on one geometry (r-z: all three axisymmetric).
        crate::field::cells::check_same_geometry(coupling.geometry, options.heat.geometry)?;
        crate::field::cells::check_same_geometry(coupling.geometry, options.elastic.geometry)?;
        check_options(options)?;
        let row_scale = row_scale(&slave, options)?;
        let ThermoElasticBody {
            heat: hs,
            conductivity: ks,
            elastic: es,
        } = slave;
        let ThermoElasticBody {
            heat: hm,
            conductivity: km,
            elastic: em,
        } = master;
        let heat = GapHeat::new(
            (hs, ks),
            (hm, km),
            slave_surface,
            master_surface,
            coupling,
            tolerances,
            thermal_law,
            &options.heat,
        )?;
        let dim = es.components();
        if em.components() != dim {
            return Err(invalid(
                &em.name,
                format!("a {}D body against a {dim}D one", em.components()),
            ));
        }
        let (gap, surface, gas_load) = interface_operators(&heat, [&es, &em], coupling, options)?;
        let stiffness = [
            assemble_elastic_stiffness(&es, &options.elastic)?,
            assemble_elastic_stiffness(&em, &options.elastic)?,
        ];
        let thermal_load = [
            assemble_thermal_load_matrix(&es, &options.elastic)?,
            assemble_thermal_load_matrix(&em, &options.elastic)?,
        ];
        // Body forces and tractions only: the thermal load is G (T - T_ref).
        let load = [
            assemble_elastic_load(&without_temperature(&es), &options.elastic)?,
            assemble_elastic_load(&without_temperature(&em), &options.elastic)?,
        ];
        let axial = [
            axial_freedom(&es, options.axial[0], &options.elastic)?,
            axial_freedom(&em, options.axial[1], &options.elastic)?,
        ];
        let (ns, nm) = (es.mesh.node_count(), em.mesh.node_count());
        let offsets = Offsets::new([ns, nm], dim, gap.weights.len(), &axial);
        let (pinned, pinned_values) =
            pinned_displacements([&es, &em], &offsets.u, &axial, options.displacement_unit)?;
        Ok(Self {
            heat,
            elastic: [es, em],
            contact_law,
            stiffness,
            thermal_load,
            load,
            gap,
            surface,
            gas_load,
            pinned,
            pinned_values,
            options: *options,
            row_scale,
            offsets,
            axial,
            eigenstrains: Vec::new(),
            pairs: Vec::new(),
        })
    }

    /// The component along the rod's axis (y in r-z, z in 3D; none in 2D), whose stretch the
    /// gap volumes do not count: they are per as-built length (the plenum's is held).
    pub(crate) fn axis(&self) -> Option<usize> {
        rod_axis(self.options.heat.geometry, self.elastic[0].components())
    }

    /// The number of unknowns.
    pub fn dimension(&self) -> usize {
        self.offsets.len
    }

    /// The heat problem (bodies, tie, thermal law).
    pub fn heat(&self) -> &GapHeat<TL> {
        &self.heat
    }

    /// The elastic bodies `[slave, master]`.
    pub fn elastic_bodies(&self) -> &[ElasticBody; 2] {
        &self.elastic
    }

    /// The contact law.
    pub fn contact_law(&self) -> &ML {
        &self.contact_law
    }

    /// The weighted normal gap operator.
    pub fn normal_gap(&self) -> &NormalGap {
        &self.gap
    }

    /// The settings.
    pub fn options(&self) -> &ThermoMechOptions {
        &self.options
    }

    /// The state of uniform temperatures `[slave, master]` (K, one per node), zero
    /// displacements, fluxes and contact pressures, and the gas pressure of the options at
    /// the reference gap (a plenum's at the slave temperature's mean).
    pub fn state(&self, temperatures: [&[f64]; 2]) -> Vec<f64> {
        let o = &self.offsets;
        let mut x = vec![0.0; o.len];
        x[..o.t[1]].copy_from_slice(temperatures[0]);
        x[o.t[1]..o.t[2]].copy_from_slice(temperatures[1]);
        let mut gas = match self.options.gas {
            GasPressure::Fixed(p) => p,
            GasPressure::Plenum(p) => {
                let t = temperatures[0].iter().sum::<f64>() / temperatures[0].len().max(1) as f64;
                let v = (0..self.gap.initial.len())
                    .map(|j| {
                        let w = self.gap.weights[j];
                        gap_column(w, self.gap.initial[j] / w, self.surface.curvature[j])
                    })
                    .sum();
                p.pressure(v, t)
            }
        };
        if !gas.is_finite() {
            gas = 0.0;
        }
        x[o.gas] = gas / self.options.pressure_unit;
        for &(i, v) in &self.pinned_values {
            x[i] = v;
        }
        x
    }

    /// The physical quantities of a state `x`.
    pub fn fields<'a>(&self, x: &'a [f64]) -> StateView<'a> {
        let o = &self.offsets;
        StateView {
            temperature: [&x[..o.t[1]], &x[o.t[1]..o.t[2]]],
            displacement: [&x[o.u[0]..o.u[1]], &x[o.u[1]..o.u[2]]],
            displacement_unit: self.options.displacement_unit,
            flux: &x[o.flux..o.pressure],
            flux_unit: self.options.flux_unit,
            contact_pressure: &x[o.pressure..o.pressure + (o.pressure - o.flux)],
            pressure_unit: self.options.pressure_unit,
            gas_pressure: x[o.gas] * self.options.pressure_unit,
            axial_strain: [0, 1].map(|b| self.axial_strain(x, b)),
        }
    }

    /// The problem with the gas pressure also pressing on `surface`, a further part of body
    /// `b`'s boundary (0 slave, 1 master; by the body's node tags): a pellet's dishes and
    /// chamfers, which the gas wets but which face no other body. Its nodal forces are
    /// `-P_o int N n`, as on the interface.
    ///
    /// # Errors
    /// [`PhysicsError::InterfaceNodeNotInBody`] for a node of `surface` not in the body;
    /// [`PhysicsError::InvalidInput`] for `b > 1`; the errors of the boundary extraction.
    pub fn with_gas_on(mut self, b: usize, surface: &SurfaceMesh) -> Result<Self, PhysicsError> {
        let body = self
            .elastic
            .get(b)
            .ok_or_else(|| PhysicsError::InvalidInput {
                body: "options".into(),
                what: format!("body {b} of a two-body problem (0 or 1)"),
            })?;
        let side = if b == 0 { Side::Slave } else { Side::Master };
        let load = surface_load(
            surface,
            body,
            side,
            body.components(),
            self.options.elastic.geometry,
        )?;
        for (g, l) in self.gas_load[b].iter_mut().zip(load) {
            *g += l;
        }
        Ok(self)
    }

    /// The problem with a uniform eigenstrain in body `b` (0 slave, 1 master) that follows
    /// time, `eps*(t) = scale(t) unit` (`unit` in the Voigt order of
    /// [`ElasticBody::eigenstrain`]): the body's equilibrium rows gain
    /// `-scale(t) int B^T C unit`, its axial balance in generalized plane strain
    /// `-scale(t) (C unit)_zz A`; a load that depends on time only, so the Jacobian is
    /// unchanged. A fuel pellet's relocation is one ([`RelocationModel`](crate::laws::RelocationModel)).
    /// Several add up; [`eigenstrain_at`](Self::eigenstrain_at) gives the body's total at a
    /// time for its stress.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for `b > 1` or a non-finite `unit`; the errors of the
    /// load assembly.
    pub fn with_eigenstrain(
        mut self,
        b: usize,
        unit: [f64; 6],
        scale: impl Fn(f64) -> f64 + Send + Sync + 'static,
    ) -> Result<Self, PhysicsError> {
        let body = self
            .elastic
            .get(b)
            .ok_or_else(|| PhysicsError::InvalidInput {
                body: "options".into(),
                what: format!("body {b} of a two-body problem (0 or 1)"),
            })?;
        // The unit's loads alone: no body force, traction or temperature.
        let mut bare = ElasticBody::new(body.name.clone(), body.mesh.clone(), body.material)
            .with_eigenstrain(unit)?;
        bare.dirichlet.clone_from(&body.dirichlet);
        let load = assemble_elastic_load(&bare, &self.options.elastic)?;
        let axial = match &self.axial[b] {
            Some(Axial {
                freedom: AxialFreedom::Generalized(gps),
                ..
            }) => body.material.stress(&unit, 0.0)[2] * gps.area,
            _ => 0.0,
        };
        self.eigenstrains.push(TimedEigenstrain {
            body: b,
            unit,
            scale: Arc::new(scale),
            load,
            axial,
        });
        Ok(self)
    }

    /// The eigenstrain of body `b` at time `t` (s): its own
    /// ([`ElasticBody::eigenstrain`]) and those that follow time
    /// ([`with_eigenstrain`](Self::with_eigenstrain)); `None` without any.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-finite factor at `t`.
    pub fn eigenstrain_at(&self, b: usize, t: f64) -> Result<Option<[f64; 6]>, PhysicsError> {
        let mut total = self.elastic.get(b).and_then(|body| body.eigenstrain);
        for e in self.eigenstrains.iter().filter(|e| e.body == b) {
            let s = self.eigenstrain_scale(e, t)?;
            let sum = total.get_or_insert([0.0; 6]);
            for (acc, u) in sum.iter_mut().zip(e.unit) {
                *acc += s * u;
            }
        }
        Ok(total)
    }

    /// The factor of `e` at `t`, refused when not finite.
    pub(super) fn eigenstrain_scale(
        &self,
        e: &TimedEigenstrain,
        t: f64,
    ) -> Result<f64, PhysicsError> {
        let s = (e.scale)(t);
        if s.is_finite() {
            Ok(s)
        } else {
            Err(PhysicsError::InvalidInput {
                body: self.elastic[e.body].name.clone(),
                what: format!("the eigenstrain's factor at t = {t} s is {s}, not finite"),
            })
        }
    }

    /// The axial strain of body `b` (0 slave, 1 master) in a state `x`, if its axial direction
    /// is free ([`ThermoMechOptions::axial`]): the uniform strain of generalized plane strain,
    /// or a free end's displacement over the body's axial extent.
    pub fn axial_strain(&self, x: &[f64], b: usize) -> Option<f64> {
        let (ax, ia) = (self.axial.get(b)?.as_ref()?, self.offsets.axial[b]?);
        Some(match ax.freedom {
            AxialFreedom::Generalized(_) => x[ia] * AXIAL_STRAIN_UNIT,
            AxialFreedom::PlaneEnd(_) => x[ia] * self.options.displacement_unit / ax.length,
        })
    }

    /// The nodal gaps `g_j` (m) of a state, one per slave interface node.
    pub fn gaps(&self, x: &[f64]) -> Vec<f64> {
        let o = &self.offsets;
        nodal_gaps(
            &self.gap,
            &x[o.u[0]..o.u[2]],
            self.options.displacement_unit,
        )
    }

    /// The gap's volume `sum_j W_j(u) g_j (1 + kappa_j g_j / 2)` over the open nodes (m^2
    /// per unit length in 2D, m^3 in r-z and 3D; see the type's doc).
    pub fn gap_volume(&self, x: &[f64]) -> f64 {
        let areas = self.moved_areas(x);
        self.gaps(x)
            .iter()
            .zip(&areas)
            .zip(&self.surface.curvature)
            .map(|((&g, &w), &k)| gap_column(w, g, k))
            .sum()
    }

    /// The slave's nodal areas as it moved, `W_j(u) = w_j + (A u)_j` (first order).
    fn moved_areas(&self, x: &[f64]) -> Vec<f64> {
        let o = &self.offsets;
        let (us, uu) = (&x[o.u[0]..o.u[1]], self.options.displacement_unit);
        self.surface
            .area_change
            .outer_iterator()
            .zip(&self.gap.weights)
            .map(|(row, w)| w + uu * row.iter().map(|(k, v)| v * us[k]).sum::<f64>())
            .collect()
    }
}

/// The error of an input of `body` (or "options") that is not as it must be.
fn invalid(body: &str, what: String) -> PhysicsError {
    PhysicsError::InvalidInput {
        body: body.into(),
        what,
    }
}

/// Refuses a body whose heat and elastic meshes differ in size, and an elastic body that
/// its own check refuses; the slave first.
fn check_bodies(bodies: [&ThermoElasticBody; 2]) -> Result<(), PhysicsError> {
    for b in bodies {
        if b.heat.mesh.node_count() != b.elastic.mesh.node_count() {
            return Err(invalid(
                &b.heat.name,
                format!(
                    "the heat mesh has {} nodes, the elastic mesh {}",
                    b.heat.mesh.node_count(),
                    b.elastic.mesh.node_count()
                ),
            ));
        }
        b.elastic.check()?;
    }
    Ok(())
}

/// Refuses units that are not positive and finite, a nominal gap that is not finite, a
/// negative or non-finite fixed gas pressure and a negative plenum.
fn check_options(options: &ThermoMechOptions) -> Result<(), PhysicsError> {
    for (what, v) in [
        ("displacement unit", options.displacement_unit),
        ("pressure unit", options.pressure_unit),
        ("flux unit", options.flux_unit),
    ] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(invalid(
                "options",
                format!("{what} {v} is not positive and finite"),
            ));
        }
    }
    if let Some(g) = options.nominal_gap {
        if !g.is_finite() {
            return Err(invalid("options", format!("nominal gap {g} is not finite")));
        }
    }
    match options.gas {
        GasPressure::Fixed(p) if !(p >= 0.0 && p.is_finite()) => Err(invalid(
            "options",
            format!("gas pressure {p} is not non-negative and finite"),
        )),
        GasPressure::Plenum(p) if !(p.volume >= 0.0 && p.gas_amount >= 0.0) => {
            Err(invalid("plenum", format!("{p:?} is not non-negative")))
        }
        _ => Ok(()),
    }
}

/// The scale of the equilibrium rows, `s_u = k / (E u_unit)` of the slave body, refused
/// when not positive and finite.
fn row_scale(slave: &ThermoElasticBody, options: &ThermoMechOptions) -> Result<f64, PhysicsError> {
    let row_scale = slave.heat.material.conductivity
        / (slave.elastic.material.youngs_modulus * options.displacement_unit);
    if !(row_scale > 0.0 && row_scale.is_finite()) {
        return Err(invalid(
            &slave.heat.name,
            format!("conductivity over Young's modulus gives the row scale {row_scale}"),
        ));
    }
    Ok(row_scale)
}

/// The mechanical operators of the interface of `heat` between the elastic `bodies`: the
/// normal gap (its reference gaps the nominal gap where given), the slave surface's
/// measures, and per body `int N n` over its interface surface.
fn interface_operators<TL: ConstraintLaw>(
    heat: &GapHeat<TL>,
    [es, em]: [&ElasticBody; 2],
    coupling: &CouplingOptions,
    options: &ThermoMechOptions,
) -> Result<(NormalGap, SlaveSurfaceMeasures, [Vec<f64>; 2]), PhysicsError> {
    let dim = es.components();
    let (ns, nm) = (es.mesh.node_count(), em.mesh.node_count());
    let mut gap = NormalGap::new(heat.tie(), dim, ns, nm)?;
    let interface = heat.tie().interface();
    let axis = rod_axis(coupling.geometry, dim);
    let surface = slave_surface_measures(
        interface,
        heat.tie().coupling(),
        coupling.geometry,
        heat.tie().slave_nodes(),
        dim,
        axis,
    )?;
    let gas_load = [
        surface_load(
            interface.slave(),
            es,
            Side::Slave,
            dim,
            options.elastic.geometry,
        )?,
        surface_load(
            interface.master(),
            em,
            Side::Master,
            dim,
            options.elastic.geometry,
        )?,
    ];
    if let Some(g) = options.nominal_gap {
        for (g0, w) in gap.initial.iter_mut().zip(&gap.weights) {
            *g0 = g * w;
        }
    }
    Ok((gap, surface, gas_load))
}

/// The prescribed displacements of both `bodies` (state offsets `u`, values in `unit`):
/// per displacement unknown whether it is prescribed, and each prescribed one's state
/// index and value. A free axial end ([`AxialFreedom::PlaneEnd`]) is refused where a node of
/// it is held axially.
#[allow(clippy::type_complexity)]
fn pinned_displacements(
    bodies: [&ElasticBody; 2],
    u: &[usize; 3],
    axial: &[Option<Axial>; 2],
    unit: f64,
) -> Result<(Vec<bool>, Vec<(usize, f64)>), PhysicsError> {
    let dim = bodies[0].components();
    let mut pinned = vec![false; u[2] - u[0]];
    let mut pinned_values = Vec::new();
    for (b, body) in bodies.into_iter().enumerate() {
        let (dofs, values) = body.dirichlet_dofs();
        for (d, v) in dofs.into_iter().zip(values) {
            let i = u[b] - u[0] + d as usize;
            pinned[i] = true;
            pinned_values.push((u[0] + i, v / unit));
        }
        if let Some(Axial {
            freedom: AxialFreedom::PlaneEnd(dofs),
            ..
        }) = &axial[b]
        {
            if let Some(&d) = dofs.iter().find(|&&d| pinned[u[b] - u[0] + d]) {
                return Err(invalid(
                    &body.name,
                    format!(
                        "node {} of the top end is held axially: a free end needs the \
                         axial component of its nodes free",
                        body.mesh.node_tags()[d / dim]
                    ),
                ));
            }
        }
    }
    Ok((pinned, pinned_values))
}

/// The axial unknown of `body` for the force `force` (none without one): generalized plane
/// strain in 2D Cartesian, the top end's axial components otherwise.
fn axial_freedom(
    body: &ElasticBody,
    force: Option<AxialForce>,
    options: &ElasticOptions,
) -> Result<Option<Axial>, PhysicsError> {
    let Some(force) = force else {
        return Ok(None);
    };
    if !(force.force.is_finite() && force.per_gas_pressure.is_finite()) {
        return Err(body.invalid(format!("axial force {force:?} is not finite")));
    }
    let dim = body.components();
    let axi = options.geometry.is_axisymmetric();
    let (freedom, length) = if dim == 2 && !axi {
        (
            AxialFreedom::Generalized(GeneralizedPlaneStrain::assemble(body, options)?),
            1.0,
        )
    } else {
        let k = if axi { 1 } else { 2 };
        let coords = body.mesh.coords();
        let (lo, hi) = coords
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x[k]), hi.max(x[k]))
            });
        let length = hi - lo;
        if !(length > 0.0 && length.is_finite()) {
            return Err(body.invalid(format!(
                "a free axial end needs a body of positive axial extent, not {length}"
            )));
        }
        let tol = 1e-9 * length;
        let dofs = (0..coords.len())
            .filter(|&n| coords[n][k] >= hi - tol)
            .map(|n| n * dim + k)
            .collect();
        (AxialFreedom::PlaneEnd(dofs), length)
    };
    Ok(Some(Axial {
        freedom,
        force,
        length,
    }))
}

/// `int N_a n` over the faces of `surface` (a surface of `body`'s mesh, by node tags), `n`
/// the unit normal pointing out of the body, numbered `node * dim + k`; over the revolved
/// surface (weight `2 pi r`) in the axisymmetric geometry. The faces integrated are the
/// body's own boundary faces ([`VolumeMesh::boundary_faces`](mortar_fem::mesh::VolumeMesh::boundary_faces),
/// outward by construction) whose nodes are those of a face of `surface`, so the orientation
/// the interface was given does not matter.
fn surface_load(
    surface: &SurfaceMesh,
    body: &ElasticBody,
    side: Side,
    dim: usize,
    geometry: ModelGeometry,
) -> Result<Vec<f64>, PhysicsError> {
    let mesh = &body.mesh;
    let mut faces = HashSet::new();
    for f in 0..surface.face_count() {
        let mut nodes = Vec::with_capacity(MAX_FACE_NODES);
        for &i in surface.face(f).nodes {
            let tag = surface.node_tags()[i as usize];
            nodes.push(
                mesh.node_index(tag)
                    .ok_or(PhysicsError::InterfaceNodeNotInBody { side, tag })?,
            );
        }
        nodes.sort_unstable();
        faces.insert(nodes);
    }
    let mut f = vec![0.0; mesh.node_count() * dim];
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    let mut shape = [0.0; MAX_FACE_NODES];
    for face in mesh.boundary_faces()? {
        let mut key = face.nodes.to_vec();
        key.sort_unstable();
        if !faces.contains(&key) {
            continue;
        }
        let (e, nn) = (face.element, face.nodes.len());
        for (xk, &n) in x.iter_mut().zip(&face.nodes) {
            *xk = mesh.coords()[n as usize];
        }
        let rule = QuadratureRule::cached(e.domain(), 2 * e.shape_degree() + 1)?;
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            let weight = geometry.weight(&e.map(&x[..nn], xi));
            let normal = e.scaled_normal(&x[..nn], xi) * (w * weight);
            e.shape_values_into(xi, &mut shape[..nn]);
            for (a, &node) in face.nodes.iter().enumerate() {
                for k in 0..dim {
                    f[node as usize * dim + k] += shape[a] * normal[k];
                }
            }
        }
    }
    Ok(f)
}

/// The component along a rod's axis in `geometry` with `dim` displacement components: y
/// (1) in r-z, z (2) in 3D, none in 2D.
fn rod_axis(geometry: ModelGeometry, dim: usize) -> Option<usize> {
    if geometry.is_axisymmetric() {
        Some(1)
    } else if dim == 3 {
        Some(2)
    } else {
        None
    }
}

/// The body without its temperature field (its thermal load is assembled as an operator).
fn without_temperature(body: &ElasticBody) -> ElasticBody {
    let mut b = body.clone();
    b.temperature = None;
    b
}

/// The physical quantities of a state of [`GapThermoMechanics`] (SI units by the accessors).
#[derive(Debug, Clone, Copy)]
pub struct StateView<'a> {
    /// Nodal temperatures `[slave, master]` (K).
    pub temperature: [&'a [f64]; 2],
    displacement: [&'a [f64]; 2],
    displacement_unit: f64,
    flux: &'a [f64],
    flux_unit: f64,
    contact_pressure: &'a [f64],
    pressure_unit: f64,
    /// The gas pressure (Pa).
    pub gas_pressure: f64,
    /// Per body, its axial strain when its axial direction is free
    /// ([`GapThermoMechanics::axial_strain`]).
    pub axial_strain: [Option<f64>; 2],
}

impl StateView<'_> {
    /// The displacements of body `b` (0 slave, 1 master), `node * dim + k` (m).
    pub fn displacement(&self, b: usize) -> Vec<f64> {
        self.displacement[b]
            .iter()
            .map(|v| v * self.displacement_unit)
            .collect()
    }

    /// The heat fluxes leaving the slave (W/m^2), one per slave interface node.
    pub fn flux(&self) -> Vec<f64> {
        self.flux.iter().map(|v| v * self.flux_unit).collect()
    }

    /// The contact pressures (Pa, in excess of the gas pressure), one per slave interface
    /// node.
    pub fn contact_pressure(&self) -> Vec<f64> {
        self.contact_pressure
            .iter()
            .map(|v| v * self.pressure_unit)
            .collect()
    }
}
