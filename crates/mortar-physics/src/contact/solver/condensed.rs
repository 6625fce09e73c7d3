//! The contact Newton step with the pressures condensed out, when D is diagonal: the pivots
//! of the active rows, the reduced unknowns and their expansion, the reduced system, its
//! regularisation where a rigid mode is held by nothing, and the recovery of the increments.

use mortar_fem::linalg::{
    fill_reducing_ordering, inf_norm, well_conditioned, SolverError, SparseMatrix, Triplets,
};

use super::linear::{solve_symmetric, Backend, Linearised, Step};

/// Marks "none" in the index maps of this file.
const NONE: u32 = u32::MAX;

/// The pivot of each active row, `(free index, N_j at it)` (`None` for inactive rows).
pub(super) type Pivots = Vec<Option<(u32, f64)>>;

/// The pivots of the active rows, or `None` when some active row cannot be condensed.
pub(super) fn plan_pivots(lin: &Linearised<'_>, free_of_slave: &[Vec<u32>]) -> Option<Pivots> {
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
///
/// `order` is the elimination order carried between steps ([`EliminationOrder`]); `by_body`
/// counts the steps solved by body.
pub(super) fn condensed_step(
    lin: &Linearised<'_>,
    kff: &SparseMatrix,
    pivot: &Pivots,
    order: &mut Option<Vec<u32>>,
    by_body: &mut usize,
    backend: Option<Backend<'_>>,
) -> Result<Step, SolverError> {
    let sys = Condensed::new(lin, kff, pivot);
    let red = &sys.reduction;
    let master = red.master(lin.slave_free);
    let (s, mut b) = sys.reduced_system();
    // Where the reduced unknowns sit, for the backend.
    let places = backend.and_then(|b| b.free_places).map(|p| {
        let keep = red
            .reduced
            .iter()
            .map(|&r| (r != NONE).then_some(r as usize));
        p.restricted(keep, red.nr)
    });
    let backend = backend.map(|b| (b.solver, places.as_ref()));
    let mut order = EliminationOrder {
        order,
        reduction: red,
        made: None,
    };
    let mut perm = |s: &SparseMatrix| order.make(s);
    let b_norm = inf_norm(&b);
    let mut rhs_b = b.clone();
    *by_body += usize::from(solve_symmetric(&s, &mut perm, &master, &mut b, backend)?);
    // A system without a correct digit has a rigid mode held by nothing (a body held only by
    // contact, before contact, or on a flat branch of a regularised law): each row without
    // stiffness gets a spring that pulls its gap shut ([`Condensed::springs`]), and the step
    // is solved again: the body moves into contact, where the law takes over. The residual
    // is not changed, so neither is the solution; only this step is.
    let mut regularised = false;
    if !well_conditioned(&s, &b, b_norm) {
        let spring = sys.springs(&s, &mut rhs_b);
        let held = &s + &spring.to_csr(red.nr, red.nr);
        b = rhs_b;
        let b_norm = inf_norm(&b);
        solve_symmetric(&held, &mut perm, &master, &mut b, backend)?;
        if !well_conditioned(&held, &b, b_norm) {
            return Err(SolverError::Singular { pivot: None });
        }
        regularised = true;
    }
    let du = red.expand(&b);
    let dp = sys.pressures(&du);
    Ok((du, dp, regularised))
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

/// The free displacements as affine functions of the reduced ones, `du = Q dv + q`: every
/// free displacement but the pivots is a reduced unknown; a pivot is
/// `(r_j - sum_{m != pivot} N_jm du_m) / N_j,pivot` from its active row.
struct Reduction<'a> {
    /// Each row of N on the free displacements.
    n_free: &'a [Vec<(u32, f64)>],
    pivot: &'a Pivots,
    /// Per free displacement, the row it is the pivot of, or [`NONE`].
    pivot_row: Vec<u32>,
    /// Per free displacement, its reduced index, or [`NONE`] for a pivot.
    reduced: Vec<u32>,
    /// The number of reduced unknowns.
    nr: usize,
    /// The constant part `q` of the expansion (non-zero at the pivots only).
    q: Vec<f64>,
}

impl<'a> Reduction<'a> {
    fn new(lin: &Linearised<'a>, pivot: &'a Pivots) -> Self {
        let (nfree, rows) = (lin.nfree, lin.c.len());
        let mut pivot_row = vec![NONE; nfree];
        for (j, p) in pivot.iter().enumerate() {
            if let Some((pv, _)) = p {
                pivot_row[*pv as usize] = j as u32;
            }
        }
        let mut reduced = vec![NONE; nfree];
        let mut nr = 0usize;
        for (i, r) in reduced.iter_mut().enumerate() {
            if pivot_row[i] == NONE {
                *r = nr as u32;
                nr += 1;
            }
        }
        let mut q = vec![0.0; nfree];
        for j in 0..rows {
            if let Some((pv, nv)) = pivot[j] {
                q[pv as usize] = -lin.c[j] / lin.a[j] / nv;
            }
        }
        Self {
            n_free: lin.n_free,
            pivot,
            pivot_row,
            reduced,
            nr,
            q,
        }
    }

    /// Which reduced unknowns are the master body's (free indices from `slave_free` on).
    fn master(&self, slave_free: usize) -> Vec<bool> {
        let mut master = vec![false; self.nr];
        for (i, &r) in self.reduced.iter().enumerate() {
            if r != NONE {
                master[r as usize] = i >= slave_free;
            }
        }
        master
    }

    /// Whether free displacement `i` is not a pivot (a reduced unknown).
    fn is_reduced(&self, i: usize) -> bool {
        self.pivot_row[i] == NONE
    }

    /// Row `i` of `Q` into `out`, `(reduced index, weight)`.
    fn expansion(&self, i: usize, out: &mut Vec<(u32, f64)>) {
        out.clear();
        match self.pivot_row[i] {
            NONE => out.push((self.reduced[i], 1.0)),
            j => {
                let (pv, nv) = self.pivot[j as usize].expect("an active row has a pivot");
                for &(m, v) in &self.n_free[j as usize] {
                    if m != pv {
                        // Master unknowns and the other components of the slave node: none
                        // of them is a pivot (pivots are slave unknowns of their own rows).
                        out.push((self.reduced[m as usize], -v / nv));
                    }
                }
            }
        }
    }

    /// The free displacements `du = Q dv + q` of the reduced ones `dv`.
    fn expand(&self, dv: &[f64]) -> Vec<f64> {
        let mut du = vec![0.0; self.pivot_row.len()];
        let mut e = Vec::new();
        for (i, d) in du.iter_mut().enumerate() {
            self.expansion(i, &mut e);
            *d = self.q[i] + e.iter().map(|&(r, w)| w * dv[r as usize]).sum::<f64>();
        }
        du
    }
}

/// The Newton system with the rows of `C_p != 0` condensed into the stiffness,
/// `K' = K_ff + sum_j N_j^T s_j N_j` with `s_j = -a_j / C_p,j`, and into the right-hand side,
/// over the [`Reduction`] of the active rows.
struct Condensed<'a> {
    lin: &'a Linearised<'a>,
    kff: &'a SparseMatrix,
    /// Per row, `s_j` (zero for the active rows).
    weight: Vec<f64>,
    /// `rhs' = -R_u + sum_j N_j^T C_j / C_p,j` over the rows of `C_p != 0`.
    rhs: Vec<f64>,
    reduction: Reduction<'a>,
}

