//! The load steps of the contact iteration: at each Newton iterate the law at every slave
//! node and the equilibrium residual, the convergence test, the Newton system and its
//! solution, the update; at the end the solution.

use std::time::Instant;

use mortar_fem::linalg::{SolverError, SparseMatrix};

use super::condensed::{condensed_step, plan_pivots};
use super::linear::{saddle_step, Backend, Linearised, Step};
use super::unknowns::Unknowns;
use super::{formulation, ContactOptions, ContactSolution, ContactStep};
use crate::contact::NormalGap;
use crate::error::PhysicsError;
use crate::field::free::{free_block, FIXED};
use crate::laws::{evaluate, ConstraintLaw, LawPoint};
use crate::linear_solve::{LinearSolve, Places};

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The contact iteration: the problem (stiffness, loads, gap, law), its unknowns, and what
/// carries from one load step to the next (the displacements and pressures, the elimination
/// order, the counts of how the systems were solved).
pub(super) struct ContactNewton<'a, L> {
    stiffness: [&'a SparseMatrix; 2],
    gap: &'a NormalGap,
    law: &'a L,
    options: &'a ContactOptions,
    unknowns: Unknowns,
    /// Where the Newton systems go.
    linear: LinearSolve<'a>,
    /// Where the free displacements sit, if a backend is told.
    free_places: Option<Places>,
    /// The loads of both bodies, concatenated.
    f: Vec<f64>,
    /// K_ff, the stiffness on the free displacements (the same in every Newton step).
    kff: SparseMatrix,
    /// The elimination order of the condensed systems, over the free displacements: computed
    /// for the first, reused for the next ones (their patterns differ in the rows of the
    /// slave nodes that change branch).
    order: Option<Vec<u32>>,
    /// The displacements of both bodies.
    u: Vec<f64>,
    /// The pressure of each slave interface node.
    p: Vec<f64>,
    /// Newton steps solved with the pressures condensed out.
    condensed_steps: usize,
    /// Condensed Newton steps solved by body.
    by_body_steps: usize,
}

/// The law and the equilibrium at one Newton iterate.
struct Iterate {
    /// The nodal gaps.
    gaps: Vec<f64>,
    /// Per row, the law's value `C`...
    c: Vec<f64>,
    /// ... its derivative in the gap, `C_g`...
    c_g: Vec<f64>,
    /// ... and in the pressure, `C_p`.
    c_p: Vec<f64>,
    /// Per row, whether `C_p = 0` (for the exact law: in contact): the branch of the law,
    /// whose settling ends the iteration.
    branch: Vec<bool>,
    /// The equilibrium residual on the free displacements.
    r_u: Vec<f64>,
    /// The equilibrium residual relative to the scale of the forces.
    res_u: f64,
    /// The law's residual relative to the largest pressure.
    res_p: f64,
}

impl Iterate {
    /// Whether both residuals are within `tolerance` (the law's also when it is zero at
    /// every node).
    fn converged(&self, tolerance: f64) -> bool {
        self.res_u <= tolerance && (self.res_p <= tolerance || self.c.iter().all(|v| *v == 0.0))
    }
}

/// The rows of the Newton system that the iterate does not hold itself: `N` on the free
/// displacements, `a = -C_g / w`, and the weighted gaps.
struct NewtonRows {
    n_free: Vec<Vec<(u32, f64)>>,
    a: Vec<f64>,
    weighted_gap: Vec<f64>,
}

