//! The Newton (semi-smooth for the exact law) iteration of frictionless contact.

use std::time::Instant;

use mortar_fem::linalg::{
    fill_reducing_ordering, inf_norm, well_conditioned, CholeskyFactorization, MatrixKind,
    SolverError, SparseMatrix, SubstructuredCholesky, Triplets,
};

use super::normal::NormalGap;
use crate::error::PhysicsError;
use crate::field::free::{free_block, free_numbering, FIXED};
use crate::laws::{evaluate, ConstraintLaw, LawPoint};
use crate::tied::Tie;
use crate::SOLVER;

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

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
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
    let n = [stiffness[0].rows(), stiffness[1].rows()];
    let ndof = n[0] + n[1];
    let wrong = |what: &str, expected: usize, got: usize| PhysicsError::WrongLength {
        what: what.into(),
        expected,
        got,
    };
    for b in 0..2 {
        if stiffness[b].cols() != n[b] {
            return Err(wrong("stiffness columns", n[b], stiffness[b].cols()));
        }
        if load[b].len() != n[b] {
            return Err(wrong("load", n[b], load[b].len()));
        }
        if dirichlet[b].0.len() != dirichlet[b].1.len() {
            return Err(wrong(
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
        return Err(wrong("normal gap columns", ndof, gap.matrix.cols()));
    }
    // Unknown numbering: free displacements, then the pressures.
    const NONE: u32 = FIXED;
    let mut fixed = Vec::new();
    let mut fixed_value = vec![0.0; ndof];
    for b in 0..2 {
        let offset = if b == 0 { 0 } else { n[0] };
        for (&d, &v) in dirichlet[b].0.iter().zip(dirichlet[b].1) {
            if d as usize >= n[b] {
                return Err(PhysicsError::InvalidInput {
                    body: ["slave", "master"][b].into(),
                    what: format!("Dirichlet unknown {d} out of range ({})", n[b]),
                });
            }
            fixed.push((offset + d as usize) as u32);
            fixed_value[offset + d as usize] = v;
        }
    }
    let (free, nfree) = free_numbering(ndof, &fixed);
    // Free indices below this are the slave body's (the numbering increases with the unknown).
    let slave_free = free[..n[0]].iter().filter(|&&f| f != FIXED).count();
    let rows = gap.weights.len();
    let dim = gap.dim;
    if rows > 0
        && gap
            .slave_node
            .iter()
            .any(|&v| (v as usize + 1) * dim > n[0])
    {
        return Err(wrong(
            "slave stiffness (interface nodes beyond it)",
            ndof,
            n[0],
        ));
    }
    // Per row, the free indices of its slave node's displacement components.
    let free_of_slave: Vec<Vec<u32>> = gap
        .slave_node
        .iter()
        .map(|&node| (0..dim).map(|k| free[node as usize * dim + k]).collect())
        .collect();
    let mut condensed_steps = 0usize;
    let mut by_body_steps = 0usize;
    let f: Vec<f64> = load[0].iter().chain(load[1]).copied().collect();
    // The global stiffness, block diagonal.
    let entry = |g: usize| -> (usize, usize) {
        if g < n[0] {
            (0, g)
        } else {
            (1, g - n[0])
        }
    };
    let k_times = |u: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; ndof];
        for (g, o) in out.iter_mut().enumerate() {
            let (b, i) = entry(g);
            let off = if b == 0 { 0 } else { n[0] };
            if let Some(row) = stiffness[b].outer_view(i) {
                *o = row.iter().map(|(j, v)| v * u[off + j]).sum();
            }
        }
        out
    };
    let gap_t_times = |p: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; ndof];
        for (j, row) in gap.matrix.outer_iterator().enumerate() {
            for (k, v) in row.iter() {
                out[k] += v * p[j];
            }
        }
        out
    };

    // K_ff, the stiffness on the free displacements (the same in every Newton step).
    let kff = free_block(&stiffness, &free, nfree);
    // The elimination order of the condensed systems, over the free displacements: computed
    // for the first, reused for the next ones (their patterns differ in the rows of the
    // slave nodes that change branch).
    let mut order: Option<Vec<u32>> = None;
    let mut u = vec![0.0; ndof];
    let mut p = vec![0.0; rows];
    let mut steps = Vec::with_capacity(options.load_steps.max(1));
    let load_steps = options.load_steps.max(1);
    for s in 1..=load_steps {
        let factor = s as f64 / load_steps as f64;
        for g in 0..ndof {
            if free[g] == NONE {
                u[g] = factor * fixed_value[g];
            }
        }
        let t_step = Instant::now();
        let mut linear_seconds = Vec::new();
        let mut regularised = 0usize;
        let mut last_held = false;
        let mut residuals = Vec::new();
        let mut branch_prev: Option<Vec<bool>> = None;
        let mut settled_at = None;
        let mut converged = false;
        let mut taken = 0usize;
        for it in 0..=options.max_newton_steps {
            let gaps = gap.nodal(&u);
            let mut c = vec![0.0; rows];
            let mut c_g = vec![0.0; rows];
            let mut c_p = vec![0.0; rows];
            for j in 0..rows {
                if !gap.carries[j] {
                    // No multiplier at this node: its pressure is held at zero (C = p).
                    (c[j], c_p[j]) = (p[j], 1.0);
                    continue;
                }
                let t = evaluate(law, LawPoint::new(gaps[j], p[j], 0.0))?;
                c[j] = t.value;
                c_g[j] = t.d_gap;
                c_p[j] = t.d_multiplier;
            }
            let branch: Vec<bool> = c_p.iter().map(|&d| d == 0.0).collect();
            let ku = k_times(&u);
            let ntp = gap_t_times(&p);
            let mut r_u = vec![0.0; nfree];
            for g in 0..ndof {
                if free[g] != NONE {
                    r_u[free[g] as usize] = ku[g] - factor * f[g] + ntp[g];
                }
            }
            // The scale of the forces: applied, contact, or (for a displacement-driven load,
            // before contact) the elastic forces of the prescribed displacements.
            let scale_u = (factor * norm(&f))
                .max(norm(&ntp))
                .max(norm(&ku))
                .max(f64::MIN_POSITIVE);
            let res_u = norm(&r_u) / scale_u;
            let p_max = p.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            // A node's law residual counts as zero within what the rounding of its gap and
            // pressure alone gives (a stiff penalty, `dC/dg` of 1e18 Pa/m, turns the 1e-20 m
            // rounding of a gap into 1e-9 of the pressure).
            let gap_rounding = gap.nodal_rounding(&u);
            let res_p = (0..rows)
                .map(|j| {
                    let floor = c_g[j].abs() * gap_rounding[j]
                        + c_p[j].abs() * 8.0 * f64::EPSILON * p[j].abs();
                    if c[j].abs() <= floor {
                        0.0
                    } else {
                        c[j].abs()
                    }
                })
                .fold(0.0f64, f64::max)
                / p_max.max(f64::MIN_POSITIVE);
            residuals.push(res_u);
            let same_branch = branch_prev.as_ref() == Some(&branch);
            if it > 0
                && same_branch
                && res_u <= options.tolerance
                && (res_p <= options.tolerance || c.iter().all(|v| *v == 0.0))
            {
                converged = true;
                break;
            }
            if it == options.max_newton_steps {
                break;
            }
            if !same_branch {
                settled_at = Some(it);
            }
            branch_prev = Some(branch);
            // Each row of N on the free displacements.
            let n_free: Vec<Vec<(u32, f64)>> = gap
                .matrix
                .outer_iterator()
                .map(|row| {
                    row.iter()
                        .filter(|(k, _)| free[*k] != NONE)
                        .map(|(k, v)| (free[k], *v))
                        .collect()
                })
                .collect();
            let a: Vec<f64> = (0..rows)
                .map(|j| {
                    if gap.carries[j] {
                        -c_g[j] / gap.weights[j]
                    } else {
                        0.0
                    }
                })
                .collect();
            let weighted_gap: Vec<f64> = (0..rows).map(|j| gap.weights[j] * gaps[j]).collect();
            let lin = Linearised {
                nfree,
                slave_free,
                weighted_gap: &weighted_gap,
                r_u: &r_u,
                n_free: &n_free,
                a: &a,
                c: &c,
                c_p: &c_p,
            };
            let singular = |e: SolverError| match e {
                SolverError::Singular { .. } | SolverError::NotPositiveDefinite { .. } => {
                    PhysicsError::InvalidInput {
                        body: "contact".into(),
                        what: format!(
                            "the Newton system is singular at load step {s}, Newton step {it} \
                             ({} of {rows} slave nodes in contact): a body is not held against \
                             rigid motion in some direction but by contact, and contact does \
                             not hold it there (yet); fix it with a Dirichlet condition in that \
                             direction, or load it by a prescribed displacement ({e})",
                            branch_prev
                                .as_ref()
                                .map_or(0, |b| b.iter().filter(|&&a| a).count())
                        ),
                    }
                }
                e => e.into(),
            };
            let t_linear = Instant::now();
            let pivots = if gap.diagonal {
                plan_pivots(&lin, &free_of_slave)
            } else {
                None
            };
            let (du, dp, held) = match pivots {
                Some(pivots) => {
                    condensed_steps += 1;
                    condensed_step(&lin, &kff, &pivots, &mut order, &mut by_body_steps)
                        .map_err(singular)?
                }
                None => saddle_step(&lin, &kff).map_err(singular)?,
            };
            linear_seconds.push(t_linear.elapsed().as_secs_f64());
            regularised += usize::from(held);
            last_held = held;
            for g in 0..ndof {
                if free[g] != NONE {
                    u[g] += du[free[g] as usize];
                }
            }
            for j in 0..rows {
                p[j] += dp[j];
            }
            taken = it + 1;
        }
        if !converged && last_held {
            return Err(PhysicsError::InvalidInput {
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
            });
        }
        if !converged {
            return Err(PhysicsError::Newton(crate::nonlinear::NewtonFailure {
                reason: crate::nonlinear::NewtonFailureReason::MaxIterations,
                iterations: taken,
                residual_history: residuals,
            }));
        }
        steps.push(ContactStep {
            load_factor: factor,
            newton_steps: taken,
            settled_at,
            residuals,
            active: p.iter().filter(|&&v| v > 0.0).count(),
            linear_seconds,
            regularised,
            seconds: t_step.elapsed().as_secs_f64(),
        });
    }
    let gaps = gap.nodal(&u);
    let force = p.iter().zip(&gap.weights).map(|(p, w)| p * w).sum();
    // The pressure the corners' multipliers stand for, at the nodes without one.
    gap.interpolate_rows_without_multiplier(&mut p);
    let total_steps: usize = steps.iter().map(|s| s.newton_steps).sum();
    let formulation = if !gap.diagonal {
        "saddle point of displacements and pressures, sparse LU: D is not diagonal (standard \
         or linear multipliers, or a partly covered interface), so the pressures cannot be \
         condensed"
            .to_string()
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
             displacements less one unknown per slave node in contact, sparse Cholesky{by_body}"
        )
    } else {
        format!(
            "pressures condensed out in {condensed_steps} of {total_steps} Newton steps (D is \
             diagonal); the saddle point (LU) where a node in contact had no free displacement \
             along its normal"
        )
    };
    let master = u.split_off(n[0]);
    Ok(ContactSolution {
        formulation,
        displacements: [u, master],
        pressure: p,
        gap: gaps,
        force,
        steps,
    })
}