impl<'a> Condensed<'a> {
    fn new(lin: &'a Linearised<'a>, kff: &'a SparseMatrix, pivot: &'a Pivots) -> Self {
        let rows = lin.c.len();
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
        Self {
            lin,
            kff,
            weight,
            rhs,
            reduction: Reduction::new(lin, pivot),
        }
    }

    /// `K' x`.
    fn kprime_times(&self, x: &[f64]) -> Vec<f64> {
        let mut out: Vec<f64> = self
            .kff
            .outer_iterator()
            .map(|row| row.iter().map(|(k, v)| v * x[k]).sum())
            .collect();
        for (j, row) in self.lin.n_free.iter().enumerate() {
            if self.weight[j] != 0.0 {
                let d: f64 = row.iter().map(|&(k, v)| v * x[k as usize]).sum();
                for &(i, v) in row {
                    out[i as usize] += self.weight[j] * v * d;
                }
            }
        }
        out
    }

    /// The reduced system `S = Q^T K' Q`, `b = Q^T (rhs' - K' q)`. The entries of K_ff
    /// between two unknowns that are not pivots (nearly all) go straight into S's compressed
    /// rows, in order. The rest is summed row by row in a dense accumulator before it is
    /// stored, each entry once: a row that is not a pivot's gets `sum_k K_ik Q_k` over its
    /// pivot columns `k`; the pivots' rows of K Q are kept as a matrix `R` and enter as
    /// `Q_p^T R` (a sparse product); the `N_j^T s_j N_j` terms as `s_j (N_j Q)^T (N_j Q)`.
    /// Pushing each product of expansions as a triplet instead made, on second-order faces (a
    /// pivot's row of K spans some 25 other pivots, each expanding into its row of N, about
    /// 100 unknowns with a Tet10 master), some 300,000 triplets per pivot: 1.3 GB for 12,000
    /// unknowns.
    fn reduced_system(&self) -> (SparseMatrix, Vec<f64>) {
        let nr = self.reduction.nr;
        let mut acc = Accumulator::new(nr);
        let mut extra = Triplets::default();
        let (base, pivots_part, b) = self.stiffness_rows(&mut acc, &mut extra);
        self.condensed_rows(&mut acc, &mut extra);
        let s = &(&base + &extra.to_csr(nr, nr)) + &pivots_part;
        (s, b)
    }

