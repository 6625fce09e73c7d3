//! The Newton (semi-smooth for the exact law) iteration of frictionless contact.
//!
//! [`solve_contact`] runs it as named steps: the sizes are checked (`check_sizes`), the
//! unknowns numbered (`unknowns`), each load step iterated (`newton`), each Newton system
//! solved with the pressures condensed out where D is diagonal (`condensed`) or as the
//! saddle point (`linear`), and the solution put together.

mod condensed;
mod linear;
mod newton;
mod unknowns;

use mortar_fem::linalg::SparseMatrix;

use super::normal::NormalGap;
use crate::error::PhysicsError;
use crate::laws::ConstraintLaw;
use crate::linear_solve::LinearSolve;
use crate::tied::Tie;
use newton::ContactNewton;
use unknowns::Unknowns;

/// Settings of [`solve_contact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOptions {
    /// Load steps: the loads and Dirichlet values are applied in this many equal increments.
    pub load_steps: usize,
    /// Newton steps allowed per load step.
    pub max_newton_steps: usize,
    /// Convergence: the equilibrium residual relative to the applied and contact forces, and
    /// the law's residual relative to the largest pressure, both below this.
    pub tolerance: f64,
}

impl Default for ContactOptions {
    fn default() -> Self {
        Self {
            load_steps: 1,
            max_newton_steps: 30,
            tolerance: 1e-10,
        }
    }
}

/// One load step of [`solve_contact`].
#[derive(Debug, Clone, PartialEq)]
pub struct ContactStep {
    /// The fraction of the load applied.
    pub load_factor: f64,
    /// Newton steps taken.
    pub newton_steps: usize,
    /// The Newton step after which the branch of the law at every node (for the exact law,
    /// the active set) stopped changing; `None` if it changed at the last step.
    pub settled_at: Option<usize>,
    /// The relative equilibrium residual before each step and at the end.
    pub residuals: Vec<f64>,
    /// Slave nodes in contact (pressure positive) at the end of the step.
    pub active: usize,
    /// Seconds of each Newton step's linear solve (building the condensed or saddle-point
    /// system, factorising, solving).
    pub linear_seconds: Vec<f64>,
    /// Newton steps whose system had a rigid mode held by nothing (a body held only by
    /// contact before it touches, or on a flat branch of a regularised law), so that each
    /// slave node without contact stiffness got a spring for that step only (the residual,
    /// hence the solution, unchanged; only the step's size made definite).
    pub regularised: usize,
    /// Seconds of the whole load step.
    pub seconds: f64,
}

/// The solution of [`solve_contact`].
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSolution {
    /// Displacements of the slave body and of the master body (`node * dim + k`).
    pub displacements: [Vec<f64>; 2],
    /// The contact pressure at each slave interface node (coupling row order), Pa; at a node
    /// without multiplier (linear multipliers on second-order faces), the first-order
    /// interpolation of its face's corners' pressures.
    pub pressure: Vec<f64>,
    /// The nodal normal gap at each slave interface node, m (positive open; interpolated
    /// likewise at a node without multiplier).
    pub gap: Vec<f64>,
    /// The total normal contact force, `sum_j w_j p_j` (N, or N/m in 2D).
    pub force: f64,
    /// The load steps.
    pub steps: Vec<ContactStep>,
    /// How the Newton systems were solved, and why.
    pub formulation: String,
}