/// Sums of sparse vectors over `0..n`, each entry stored once: [`add`](Self::add) adds
/// `scale` times a vector, [`drain`](Self::drain) hands out the sum (indices ascending) and
/// clears it.
struct Accumulator {
    value: Vec<f64>,
    seen: Vec<bool>,
    touched: Vec<u32>,
}

impl Accumulator {
    fn new(n: usize) -> Self {
        Self {
            value: vec![0.0; n],
            seen: vec![false; n],
            touched: Vec::new(),
        }
    }

    fn add(&mut self, entries: &[(u32, f64)], scale: f64) {
        for &(i, v) in entries {
            let k = i as usize;
            if !self.seen[k] {
                self.seen[k] = true;
                self.touched.push(i);
            }
            self.value[k] += scale * v;
        }
    }

    fn drain(&mut self, mut f: impl FnMut(u32, f64)) {
        self.touched.sort_unstable();
        for &i in &self.touched {
            let k = i as usize;
            f(i, self.value[k]);
            self.value[k] = 0.0;
            self.seen[k] = false;
        }
        self.touched.clear();
    }
}

/// A Newton step: the change of the free displacements and of the pressures.
/// A Newton step: the displacement and pressure increments, and whether its system had to be
/// regularised (see [`condensed_step`]).
type Step = (Vec<f64>, Vec<f64>, bool);