impl<'a, L: ConstraintLaw> ContactNewton<'a, L> {
    /// The iteration from zero displacements and pressures.
    pub fn new(
        stiffness: [&'a SparseMatrix; 2],
        load: [&[f64]; 2],
        gap: &'a NormalGap,
        law: &'a L,
        options: &'a ContactOptions,
        unknowns: Unknowns,
        linear: LinearSolve<'a>,
    ) -> Self {
        let f = load[0].iter().chain(load[1]).copied().collect();
        let free_places = linear.backend.and(free_places(&unknowns, &linear, gap.dim));
        let kff = free_block(&stiffness, &unknowns.free, unknowns.nfree);
        let (u, p) = (vec![0.0; unknowns.ndof], vec![0.0; gap.weights.len()]);
        Self {
            stiffness,
            gap,
            law,
            options,
            unknowns,
            linear,
            free_places,
            f,
            kff,
            order: None,
            u,
            p,
            condensed_steps: 0,
            by_body_steps: 0,
        }
    }

    /// Load step `s` of `load_steps`: the Dirichlet values and loads at `s / load_steps` of
    /// theirs, Newton steps until the branch of the law has settled and both residuals are
    /// within the tolerance.
    ///
    /// # Errors
    /// The law's errors; [`singular_system`] for a singular Newton system; [`not_converged`]
    /// when the steps run out.
    pub fn load_step(&mut self, s: usize, load_steps: usize) -> Result<ContactStep, PhysicsError> {
        let factor = s as f64 / load_steps as f64;
        self.unknowns.impose(factor, &mut self.u);
        let t_step = Instant::now();
        let mut linear_seconds = Vec::new();
        let mut regularised = 0usize;
        let mut last_held = false;
        let mut residuals = Vec::new();
        let mut branch_prev: Option<Vec<bool>> = None;
        let mut settled_at = None;
        let mut converged = false;
        let mut taken = 0usize;
        for it in 0..=self.options.max_newton_steps {
            let at = self.iterate(factor)?;
            residuals.push(at.res_u);
            let same_branch = branch_prev.as_ref() == Some(&at.branch);
            if it > 0 && same_branch && at.converged(self.options.tolerance) {
                converged = true;
                break;
            }
            if it == self.options.max_newton_steps {
                break;
            }
            if !same_branch {
                settled_at = Some(it);
            }
            let rows = self.newton_rows(&at);
            let t_linear = Instant::now();
            let (du, dp, held) = self
                .increment(&at, &rows)
                .map_err(|e| singular_system(e, s, it, &at.branch))?;
            linear_seconds.push(t_linear.elapsed().as_secs_f64());
            regularised += usize::from(held);
            last_held = held;
            self.unknowns.add_free(&mut self.u, &du);
            for j in 0..self.p.len() {
                self.p[j] += dp[j];
            }
            taken = it + 1;
            branch_prev = Some(at.branch);
        }
        if !converged {
            return Err(not_converged(s, taken, residuals, regularised, last_held));
        }
        Ok(ContactStep {
            load_factor: factor,
            newton_steps: taken,
            settled_at,
            residuals,
            active: self.p.iter().filter(|&&v| v > 0.0).count(),
            linear_seconds,
            regularised,
            seconds: t_step.elapsed().as_secs_f64(),
        })
    }

    /// The law and the residuals at the current displacements and pressures, the load at
    /// `factor`.
    fn iterate(&self, factor: f64) -> Result<Iterate, PhysicsError> {
        let gaps = self.gap.nodal(&self.u);
        let (c, c_g, c_p) = self.law_values(&gaps)?;
        let branch = c_p.iter().map(|&d| d == 0.0).collect();
        let (r_u, res_u) = self.equilibrium(factor);
        let res_p = self.law_residual(&c, &c_g, &c_p);
        Ok(Iterate {
            gaps,
            c,
            c_g,
            c_p,
            branch,
            r_u,
            res_u,
            res_p,
        })
    }

    /// Per row, the law's value and its derivatives in the gap and in the pressure at the
    /// nodal gaps `gaps`; a row without multiplier holds its pressure at zero (`C = p`).
    #[allow(clippy::type_complexity)]
    fn law_values(&self, gaps: &[f64]) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>), PhysicsError> {
        let (gap, p) = (self.gap, &self.p);
        let rows = gap.weights.len();
        let mut c = vec![0.0; rows];
        let mut c_g = vec![0.0; rows];
        let mut c_p = vec![0.0; rows];
        for j in 0..rows {
            if !gap.carries[j] {
                // No multiplier at this node: its pressure is held at zero (C = p).
                (c[j], c_p[j]) = (p[j], 1.0);
                continue;
            }
            let t = evaluate(self.law, LawPoint::new(gaps[j], p[j], 0.0))?;
            c[j] = t.value;
            c_g[j] = t.d_gap;
            c_p[j] = t.d_multiplier;
        }
        Ok((c, c_g, c_p))
    }