    /// The rows of `K_ff` in the reduced system, and `b`: the entries between reduced
    /// unknowns as the compressed matrix `base`, those through a pivot column into `extra`,
    /// and the pivots' rows as `Q_p^T R`.
    fn stiffness_rows(
        &self,
        acc: &mut Accumulator,
        extra: &mut Triplets,
    ) -> (SparseMatrix, SparseMatrix, Vec<f64>) {
        let (red, kff) = (&self.reduction, self.kff);
        let nr = red.nr;
        let kq = self.kprime_times(&red.q);
        let mut b = vec![0.0; nr];
        let (mut ei, mut ek) = (Vec::new(), Vec::new());
        let mut ptr = Vec::with_capacity(nr + 1);
        let (mut idx, mut val) = (Vec::with_capacity(kff.nnz()), Vec::with_capacity(kff.nnz()));
        ptr.push(0usize);
        // R: the pivots' rows of K Q (one row per pivot, in the order met), and Q_p^T's entries.
        let (mut r_ptr, mut r_idx, mut r_val) = (vec![0usize], Vec::new(), Vec::new());
        let mut qpt = Triplets::default();
        for (i, row) in kff.outer_iterator().enumerate() {
            red.expansion(i, &mut ei);
            for &(ri, wi) in &ei {
                b[ri as usize] += wi * (self.rhs[i] - kq[i]);
            }
            if red.is_reduced(i) {
                let ri = red.reduced[i];
                for (k, v) in row.iter() {
                    if red.is_reduced(k) {
                        idx.push(red.reduced[k] as usize);
                        val.push(*v);
                    } else {
                        red.expansion(k, &mut ek);
                        acc.add(&ek, *v);
                    }
                }
                acc.drain(|rk, v| extra.push(ri, rk, v));
                ptr.push(idx.len());
            } else {
                for (k, v) in row.iter() {
                    red.expansion(k, &mut ek);
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
        let npiv = r_ptr.len() - 1;
        let r = SparseMatrix::new((npiv, nr), r_ptr, r_idx, r_val);
        let pivots_part = &qpt.to_csr(nr, npiv) * &r;
        let base = SparseMatrix::new((nr, nr), ptr, idx, val);
        (base, pivots_part, b)
    }

    /// The condensed rows' `s_j (N_j Q)^T (N_j Q)` into `extra`.
    fn condensed_rows(&self, acc: &mut Accumulator, extra: &mut Triplets) {
        let red = &self.reduction;
        let (mut ei, mut z) = (Vec::new(), Vec::new());
        for (j, row) in self.lin.n_free.iter().enumerate() {
            if self.weight[j] == 0.0 {
                continue;
            }
            for &(i, vi) in row {
                red.expansion(i as usize, &mut ei);
                acc.add(&ei, vi);
            }
            z.clear();
            acc.drain(|r, v| z.push((r, v)));
            for &(ri, zi) in &z {
                for &(rk, zk) in &z {
                    extra.push(ri, rk, self.weight[j] * zi * zk);
                }
            }
        }
    }

    /// The springs of a reduced system `s` with a rigid mode held by nothing, adding their
    /// pull to `rhs_b`: each row neither condensed nor active gets the penalty
    /// `mu_j / 2 (w_j g_j - N_j du)^2` (`N_j du` is minus the change of the weighted gap) with
    /// `mu_j` as stiff as its stiffest unknown.
    fn springs(&self, s: &SparseMatrix, rhs_b: &mut [f64]) -> Triplets {
        let red = &self.reduction;
        let (mut ei, mut ek) = (Vec::new(), Vec::new());
        let mut spring = Triplets::default();
        for (j, row) in self.lin.n_free.iter().enumerate() {
            if self.weight[j] != 0.0 || red.pivot[j].is_some() {
                continue;
            }
            let nn: f64 = row.iter().map(|(_, v)| v * v).sum();
            let mut stiffest = 0.0f64;
            for &(i, _) in row {
                red.expansion(i as usize, &mut ei);
                for &(r, _) in &ei {
                    stiffest = stiffest.max(s.get(r as usize, r as usize).copied().unwrap_or(0.0));
                }
            }
            if nn == 0.0 || stiffest == 0.0 {
                continue;
            }
            let mu = stiffest / nn;
            for &(i, vi) in row {
                red.expansion(i as usize, &mut ei);
                for &(ri, wi) in &ei {
                    rhs_b[ri as usize] += wi * mu * self.lin.weighted_gap[j] * vi;
                }
                for &(k, vk) in row {
                    red.expansion(k as usize, &mut ek);
                    for &(ri, wi) in &ei {
                        for &(rk, wk) in &ek {
                            spring.push(ri, rk, wi * mu * vi * vk * wk);
                        }
                    }
                }
            }
        }
        spring
    }

    /// The pressure increments of the displacement increment `du`: inactive rows from their
    /// law, active ones from their pivot's equilibrium.
    fn pressures(&self, du: &[f64]) -> Vec<f64> {
        let lin = self.lin;
        let kdu = self.kprime_times(du);
        let mut dp = vec![0.0; lin.c.len()];
        for (j, d) in dp.iter_mut().enumerate() {
            *d = match self.reduction.pivot[j] {
                Some((pv, nv)) => (self.rhs[pv as usize] - kdu[pv as usize]) / nv,
                None => {
                    let ndu: f64 = lin.n_free[j].iter().map(|&(i, v)| v * du[i as usize]).sum();
                    (-lin.c[j] - lin.a[j] * ndu) / lin.c_p[j]
                }
            };
        }
        dp
    }
}

/// The elimination order of the single factor of a condensed system, made only if the
/// system is not solved by body: the free displacements' order carried between steps in
/// `order` (made from this system the first time, the pivots of that step put last) without
/// this step's pivots, kept in `made` for a second solve of the step.
struct EliminationOrder<'a> {
    order: &'a mut Option<Vec<u32>>,
    reduction: &'a Reduction<'a>,
    made: Option<Vec<usize>>,
}

impl EliminationOrder<'_> {
    /// The order of the reduced system `s`.
    fn make(&mut self, s: &SparseMatrix) -> Result<Vec<usize>, SolverError> {
        if let Some(p) = &self.made {
            return Ok(p.clone());
        }
        let red = self.reduction;
        let p: Vec<usize> = match self.order {
            Some(o) => o
                .iter()
                .filter(|&&i| red.is_reduced(i as usize))
                .map(|&i| red.reduced[i as usize] as usize)
                .collect(),
            None => {
                let (perm, _) = fill_reducing_ordering(s)?;
                let mut free_of = vec![0u32; red.nr];
                for (i, &r) in red.reduced.iter().enumerate() {
                    if r != NONE {
                        free_of[r as usize] = i as u32;
                    }
                }
                let nfree = red.pivot_row.len();
                let mut o: Vec<u32> = perm.iter().map(|&r| free_of[r]).collect();
                o.extend((0..nfree as u32).filter(|&i| !red.is_reduced(i as usize)));
                *self.order = Some(o);
                perm
            }
        };
        self.made = Some(p.clone());
        Ok(p)
    }
}