/// The Newton system of one step, on the free displacements and the slave-node pressures:
/// `[[K_ff, N_f^T], [A N_f, diag(C_p)]] [du; dp] = [-R_u; -C]`, `A = diag(-C_g / w)`.
struct Linearised<'a> {
    nfree: usize,
    /// Free displacements of the slave body (the first `slave_free` of them).
    slave_free: usize,
    /// The weighted gaps `w_j g_j`.
    weighted_gap: &'a [f64],
    r_u: &'a [f64],
    n_free: &'a [Vec<(u32, f64)>],
    a: &'a [f64],
    c: &'a [f64],
    c_p: &'a [f64],
}

/// The step by sparse LU of the whole system (any D).
fn saddle_step(lin: &Linearised<'_>, kff: &SparseMatrix) -> Result<Step, SolverError> {
    let (nfree, rows) = (lin.nfree, lin.c.len());
    let mut t = Triplets::default();
    for (v, (i, k)) in kff.iter() {
        t.push(i as u32, k as u32, *v);
    }
    let size = nfree + rows;
    let mut rhs = vec![0.0; size];
    for (i, r) in lin.r_u.iter().enumerate() {
        rhs[i] = -r;
    }
    for (j, row) in lin.n_free.iter().enumerate() {
        let pj = (nfree + j) as u32;
        for &(cf, v) in row {
            t.push(cf, pj, v);
            if lin.a[j] != 0.0 {
                t.push(pj, cf, lin.a[j] * v);
            }
        }
        // Keep the diagonal in the pattern (zero on active rows).
        t.push(pj, pj, lin.c_p[j]);
        rhs[nfree + j] = -lin.c[j];
    }
    let jac = t.to_csr(size, size);
    SOLVER
        .factor(&jac, MatrixKind::General)?
        .solve_in_place(&mut rhs)?;
    let dp = rhs.split_off(nfree);
    Ok((rhs, dp, false))
}