    /// The equilibrium residual `K u - factor f + N^T p` on the free displacements, and its
    /// norm relative to the scale of the forces.
    fn equilibrium(&self, factor: f64) -> (Vec<f64>, f64) {
        let free = &self.unknowns.free;
        let ku = self.k_times(&self.u);
        let ntp = self.gap_t_times(&self.p);
        let mut r_u = vec![0.0; self.unknowns.nfree];
        for g in 0..self.unknowns.ndof {
            if free[g] != FIXED {
                r_u[free[g] as usize] = ku[g] - factor * self.f[g] + ntp[g];
            }
        }
        // The scale of the forces: applied, contact, or (for a displacement-driven load,
        // before contact) the elastic forces of the prescribed displacements.
        let scale_u = (factor * norm(&self.f))
            .max(norm(&ntp))
            .max(norm(&ku))
            .max(f64::MIN_POSITIVE);
        let res_u = norm(&r_u) / scale_u;
        (r_u, res_u)
    }

    /// The largest law residual `|C_j|` relative to the largest pressure.
    fn law_residual(&self, c: &[f64], c_g: &[f64], c_p: &[f64]) -> f64 {
        let p = &self.p;
        let p_max = p.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        // A node's law residual counts as zero within what the rounding of its gap and
        // pressure alone gives (a stiff penalty, `dC/dg` of 1e18 Pa/m, turns the 1e-20 m
        // rounding of a gap into 1e-9 of the pressure).
        let gap_rounding = self.gap.nodal_rounding(&self.u);
        (0..c.len())
            .map(|j| {
                let floor =
                    c_g[j].abs() * gap_rounding[j] + c_p[j].abs() * 8.0 * f64::EPSILON * p[j].abs();
                if c[j].abs() <= floor {
                    0.0
                } else {
                    c[j].abs()
                }
            })
            .fold(0.0f64, f64::max)
            / p_max.max(f64::MIN_POSITIVE)
    }

    /// `K u`, the block-diagonal stiffness of both bodies times `u`.
    fn k_times(&self, u: &[f64]) -> Vec<f64> {
        let n = self.unknowns.n;
        let mut out = vec![0.0; self.unknowns.ndof];
        for (g, o) in out.iter_mut().enumerate() {
            let (b, i) = if g < n[0] { (0, g) } else { (1, g - n[0]) };
            let off = if b == 0 { 0 } else { n[0] };
            if let Some(row) = self.stiffness[b].outer_view(i) {
                *o = row.iter().map(|(j, v)| v * u[off + j]).sum();
            }
        }
        out
    }

    /// `N^T p`, the contact forces of the pressures `p`.
    fn gap_t_times(&self, p: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.unknowns.ndof];
        for (j, row) in self.gap.matrix.outer_iterator().enumerate() {
            for (k, v) in row.iter() {
                out[k] += v * p[j];
            }
        }
        out
    }

    /// The rows of the Newton system at `at` that it does not hold itself.
    fn newton_rows(&self, at: &Iterate) -> NewtonRows {
        let gap = self.gap;
        let rows = gap.weights.len();
        let a = (0..rows)
            .map(|j| {
                if gap.carries[j] {
                    -at.c_g[j] / gap.weights[j]
                } else {
                    0.0
                }
            })
            .collect();
        NewtonRows {
            n_free: self.unknowns.free_rows(gap),
            a,
            weighted_gap: (0..rows).map(|j| gap.weights[j] * at.gaps[j]).collect(),
        }
    }

    /// The Newton step at `at`: with the pressures condensed out where D is diagonal and
    /// every active row has a pivot ([`plan_pivots`]), else the saddle point.
    fn increment(&mut self, at: &Iterate, rows: &NewtonRows) -> Result<Step, SolverError> {
        let lin = Linearised {
            nfree: self.unknowns.nfree,
            slave_free: self.unknowns.slave_free,
            weighted_gap: &rows.weighted_gap,
            r_u: &at.r_u,
            n_free: &rows.n_free,
            a: &rows.a,
            c: &at.c,
            c_p: &at.c_p,
        };
        let backend = self.linear.backend.map(|solver| Backend {
            solver,
            free_places: self.free_places.as_ref(),
        });
        let pivots = if self.gap.diagonal {
            plan_pivots(&lin, &self.unknowns.free_of_slave)
        } else {
            None
        };
        match pivots {
            Some(pivots) => {
                self.condensed_steps += 1;
                condensed_step(
                    &lin,
                    &self.kff,
                    &pivots,
                    &mut self.order,
                    &mut self.by_body_steps,
                    backend,
                )
            }
            None => saddle_step(&lin, &self.kff, backend),
        }
    }

    /// The solution after the load steps `steps`: both bodies' displacements, the pressures
    /// (interpolated at the nodes without multiplier), the gaps, the force, and how the
    /// systems were solved.
    pub fn into_solution(self, steps: Vec<ContactStep>) -> ContactSolution {
        let Self {
            gap,
            unknowns,
            mut u,
            mut p,
            condensed_steps,
            by_body_steps,
            linear,
            ..
        } = self;
        let gaps = gap.nodal(&u);
        let force = p.iter().zip(&gap.weights).map(|(p, w)| p * w).sum();
        // The pressure the corners' multipliers stand for, at the nodes without one.
        gap.interpolate_rows_without_multiplier(&mut p);
        let total_steps: usize = steps.iter().map(|s| s.newton_steps).sum();
        let formulation = formulation(
            gap.diagonal,
            condensed_steps,
            by_body_steps,
            total_steps,
            linear.backend.is_some(),
        );
        let master = u.split_off(unknowns.n[0]);
        ContactSolution {
            formulation,
            displacements: [u, master],
            pressure: p,
            gap: gaps,
            force,
            steps,
        }
    }
}

