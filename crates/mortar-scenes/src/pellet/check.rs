//! The pellet scene's check, by concern: the kind, the heat problem's data, the geometry and
//! mesh size, the time and solver settings, the gap law, the materials' elasticity, the
//! mechanics' data, the `[model]` choices that go together, and the mesh file. Each step
//! returns the first value it refuses, in this order.

use super::{AxialModel, Geometry, PelletError, PelletScene, SolverMethod};
use crate::linear_solver::BackendChoice;

/// A value out of range: the check's error.
fn bad(what: String) -> Result<(), PelletError> {
    Err(PelletError::Invalid(what))
}

/// Each `(key, value)` positive and finite.
fn positive(values: &[(&str, f64)]) -> Result<(), PelletError> {
    for &(what, v) in values {
        if !(v > 0.0 && v.is_finite()) {
            return bad(format!("{what} = {v} is not positive and finite"));
        }
    }
    Ok(())
}

/// Each `(key, value)` non-negative and finite.
fn non_negative(values: &[(&str, f64)]) -> Result<(), PelletError> {
    for &(what, v) in values {
        if !(v >= 0.0 && v.is_finite()) {
            return bad(format!("{what} = {v} is not non-negative and finite"));
        }
    }
    Ok(())
}

impl PelletScene {
    /// Checks the values.
    ///
    /// # Errors
    /// [`PelletError::Invalid`] naming the first value out of range.
    pub fn check(&self) -> Result<(), PelletError> {
        if let Some(s) = &self.scene {
            if s != "pellet" {
                return bad(format!("scene = {s:?} is not \"pellet\""));
            }
        }
        self.check_heat_data()?;
        self.check_geometry()?;
        self.check_time_and_solver()?;
        self.gap_law()?;
        self.check_elasticity()?;
        self.check_mechanics_data()?;
        self.check_model()?;
        self.check_mesh_file()
    }

    /// The heat problem's data: radius, conductivities, temperature, time step and solver
    /// tolerance positive; the other conductivity term, heat capacities, power, ramp and end
    /// time non-negative.
    fn check_heat_data(&self) -> Result<(), PelletError> {
        let (p, c) = (&self.pellet, &self.cladding);
        positive(&[
            ("pellet.radius", p.radius),
            ("pellet.conductivity_a", p.conductivity_a),
            ("cladding.conductivity", c.conductivity),
            ("cladding.outer_temperature", c.outer_temperature),
            ("time.step", self.time.step),
            ("solver.relative_tolerance", self.solver.relative_tolerance),
        ])?;
        non_negative(&[
            ("pellet.conductivity_b", p.conductivity_b),
            ("pellet.heat_capacity", p.heat_capacity),
            ("cladding.heat_capacity", c.heat_capacity),
            ("power.linear_power", self.power.linear_power),
            ("power.ramp_time", self.power.ramp_time),
            ("time.end", self.time.end),
        ])
    }

    /// The radii in order (pellet inside the cladding's bore, the bore inside its outer
    /// surface) and the mesh refinement in range.
    fn check_geometry(&self) -> Result<(), PelletError> {
        let (p, c) = (&self.pellet, &self.cladding);
        if !(p.radius < c.inner_radius
            && c.inner_radius < c.outer_radius
            && c.outer_radius.is_finite())
        {
            return bad(format!(
                "radii must satisfy pellet.radius < cladding.inner_radius < cladding.outer_radius (got {}, {}, {})",
                p.radius, c.inner_radius, c.outer_radius
            ));
        }
        if self.mesh.refinement == 0 || self.mesh.refinement > 64 {
            return bad(format!(
                "mesh.refinement = {} is not in 1..=64",
                self.mesh.refinement
            ));
        }
        Ok(())
    }

    /// The solver's iteration limits positive, and not too many time steps.
    fn check_time_and_solver(&self) -> Result<(), PelletError> {
        if self.solver.max_iterations == 0 || self.solver.gmres_restart == 0 {
            return bad("solver.max_iterations and solver.gmres_restart must be positive".into());
        }
        if self.solver.backend == BackendChoice::Petsc && self.solver.method == SolverMethod::Jfnk {
            return bad(
                "solver.backend = \"petsc\" solves Newton's Jacobians: method = \"jfnk\" \
                        would not use it (method = \"newton\" or \"auto\")"
                    .into(),
            );
        }
        self.solver.linear_solver(usize::MAX)?;
        if self.time.end / self.time.step > 1e6 {
            return bad(format!(
                "time.end / time.step = {} steps is too many",
                self.time.end / self.time.step
            ));
        }
        Ok(())
    }