/// Solves the symmetric `a x = b` in place: by body where that pays
/// ([`SubstructuredCholesky::try_new_if_worthwhile`], `master` saying which unknowns are the
/// master body's: the two bodies factorised side by side, the unknowns between them last),
/// else Cholesky in the elimination order that `perm` makes for `a` (asked for only then), or
/// LU if `a` is not positive definite. Whether it was solved by body.
fn solve_symmetric(
    a: &SparseMatrix,
    perm: &mut dyn FnMut(&SparseMatrix) -> Result<Vec<usize>, SolverError>,
    master: &[bool],
    b: &mut [f64],
) -> Result<bool, SolverError> {
    if let Ok(Some(f)) = SubstructuredCholesky::try_new_if_worthwhile(a, master) {
        return f.solve_in_place(b).map(|()| true);
    }
    match CholeskyFactorization::try_new_ordered(a, &perm(a)?) {
        Ok(f) => f.solve_in_place(b),
        Err(_) => SOLVER
            .factor(a, MatrixKind::General)
            .and_then(|f| f.solve_in_place(b)),
    }
    .map(|()| false)
}

/// The pivot of each active row, `(free index, N_j at it)` (`None` for inactive rows).
type Pivots = Vec<Option<(u32, f64)>>;

/// The pivots of the active rows, or `None` when some active row cannot be condensed.
fn plan_pivots(lin: &Linearised<'_>, free_of_slave: &[Vec<u32>]) -> Option<Pivots> {
    const NONE: u32 = u32::MAX;
    let rows = lin.c.len();
    let mut pivot: Pivots = vec![None; rows];
    let mut pivot_row = vec![NONE; lin.nfree];
    for j in 0..rows {
        if lin.c_p[j] != 0.0 {
            continue;
        }
        if lin.a[j] == 0.0 {
            return None;
        }
        let row = &lin.n_free[j];
        let own = &free_of_slave[j];
        let best = row
            .iter()
            .filter(|(i, _)| own.contains(i))
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            .copied()?;
        let scale = row.iter().fold(0.0f64, |m, (_, v)| m.max(v.abs()));
        if best.1.abs() <= 1e-8 * scale || pivot_row[best.0 as usize] != NONE {
            return None;
        }
        pivot[j] = Some(best);
        pivot_row[best.0 as usize] = j as u32;
    }
    // A pivot must appear in its own row only (D diagonal to round-off is not enough when an
    // off-diagonal entry lands on another row's pivot): otherwise keep the saddle point.
    for (j, row) in lin.n_free.iter().enumerate() {
        if row
            .iter()
            .any(|&(m, _)| pivot_row[m as usize] != NONE && pivot_row[m as usize] != j as u32)
        {
            return None;
        }
    }
    Some(pivot)
}