/// The complementarity parameter `c` (Pa/m) of the order of the slave body's stiffness over
/// its element size: the median over slave interface nodes of the mean diagonal stiffness of
/// the node's displacement unknowns over its area `w_j`. Any positive `c` gives the same
/// solution; this one makes the active and inactive rows of the Newton system of comparable
/// size, so that the user never tunes it.
pub fn automatic_complementarity(
    slave_stiffness: &SparseMatrix,
    tie: &Tie,
    gap: &NormalGap,
    dim: usize,
) -> f64 {
    let mut ratios: Vec<f64> = tie
        .slave_nodes()
        .iter()
        .zip(&gap.weights)
        .map(|(&node, &w)| {
            let k: f64 = (0..dim)
                .map(|a| {
                    let i = node as usize * dim + a;
                    slave_stiffness
                        .outer_view(i)
                        .and_then(|r| r.get(i).copied())
                        .unwrap_or(0.0)
                })
                .sum();
            k / dim as f64 / w
        })
        .filter(|r| r.is_finite() && *r > 0.0)
        .collect();
    if ratios.is_empty() {
        return 1.0;
    }
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// Solves frictionless contact between two bodies of stiffness `stiffness = [K_s, K_m]`
/// (displacement unknowns `node * dim + k` each), loads `load`, Dirichlet unknowns and values
/// `dirichlet = [(dofs, values); 2]`, through the weighted gap `gap` and the law `law` (see
/// the [module](super) documentation), in `options.load_steps` increments.
///
/// # Errors
/// [`PhysicsError::WrongLength`] for mismatched sizes; [`PhysicsError::InvalidInput`] for a
/// body without any Dirichlet unknown (held against rigid motion only by contact, which a
/// linear solve cannot do before contact is established) or a Dirichlet unknown out of range;
/// [`PhysicsError::Law`] if the law fails at a node; [`PhysicsError::InvalidInput`] naming the
/// load and Newton step for a singular Newton system (a body held in some direction by
/// nothing but contact that has not closed), [`PhysicsError::Solver`] for another solver
/// failure; [`PhysicsError::Newton`] when a load step does not converge.
pub fn solve_contact<L: ConstraintLaw>(
    stiffness: [&SparseMatrix; 2],
    load: [&[f64]; 2],
    dirichlet: [(&[u32], &[f64]); 2],
    gap: &NormalGap,
    law: &L,
    options: &ContactOptions,
) -> Result<ContactSolution, PhysicsError> {
    solve_contact_on(
        stiffness,
        load,
        dirichlet,
        gap,
        law,
        options,
        LinearSolve::default(),
    )
}

/// [`solve_contact`] with its Newton systems solved where `linear` says: by a backend of the
/// solver interface (PETSc's, say) instead of the direct solves, told where the bodies'
/// unknowns sit. The condensed systems go to it as symmetric positive definite (as general
/// matrices if that solve fails), the saddle points of a non-diagonal D with the pressures
/// last.
///
/// # Errors
/// As [`solve_contact`], and the backend's errors (a Krylov solve that does not converge:
/// [`PhysicsError::Newton`] naming the load step and iteration, with the solver's error).
pub fn solve_contact_on<L: ConstraintLaw>(
    stiffness: [&SparseMatrix; 2],
    load: [&[f64]; 2],
    dirichlet: [(&[u32], &[f64]); 2],
    gap: &NormalGap,
    law: &L,
    options: &ContactOptions,
    linear: LinearSolve<'_>,
) -> Result<ContactSolution, PhysicsError> {
    check_sizes(stiffness, load, dirichlet, gap)?;
    let unknowns = Unknowns::new(stiffness, dirichlet, gap)?;
    let mut newton = ContactNewton::new(stiffness, load, gap, law, options, unknowns, linear);
    let load_steps = options.load_steps.max(1);
    let mut steps = Vec::with_capacity(options.load_steps.max(1));
    for s in 1..=load_steps {
        steps.push(newton.load_step(s, load_steps)?);
    }
    Ok(newton.into_solution(steps))
}

/// The error for a size of the input that does not match the stiffness.
pub(super) fn wrong_length(what: &str, expected: usize, got: usize) -> PhysicsError {
    PhysicsError::WrongLength {
        what: what.into(),
        expected,
        got,
    }
}

/// Refuses inputs whose sizes disagree with the stiffness, and a body without any Dirichlet
/// unknown (before contact closes, nothing would hold it against rigid motion), body by body
/// and then the gap, so that the first mismatch is the one reported.
fn check_sizes(
    stiffness: [&SparseMatrix; 2],
    load: [&[f64]; 2],
    dirichlet: [(&[u32], &[f64]); 2],
    gap: &NormalGap,
) -> Result<(), PhysicsError> {
    let n = [stiffness[0].rows(), stiffness[1].rows()];
    let ndof = n[0] + n[1];
    for b in 0..2 {
        if stiffness[b].cols() != n[b] {
            return Err(wrong_length("stiffness columns", n[b], stiffness[b].cols()));
        }
        if load[b].len() != n[b] {
            return Err(wrong_length("load", n[b], load[b].len()));
        }
        if dirichlet[b].0.len() != dirichlet[b].1.len() {
            return Err(wrong_length(
                "Dirichlet values",
                dirichlet[b].0.len(),
                dirichlet[b].1.len(),
            ));
        }
        if dirichlet[b].0.is_empty() {
            return Err(PhysicsError::InvalidInput {
                body: ["slave", "master"][b].into(),
                what: "the body has no Dirichlet condition: held against rigid motion only by \
                       contact, it cannot be solved for before contact is established (fix \
                       it in the loaded direction, or load it by a prescribed displacement)"
                    .into(),
            });
        }
    }
    if gap.matrix.cols() != ndof {
        return Err(wrong_length("normal gap columns", ndof, gap.matrix.cols()));
    }
    Ok(())
}

/// What [`ContactSolution::formulation`] says: the saddle point when D is not diagonal, else
/// the condensation, with how many of the `total_steps` Newton steps were condensed
/// (`condensed_steps`) and solved by body (`by_body_steps`), and which solve: the direct
/// factorisations, or (`on_backend`) the backend the systems went to, whose reports say its
/// method.
fn formulation(
    diagonal: bool,
    condensed_steps: usize,
    by_body_steps: usize,
    total_steps: usize,
    on_backend: bool,
) -> String {
    let (lu, cholesky) = if on_backend {
        ("the linear solver's backend", "the linear solver's backend")
    } else {
        ("sparse LU", "sparse Cholesky")
    };
    if !diagonal {
        format!(
            "saddle point of displacements and pressures, {lu}: D is not diagonal (standard \
             or linear multipliers, or a partly covered interface), so the pressures cannot be \
             condensed"
        )
    } else if condensed_steps == total_steps {
        let by_body = match by_body_steps {
            0 => String::new(),
            k if k == total_steps => " by body (the two bodies factorised side by side, the \
                                       unknowns between them last)"
                .to_string(),
            k => format!(" (by body, the two bodies side by side, in {k} of {total_steps} steps)"),
        };
        format!(
            "pressures condensed out (D is diagonal: dual multipliers), symmetric system of the \
             displacements less one unknown per slave node in contact, {cholesky}{by_body}"
        )
    } else {
        format!(
            "pressures condensed out in {condensed_steps} of {total_steps} Newton steps (D is \
             diagonal, {cholesky}); the saddle point ({lu}) where a node in contact had no \
             free displacement along its normal"
        )
    }
}