/// The error of a Newton system that could not be solved at load step `s`, Newton step `it`
/// (`branch`: the rows in contact): a singular or indefinite one is a body held in some
/// direction by nothing but contact that has not closed, and says so; another solver error
/// passes through.
fn singular_system(e: SolverError, s: usize, it: usize, branch: &[bool]) -> PhysicsError {
    match e {
        SolverError::Singular { .. } | SolverError::NotPositiveDefinite { .. } => {
            PhysicsError::InvalidInput {
                body: "contact".into(),
                what: format!(
                    "the Newton system is singular at load step {s}, Newton step {it} \
                     ({} of {} slave nodes in contact): a body is not held against \
                     rigid motion in some direction but by contact, and contact does \
                     not hold it there (yet); fix it with a Dirichlet condition in that \
                     direction, or load it by a prescribed displacement ({e})",
                    branch.iter().filter(|&&a| a).count(),
                    branch.len()
                ),
            }
        }
        e @ SolverError::NotConverged { .. } => PhysicsError::LinearSolve {
            system: format!(
                "the contact Newton system at load step {s}, Newton step {it} ({} of {} slave \
                 nodes in contact): its iterative solve did not converge; loosen \
                 [solve] linear_tolerance, allow more iterations (petsc_options \
                 \"-ksp_max_it N\"), or solve it directly (backend = \"direct\")",
                branch.iter().filter(|&&a| a).count(),
                branch.len()
            ),
            source: e,
        },
        e => e.into(),
    }
}

/// The error of load step `s` that did not converge in `taken` Newton steps: a body pulled
/// off, when the last system still needed the contact springs (`last_held`, of `regularised`
/// such), else Newton's failure with the `residuals`.
fn not_converged(
    s: usize,
    taken: usize,
    residuals: Vec<f64>,
    regularised: usize,
    last_held: bool,
) -> PhysicsError {
    if last_held {
        return PhysicsError::InvalidInput {
            body: "contact".into(),
            what: format!(
                "Newton did not converge at load step {s} ({taken} steps, relative \
                 residual {:.1e}), and its last system (of {regularised} such) still had a \
                 rigid mode held by nothing but the contact springs: a body is not held against rigid \
                 motion in some direction but by contact, and contact does not hold it \
                 there (pulled off?); fix it with a Dirichlet condition in that \
                 direction, or load it by a prescribed displacement",
                residuals.last().copied().unwrap_or(f64::NAN)
            ),
        };
    }
    PhysicsError::Newton(crate::nonlinear::NewtonFailure {
        reason: crate::nonlinear::NewtonFailureReason::MaxIterations,
        iterations: taken,
        residual_history: residuals,
    })
}

/// Where the free displacements of `unknowns` sit (in the free numbering, `dim` components
/// per node), if `linear` tells both bodies' nodes.
fn free_places(unknowns: &Unknowns, linear: &LinearSolve<'_>, dim: usize) -> Option<Places> {
    let n0 = unknowns.n[0];
    let dofs = (0..unknowns.ndof)
        .filter(|&g| unknowns.free[g] != FIXED)
        .map(|g| if g < n0 { (0, g) } else { (1, g - n0) });
    Places::of(linear, dim, dofs)
}