/// The step with the pressures condensed out, when D is diagonal (each row's slave part on
/// its own node only). Rows whose law has `C_p != 0` (inactive, or a regularised law) give
/// `dp_j = (-C_j - a_j N_j du) / C_p,j`, which adds `N_j^T (-a_j / C_p,j) N_j` to the
/// stiffness; each row with `C_p = 0` (active) fixes `N_j du = -C_j / a_j`, solved for the
/// free component of its slave node with the largest normal component (the pivot), an affine
/// function of the other unknowns, as the tied condensation does. The remaining system, the
/// size of the displacements less one per active node, is symmetric: Cholesky, or LU if it
/// is not positive definite. The active pressures follow from the pivots' equilibrium rows.
/// The pivots come from [`plan_pivots`], which refuses a row without a free slave component
/// along its normal (the saddle point is solved then).
fn condensed_step(
    lin: &Linearised<'_>,
    kff: &SparseMatrix,
    pivot: &Pivots,
    order: &mut Option<Vec<u32>>,
    by_body: &mut usize,
) -> Result<Step, SolverError> {
    const NONE: u32 = u32::MAX;
    let (nfree, rows) = (lin.nfree, lin.c.len());
    let mut pivot_row = vec![NONE; nfree];
    for (j, p) in pivot.iter().enumerate() {
        if let Some((pv, _)) = p {
            pivot_row[*pv as usize] = j as u32;
        }
    }
    // K' = K_ff + sum over C_p != 0 rows of N_j^T s_j N_j, s_j = -a_j / C_p,j; rhs' likewise.
    let weight: Vec<f64> = (0..rows)
        .map(|j| {
            if lin.c_p[j] == 0.0 {
                0.0
            } else {
                -lin.a[j] / lin.c_p[j]
            }
        })
        .collect();
    let mut rhs: Vec<f64> = lin.r_u.iter().map(|r| -r).collect();
    for j in 0..rows {
        if lin.c_p[j] != 0.0 {
            let f = lin.c[j] / lin.c_p[j];
            for &(i, vi) in &lin.n_free[j] {
                rhs[i as usize] += vi * f;
            }
        }
    }
    let kprime_times = |x: &[f64]| -> Vec<f64> {
        let mut out: Vec<f64> = kff
            .outer_iterator()
            .map(|row| row.iter().map(|(k, v)| v * x[k]).sum())
            .collect();
        for (j, row) in lin.n_free.iter().enumerate() {
            if weight[j] != 0.0 {
                let d: f64 = row.iter().map(|&(k, v)| v * x[k as usize]).sum();
                for &(i, v) in row {
                    out[i as usize] += weight[j] * v * d;
                }
            }
        }
        out
    };
    // Reduced unknowns: the free displacements but the pivots.
    let mut reduced = vec![NONE; nfree];
    let mut nr = 0usize;
    for (i, r) in reduced.iter_mut().enumerate() {
        if pivot_row[i] == NONE {
            *r = nr as u32;
            nr += 1;
        }
    }
    // Which reduced unknowns are the master body's.
    let mut master = vec![false; nr];
    for (i, &r) in reduced.iter().enumerate() {
        if r != NONE {
            master[r as usize] = i >= lin.slave_free;
        }
    }
    // du = Q dv + q: a pivot is (r_j - sum_{m != pivot} N_jm du_m) / N_j,pivot.
    let mut q = vec![0.0; nfree];
    let expansion = |i: usize, out: &mut Vec<(u32, f64)>| {
        out.clear();
        match pivot_row[i] {
            NONE => out.push((reduced[i], 1.0)),
            j => {
                let (pv, nv) = pivot[j as usize].expect("an active row has a pivot");
                for &(m, v) in &lin.n_free[j as usize] {
                    if m != pv {
                        // Master unknowns and the other components of the slave node: none
                        // of them is a pivot (pivots are slave unknowns of their own rows).
                        out.push((reduced[m as usize], -v / nv));
                    }
                }
            }
        }
    };
    for j in 0..rows {
        if let Some((pv, nv)) = pivot[j] {
            q[pv as usize] = -lin.c[j] / lin.a[j] / nv;
        }
    }
    // S = Q^T K' Q, b = Q^T (rhs' - K' q). The entries of K_ff between two unknowns that
    // are not pivots (nearly all) go straight into S's compressed rows, in order. The rest is
    // summed row by row in a dense accumulator before it is stored, each entry once: a row
    // that is not a pivot's gets `sum_k K_ik Q_k` over its pivot columns `k`; the pivots'
    // rows of K Q are kept as a matrix `R` and enter as `Q_p^T R` (a sparse product); the
    // `N_j^T s_j N_j` terms as `s_j (N_j Q)^T (N_j Q)`. Pushing each product of expansions
    // as a triplet instead made, on second-order faces (a pivot's row of K spans some 25
    // other pivots, each expanding into its row of N, about 100 unknowns with a Tet10
    // master), some 300,000 triplets per pivot: 1.3 GB for 12,000 unknowns.
    let kq = kprime_times(&q);
    let mut b = vec![0.0; nr];
    let (mut ei, mut ek) = (Vec::new(), Vec::new());
    let mut extra = Triplets::default();
    let mut acc = Accumulator::new(nr);
    let mut ptr = Vec::with_capacity(nr + 1);
    let (mut idx, mut val) = (Vec::with_capacity(kff.nnz()), Vec::with_capacity(kff.nnz()));
    ptr.push(0usize);
    // R: the pivots' rows of K Q (one row per pivot, in the order met), and Q_p^T's entries.
    let (mut r_ptr, mut r_idx, mut r_val) = (vec![0usize], Vec::new(), Vec::new());
    let mut qpt = Triplets::default();
    for (i, row) in kff.outer_iterator().enumerate() {
        expansion(i, &mut ei);
        for &(ri, wi) in &ei {
            b[ri as usize] += wi * (rhs[i] - kq[i]);
        }
        if pivot_row[i] == NONE {
            let ri = reduced[i];
            for (k, v) in row.iter() {
                if pivot_row[k] == NONE {
                    idx.push(reduced[k] as usize);
                    val.push(*v);
                } else {
                    expansion(k, &mut ek);
                    acc.add(&ek, *v);
                }
            }
            acc.drain(|rk, v| extra.push(ri, rk, v));
            ptr.push(idx.len());
        } else {
            for (k, v) in row.iter() {
                expansion(k, &mut ek);
                acc.add(&ek, *v);
            }
            let p = (r_ptr.len() - 1) as u32;
            acc.drain(|rk, v| {
                r_idx.push(rk as usize);
                r_val.push(v);
            });
            r_ptr.push(r_idx.len());
            for &(ri, wi) in &ei {
                qpt.push(ri, p, wi);
            }
        }
    }
    let mut z = Vec::new();
    for (j, row) in lin.n_free.iter().enumerate() {
        if weight[j] == 0.0 {
            continue;
        }
        for &(i, vi) in row {
            expansion(i as usize, &mut ei);
            acc.add(&ei, vi);
        }
        z.clear();
        acc.drain(|r, v| z.push((r, v)));
        for &(ri, zi) in &z {
            for &(rk, zk) in &z {
                extra.push(ri, rk, weight[j] * zi * zk);
            }
        }
    }
    let npiv = r_ptr.len() - 1;
    let r = SparseMatrix::new((npiv, nr), r_ptr, r_idx, r_val);
    let pivots_part = &qpt.to_csr(nr, npiv) * &r;
    drop(r);
    let base = SparseMatrix::new((nr, nr), ptr, idx, val);
    let s = &(&base + &extra.to_csr(nr, nr)) + &pivots_part;
    drop(base);
    drop(pivots_part);
    // The elimination order of the single factor, made only if the system is not solved by
    // body: the free displacements' order (made from this system the first time, the pivots
    // of that step put last) without this step's pivots.
    let mut made: Option<Vec<usize>> = None;
    let mut perm = |s: &SparseMatrix| -> Result<Vec<usize>, SolverError> {
        if let Some(p) = &made {
            return Ok(p.clone());
        }
        let p: Vec<usize> = match order {
            Some(o) => o
                .iter()
                .filter(|&&i| pivot_row[i as usize] == NONE)
                .map(|&i| reduced[i as usize] as usize)
                .collect(),
            None => {
                let (perm, _) = fill_reducing_ordering(s)?;
                let mut free_of = vec![0u32; nr];
                for (i, &r) in reduced.iter().enumerate() {
                    if r != NONE {
                        free_of[r as usize] = i as u32;
                    }
                }
                let mut o: Vec<u32> = perm.iter().map(|&r| free_of[r]).collect();
                o.extend((0..nfree as u32).filter(|&i| pivot_row[i as usize] != NONE));
                *order = Some(o);
                perm
            }
        };
        made = Some(p.clone());
        Ok(p)
    };
    let b_norm = inf_norm(&b);
    let mut rhs_b = b.clone();
    *by_body += usize::from(solve_symmetric(&s, &mut perm, &master, &mut b)?);
    // A system without a correct digit has a rigid mode held by nothing (a body held only by
    // contact, before contact, or on a flat branch of a regularised law): each row without
    // stiffness gets a spring that pulls its gap shut, the penalty `mu_j / 2 (w_j g_j -
    // N_j du)^2` (`N_j du` is minus the change of the weighted gap) with `mu_j` as stiff as its stiffest unknown, and the step is solved again:
    // the body moves into contact, where the law takes over. The residual is not changed, so
    // neither is the solution; only this step is.
    let mut regularised = false;
    if !well_conditioned(&s, &b, b_norm) {
        let mut spring = Triplets::default();
        for (j, row) in lin.n_free.iter().enumerate() {
            if weight[j] != 0.0 || pivot[j].is_some() {
                continue;
            }
            let nn: f64 = row.iter().map(|(_, v)| v * v).sum();
            let mut stiffest = 0.0f64;
            for &(i, _) in row {
                expansion(i as usize, &mut ei);
                for &(r, _) in &ei {
                    stiffest = stiffest.max(s.get(r as usize, r as usize).copied().unwrap_or(0.0));
                }
            }
            if nn == 0.0 || stiffest == 0.0 {
                continue;
            }
            let mu = stiffest / nn;
            for &(i, vi) in row {
                expansion(i as usize, &mut ei);
                for &(ri, wi) in &ei {
                    rhs_b[ri as usize] += wi * mu * lin.weighted_gap[j] * vi;
                }
                for &(k, vk) in row {
                    expansion(k as usize, &mut ek);
                    for &(ri, wi) in &ei {
                        for &(rk, wk) in &ek {
                            spring.push(ri, rk, wi * mu * vi * vk * wk);
                        }
                    }
                }
            }
        }
        let held = &s + &spring.to_csr(nr, nr);
        b = rhs_b;
        let b_norm = inf_norm(&b);
        solve_symmetric(&held, &mut perm, &master, &mut b)?;
        if !well_conditioned(&held, &b, b_norm) {
            return Err(SolverError::Singular { pivot: None });
        }
        regularised = true;
    }
    let mut du = vec![0.0; nfree];
    let mut e = Vec::new();
    for (i, d) in du.iter_mut().enumerate() {
        expansion(i, &mut e);
        *d = q[i] + e.iter().map(|&(r, w)| w * b[r as usize]).sum::<f64>();
    }
    // Pressures: inactive rows from their law, active ones from their pivot's equilibrium.
    let kdu = kprime_times(&du);
    let mut dp = vec![0.0; rows];
    for j in 0..rows {
        dp[j] = match pivot[j] {
            Some((pv, nv)) => (rhs[pv as usize] - kdu[pv as usize]) / nv,
            None => {
                let ndu: f64 = lin.n_free[j].iter().map(|&(i, v)| v * du[i as usize]).sum();
                (-lin.c[j] - lin.a[j] * ndu) / lin.c_p[j]
            }
        };
    }
    Ok((du, dp, regularised))
}