    /// Each body's Young's modulus positive, Poisson's ratio in (-1, 0.5), thermal expansion
    /// non-negative.
    fn check_elasticity(&self) -> Result<(), PelletError> {
        let (p, c) = (&self.pellet, &self.cladding);
        for (what, e, nu, alpha) in [
            (
                "pellet",
                p.youngs_modulus,
                p.poisson_ratio,
                p.thermal_expansion,
            ),
            (
                "cladding",
                c.youngs_modulus,
                c.poisson_ratio,
                c.thermal_expansion,
            ),
        ] {
            if !(e > 0.0 && e.is_finite()) {
                return bad(format!(
                    "{what}.youngs_modulus = {e} is not positive and finite"
                ));
            }
            if !(nu > -1.0 && nu < 0.5) {
                return bad(format!("{what}.poisson_ratio = {nu} is not in (-1, 0.5)"));
            }
            if !(alpha >= 0.0 && alpha.is_finite()) {
                return bad(format!(
                    "{what}.thermal_expansion = {alpha} is not non-negative and finite"
                ));
            }
        }
        Ok(())
    }

    /// The mechanics' data: pressures, the contact conductance and stiffness exponent and the
    /// plenum's volume non-negative; the plenum's fill temperature and the model's reference
    /// temperature positive; the contact law's onset gap finite.
    fn check_mechanics_data(&self) -> Result<(), PelletError> {
        let (c, ct, pl, m) = (&self.cladding, &self.contact, &self.plenum, &self.model);
        non_negative(&[
            ("cladding.coolant_pressure", c.coolant_pressure),
            ("gap.contact_conductance", self.gap.contact_conductance),
            ("contact.stiffness_exponent", ct.stiffness_exponent),
            ("plenum.fill_pressure", pl.fill_pressure),
            ("plenum.volume", pl.volume),
        ])?;
        positive(&[
            ("plenum.fill_temperature", pl.fill_temperature),
            ("model.reference_temperature", m.reference_temperature),
        ])?;
        if !ct.onset_gap.is_finite() {
            return bad(format!(
                "contact.onset_gap = {} is not finite",
                ct.onset_gap
            ));
        }
        Ok(())
    }

    /// `[model]`: a burnup in range that a relocation model sees, and the choices that go
    /// together: relocation, a geometry other than the plane one, and laws by name only with
    /// the mechanics; generalized plane strain with the plane geometry; a positive segment
    /// height.
    fn check_model(&self) -> Result<(), PelletError> {
        let m = &self.model;
        if !(m.burnup >= 0.0 && m.burnup.is_finite()) {
            return bad(format!(
                "model.burnup = {} is not non-negative and finite (MWd/kgU)",
                m.burnup
            ));
        }
        if m.burnup != 0.0 && m.relocation == "none" {
            return bad(format!(
                "model.burnup = {} has no effect with model.relocation = \"none\": the \
                 burnup is what the relocation model sees (give model.relocation = \
                 \"frapcon\", say)",
                m.burnup
            ));
        }
        if m.relocation != "none" && !m.mechanics {
            return bad(format!(
                "model.relocation = {:?} with model.mechanics = false: relocation moves the \
                 pellet, which the heat-only scene holds",
                m.relocation
            ));
        }
        if m.geometry == Geometry::PlaneStrain && m.axial == Some(AxialModel::Generalized) {
            return bad(
                "model.geometry = \"plane_strain\" with model.axial = \"generalized\": give \
                 geometry = \"plane\" for generalized plane strain"
                    .into(),
            );
        }
        if !m.geometry.is_plane() && !m.mechanics {
            return bad(format!(
                "model.geometry = {:?} with model.mechanics = false: the thermal scene is the 2D \
                 cross-section",
                m.geometry
            ));
        }
        // The thermal scene makes its gap conductance from [gap] alone: a law by name would
        // be passed over.
        for (what, set) in [
            ("laws.thermal", self.laws.thermal.is_some()),
            ("laws.contact", self.laws.contact.is_some()),
        ] {
            if set && !m.mechanics {
                return bad(format!(
                    "{what} with model.mechanics = false: the thermal scene holds the gap at its \
                     as-built width with the law of [gap]; laws by name are for the \
                     thermomechanical scene"
                ));
            }
        }
        // The heat-only scene solves directly: PETSc asked for would be passed over.
        if self.solver.backend == BackendChoice::Petsc && !m.mechanics {
            return bad(
                "solver.backend = \"petsc\" with model.mechanics = false: the heat-only scene \
                 solves its Newton systems directly; PETSc takes the thermomechanical scene's"
                    .into(),
            );
        }
        if !(m.segment_height > 0.0 && m.segment_height.is_finite()) {
            return bad(format!(
                "model.segment_height = {} is not positive and finite",
                m.segment_height
            ));
        }
        Ok(())
    }

    /// `[mesh]`: a mesh file only for the thermomechanical 2D or r-z scene, and the axial
    /// layers in range.
    fn check_mesh_file(&self) -> Result<(), PelletError> {
        let m = &self.model;
        if self.mesh.file.is_some() && (m.geometry == Geometry::ThreeD || !m.mechanics) {
            return bad(format!(
                "mesh.file with model.geometry = {:?} and model.mechanics = {}: a mesh file is \
                 the 2D cross-section or the r-z section of the thermomechanical scene",
                m.geometry, m.mechanics
            ));
        }
        if self.mesh.axial_layers == 0 || self.mesh.axial_layers > 64 {
            return bad(format!(
                "mesh.axial_layers = {} is not in 1..=64",
                self.mesh.axial_layers
            ));
        }
        Ok(())
    }
}
