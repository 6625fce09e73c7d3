//! The one module that calls PETSc: its bindings, its start (once per process), its objects
//! owned and destroyed in Rust, and every call's error code turned into a [`PetscError`].
//!
//! PETSc is not thread-safe: every use holds the lock on [`STATE`], so solves from several
//! threads run one after another. MPI is started with `MPI_THREAD_SERIALIZED` (any thread,
//! one at a time) unless the program started it itself. PETSc's signal handler is switched
//! off (`-no_signal_handler`), so that Rust's own (stack overflow) stays in place, and its
//! error handler records the innermost message for the typed error instead of printing a
//! traceback.
#![allow(unsafe_code)]

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::ptr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::Instant;

use mortar_core::linalg::SparseMatrix;

use crate::csr::CsrParts;
use crate::error::PetscError;
use crate::options::{KrylovMethod, Preconditioner, SolveOptions};
use crate::report::{ConvergedReason, SolveReport};

/// The bindings bindgen made from PETSc's headers (see build.rs).
#[allow(
    non_upper_case_globals,
    non_camel_case_types,
    non_snake_case,
    dead_code,
    missing_docs,
    clippy::all
)]
mod sys {
    include!(concat!(env!("OUT_DIR"), "/petsc_bindings.rs"));
}

use sys::{PetscErrorCode, PetscInt};

/// Where PETSc is in this process.
enum State {
    /// Not started.
    Uninitialized,
    /// Started; `version` as PETSc names itself, `began_mpi` if we started MPI too.
    Ready { version: String, began_mpi: bool },
    /// Could not start; every later use gets the same error.
    Failed { code: i32, message: String },
    /// Finalised: it cannot start again.
    Finalized,
}

/// PETSc's state, locked for every use of PETSc.
static STATE: Mutex<State> = Mutex::new(State::Uninitialized);

/// The innermost message of the last PETSc error, written by [`record_error`].
static LAST_ERROR: Mutex<Option<String>> = Mutex::new(None);

/// PETSc's state, locked (a panic elsewhere while it was held leaves PETSc's own state
/// sound: every object is destroyed by its owner's `Drop`).
fn lock_state() -> MutexGuard<'static, State> {
    STATE.lock().unwrap_or_else(|e| e.into_inner())
}

/// PETSc's error handler: records the message of an error where it arises (the first of its
/// calls for that error), and returns the code so that the caller sees it.
unsafe extern "C" fn record_error(
    _comm: sys::MPI_Comm,
    _line: c_int,
    func: *const c_char,
    _file: *const c_char,
    code: PetscErrorCode,
    kind: sys::PetscErrorType,
    message: *const c_char,
    _ctx: *mut c_void,
) -> PetscErrorCode {
    if kind == sys::PetscErrorType_PETSC_ERROR_INITIAL {
        // SAFETY: PETSc passes NUL-terminated strings or null.
        let text = |p: *const c_char| {
            if p.is_null() {
                String::new()
            } else {
                unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
            }
        };
        let (message, func) = (text(message), text(func));
        let full = match (message.trim().is_empty(), func.is_empty()) {
            (true, _) => generic_message(code),
            (false, true) => message.trim().to_owned(),
            (false, false) => format!("{} (in {func})", message.trim()),
        };
        if let Ok(mut last) = LAST_ERROR.try_lock() {
            *last = Some(full);
        }
    }
    code
}

/// PETSc's generic text for an error code.
fn generic_message(code: PetscErrorCode) -> String {
    let mut text: *const c_char = ptr::null();
    // SAFETY: PetscErrorMessage writes a pointer to a static string (or null) into `text`.
    let rc = unsafe { sys::PetscErrorMessage(code, &mut text, ptr::null_mut()) };
    if rc != 0 || text.is_null() {
        format!("PETSc error {code}")
    } else {
        // SAFETY: a NUL-terminated static string of PETSc's.
        unsafe { CStr::from_ptr(text) }
            .to_string_lossy()
            .into_owned()
    }
}

/// `Ok` for PETSc's success code, the typed error with PETSc's message otherwise.
fn check(code: PetscErrorCode, function: &'static str) -> Result<(), PetscError> {
    if code == 0 {
        return Ok(());
    }
    let recorded = LAST_ERROR.lock().unwrap_or_else(|e| e.into_inner()).take();
    Err(PetscError::Call {
        function,
        code,
        message: recorded.unwrap_or_else(|| generic_message(code)),
    })
}

/// Calls the PETSc function `f` (a name in [`sys`]) and checks its error code, naming `f`.
macro_rules! call {
    ($f:ident ( $($arg:expr),* $(,)? )) => {{
        // SAFETY: the arguments are live PETSc objects owned by this module's wrappers, or
        // pointers to Rust values and buffers that outlive the call, of the lengths the
        // function reads; PETSc is started and the state lock is held (`with_petsc`).
        let code = unsafe { sys::$f($($arg),*) };
        check(code, stringify!($f))
    }};
}

/// The self communicator (one process): every object here is sequential.
fn comm_self() -> sys::MPI_Comm {
    // SAFETY: returns a constant of the MPI library's.
    unsafe { sys::mortar_petsc_comm_self() }
}

/// Starts MPI (unless the program did) and PETSc, and returns PETSc's version.
fn start() -> Result<(String, bool), (i32, String)> {
    let mut mpi_started: c_int = 0;
    // SAFETY: MPI_Initialized may be called at any time and writes a flag.
    unsafe { sys::MPI_Initialized(&mut mpi_started) };
    let mut began_mpi = false;
    if mpi_started == 0 {
        let mut finalized: c_int = 0;
        // SAFETY: as MPI_Initialized.
        unsafe { sys::MPI_Finalized(&mut finalized) };
        if finalized != 0 {
            return Err((-1, "MPI was finalised in this process".into()));
        }
        let mut provided: c_int = 0;
        // SAFETY: MPI allows null argc and argv; MPI is not started (checked above).
        let rc = unsafe {
            sys::MPI_Init_thread(
                ptr::null_mut(),
                ptr::null_mut(),
                sys::mortar_petsc_thread_serialized(),
                &mut provided,
            )
        };
        if rc != 0 {
            return Err((rc, "MPI_Init_thread failed".into()));
        }
        began_mpi = true;
    }
    // PETSc keeps argv for the life of the process: leaked on purpose, once.
    let args: Vec<*mut c_char> = ["mortar", "-no_signal_handler"]
        .iter()
        .map(|a| CString::new(*a).expect("no NUL").into_raw())
        .chain(std::iter::once(ptr::null_mut()))
        .collect();
    let argv: &'static mut [*mut c_char] = Box::leak(args.into_boxed_slice());
    let mut argc: c_int = (argv.len() - 1) as c_int;
    let mut argv_ptr: *mut *mut c_char = argv.as_mut_ptr();
    // SAFETY: argc and argv describe NUL-terminated strings, null-terminated, alive for the
    // process; no options file, no help text.
    let rc = unsafe { sys::PetscInitialize(&mut argc, &mut argv_ptr, ptr::null(), ptr::null()) };
    if rc != 0 {
        return Err((rc, "PetscInitialize failed".into()));
    }
    // SAFETY: `record_error` has the handler's signature and needs no context.
    let rc = unsafe { sys::PetscPushErrorHandler(Some(record_error), ptr::null_mut()) };
    if rc != 0 {
        return Err((rc, "PetscPushErrorHandler failed".into()));
    }
    let mut buf = [0 as c_char; 256];
    // SAFETY: writes a NUL-terminated string of at most `buf.len()` bytes.
    let rc = unsafe { sys::PetscGetVersion(buf.as_mut_ptr(), buf.len()) };
    let version = if rc == 0 {
        // SAFETY: NUL-terminated within `buf`.
        let v = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_string_lossy();
        // "Petsc Release Version 3.18.5, Mar 04, 2023 " -> "PETSc 3.18.5"
        v.split(',')
            .next()
            .and_then(|s| s.rsplit(' ').next())
            .map_or_else(|| v.trim().to_owned(), |n| format!("PETSc {n}"))
    } else {
        "PETSc".to_owned()
    };
    Ok((version, began_mpi))
}

/// Runs `f` with PETSc started (at the first call in the process) and locked; `f` gets
/// PETSc's version.
///
/// The options database PETSc read at its start (`PETSC_OPTIONS`, `~/.petscrc`) is hidden
/// while a solve's own is pushed; `solve` reads `PETSC_OPTIONS` again into each solve's.
fn with_petsc<T>(f: impl FnOnce(&str) -> Result<T, PetscError>) -> Result<T, PetscError> {
    let mut state = lock_state();
    if let State::Uninitialized = *state {
        *state = match start() {
            Ok((version, began_mpi)) => State::Ready { version, began_mpi },
            Err((code, message)) => State::Failed { code, message },
        };
    }
    match &*state {
        State::Ready { version, .. } => {
            let version = version.clone();
            // A message left by an error PETSc handled itself must not name a later one.
            *LAST_ERROR.lock().unwrap_or_else(|e| e.into_inner()) = None;
            f(&version)
        }
        State::Failed { code, message } => Err(PetscError::Initialize {
            code: *code,
            message: message.clone(),
        }),
        State::Finalized => Err(PetscError::Finalized),
        State::Uninitialized => unreachable!("started above"),
    }
}

/// Whether PETSc can start in this process (starting it if not yet started).
pub(crate) fn ensure_started() -> Result<String, PetscError> {
    with_petsc(|version| Ok(version.to_owned()))
}

/// Finalises PETSc (and MPI, if we started it); later solves answer
/// [`PetscError::Finalized`]. Nothing to do if PETSc never started or is finalised.
pub(crate) fn finalize() -> Result<(), PetscError> {
    let mut state = lock_state();
    if let State::Ready { began_mpi, .. } = *state {
        *state = State::Finalized;
        // SAFETY: PETSc is started; every object of ours is destroyed (each solve destroys
        // its own before it releases the lock).
        check(unsafe { sys::PetscFinalize() }, "PetscFinalize")?;
        if began_mpi {
            // SAFETY: we started MPI, and PETSc, its only user here, has finished.
            let rc = unsafe { sys::MPI_Finalize() };
            if rc != 0 {
                return Err(PetscError::Call {
                    function: "MPI_Finalize",
                    code: rc,
                    message: "MPI_Finalize failed".into(),
                });
            }
        }
    }
    Ok(())
}

/// `n` as PETSc's index type, or the error that it does not fit.
fn petsc_int(n: usize) -> Result<PetscInt, PetscError> {
    PetscInt::try_from(n).map_err(|_| {
        PetscError::InvalidInput(format!(
            "{n} does not fit PETSc's {}-bit indices",
            8 * std::mem::size_of::<PetscInt>()
        ))
    })
}

/// `v` as PETSc's index type, each entry checked.
fn petsc_ints(v: &[usize]) -> Result<Vec<PetscInt>, PetscError> {
    v.iter().map(|&i| petsc_int(i)).collect()
}

/// A PETSc string (type name) as Rust's.
fn type_name(p: *const c_char) -> String {
    if p.is_null() {
        String::new()
    } else {
        // SAFETY: PETSc's type names are NUL-terminated strings it owns.
        unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
    }
}

/// A PETSc `Mat`, destroyed on drop.
struct Mat(sys::Mat);
impl Drop for Mat {
    fn drop(&mut self) {
        // SAFETY: `self.0` is a live matrix of ours or null, which MatDestroy accepts.
        unsafe { sys::MatDestroy(&mut self.0) };
    }
}

/// A PETSc `Vec`, destroyed on drop.
struct Vector(sys::Vec);
impl Drop for Vector {
    fn drop(&mut self) {
        // SAFETY: as for `Mat`.
        unsafe { sys::VecDestroy(&mut self.0) };
    }
}

impl Vector {
    /// A sequential vector with the values of `values` (block size `bs`).
    fn from_slice(values: &[f64], bs: usize) -> Result<Self, PetscError> {
        let mut v = Vector(ptr::null_mut());
        call!(VecCreateSeq(
            comm_self(),
            petsc_int(values.len())?,
            &mut v.0
        ))?;
        if bs > 1 {
            call!(VecSetBlockSize(v.0, petsc_int(bs)?))?;
        }
        v.with_values(|x| x.copy_from_slice(values))?;
        Ok(v)
    }

    /// Runs `f` on all the vector's values.
    fn with_values(&mut self, f: impl FnOnce(&mut [f64])) -> Result<(), PetscError> {
        let mut data: *mut f64 = ptr::null_mut();
        let mut n: PetscInt = 0;
        call!(VecGetLocalSize(self.0, &mut n))?;
        call!(VecGetArray(self.0, &mut data))?;
        if n > 0 {
            // SAFETY: VecGetArray gives the vector's `n` contiguous values, ours until
            // VecRestoreArray.
            f(unsafe { std::slice::from_raw_parts_mut(data, n as usize) });
        }
        call!(VecRestoreArray(self.0, &mut data))
    }
}

/// A PETSc `IS` (index set), destroyed on drop.
struct IndexSet(sys::IS);
impl Drop for IndexSet {
    fn drop(&mut self) {
        // SAFETY: as for `Mat`.
        unsafe { sys::ISDestroy(&mut self.0) };
    }
}

/// A PETSc `MatNullSpace`, destroyed on drop.
struct NullSpace(sys::MatNullSpace);
impl Drop for NullSpace {
    fn drop(&mut self) {
        // SAFETY: as for `Mat`.
        unsafe { sys::MatNullSpaceDestroy(&mut self.0) };
    }
}

/// A PETSc `KSP`, destroyed on drop.
struct Ksp(sys::KSP);
impl Drop for Ksp {
    fn drop(&mut self) {
        // SAFETY: as for `Mat`.
        unsafe { sys::KSPDestroy(&mut self.0) };
    }
}

/// An options database pushed as PETSc's default for the life of this value, then popped
/// and destroyed: a solve's options do not leak into the next.
struct PushedOptions(sys::PetscOptions);
impl PushedOptions {
    fn push(options: &str) -> Result<Self, PetscError> {
        let text = CString::new(options)
            .map_err(|_| PetscError::InvalidInput("PETSc options contain a NUL byte".into()))?;
        let mut o: sys::PetscOptions = ptr::null_mut();
        call!(PetscOptionsCreate(&mut o))?;
        if let Err(e) = call!(PetscOptionsInsertString(o, text.as_ptr())) {
            // SAFETY: `o` is ours and not pushed.
            unsafe { sys::PetscOptionsDestroy(&mut o) };
            return Err(e);
        }
        if let Err(e) = call!(PetscOptionsPush(o)) {
            // SAFETY: as above.
            unsafe { sys::PetscOptionsDestroy(&mut o) };
            return Err(e);
        }
        Ok(Self(o))
    }
}
impl Drop for PushedOptions {
    fn drop(&mut self) {
        // SAFETY: `self.0` is the database on top of PETSc's stack (pushed by `push`, every
        // later push popped by its own drop first).
        unsafe {
            sys::PetscOptionsPop();
            sys::PetscOptionsDestroy(&mut self.0);
        }
    }
}

/// The matrix of `a` (sequential AIJ, block size `bs`).
fn matrix(a: &CsrParts<'_>, bs: usize) -> Result<Mat, PetscError> {
    let n = petsc_int(a.nrows)?;
    let m = petsc_int(a.ncols)?;
    let indptr = petsc_ints(&a.indptr)?;
    let indices = petsc_ints(&a.indices)?;
    let mut mat = Mat(ptr::null_mut());
    call!(MatCreate(comm_self(), &mut mat.0))?;
    call!(MatSetSizes(mat.0, n, m, n, m))?;
    call!(MatSetType(mat.0, c"seqaij".as_ptr()))?;
    if bs > 1 {
        call!(MatSetBlockSize(mat.0, petsc_int(bs)?))?;
    }
    // Copies the arrays into PETSc's storage and assembles the matrix.
    call!(MatSeqAIJSetPreallocationCSR(
        mat.0,
        indptr.as_ptr(),
        indices.as_ptr(),
        a.data.as_ptr()
    ))?;
    Ok(mat)
}

/// The PETSc objects of a system set up for solves: the Krylov solver with its
/// preconditioner, the index sets of a field split, the matrix and its near null space.
struct Objects {
    ksp: Ksp,
    _splits: Vec<IndexSet>,
    mat: Mat,
    near_null_space: Option<NullSpace>,
}

// SAFETY: PETSc's objects are plain heap data of the one process; this module touches them
// only while it holds the lock on `STATE` (`with_petsc`, `Prepared`'s drop), one thread at
// a time.
unsafe impl Send for Objects {}
// SAFETY: as for `Send`: every use, shared or not, holds the lock.
unsafe impl Sync for Objects {}

/// The matrix of `a` with its near null space, if the options give one.
fn operator(
    a: &CsrParts<'_>,
    options: &SolveOptions,
    modes: &[Vec<f64>],
) -> Result<(Mat, Option<NullSpace>), PetscError> {
    let mat = matrix(a, options.effective_block_size())?;
    let mut nsp = NullSpace(ptr::null_mut());
    if let Some(rigid) = &options.near_null_space {
        let coords = Vector::from_slice(&rigid.coordinates, rigid.dim)?;
        call!(MatNullSpaceCreateRigidBody(coords.0, &mut nsp.0))?;
    } else if !modes.is_empty() {
        let vectors = modes
            .iter()
            .map(|m| Vector::from_slice(m, 1))
            .collect::<Result<Vec<_>, _>>()?;
        let raw: Vec<sys::Vec> = vectors.iter().map(|v| v.0).collect();
        // PETSc takes its own references to the vectors.
        call!(MatNullSpaceCreate(
            comm_self(),
            sys::PetscBool_PETSC_FALSE,
            petsc_int(raw.len())?,
            raw.as_ptr(),
            &mut nsp.0
        ))?;
    } else {
        return Ok((mat, None));
    }
    call!(MatSetNearNullSpace(mat.0, nsp.0))?;
    Ok((mat, Some(nsp)))
}

/// Index sets of the two fields of a Schur field split of `n` unknowns, given to `pc`.
fn field_split(
    pc: sys::PC,
    split: &crate::options::FieldSplit,
    n: usize,
) -> Result<Vec<IndexSet>, PetscError> {
    let mut in_first = vec![false; n];
    for &i in &split.first {
        in_first[i] = true;
    }
    let second: Vec<usize> = (0..n).filter(|&i| !in_first[i]).collect();
    let mut splits = Vec::new();
    for (name, field) in [(c"0", &split.first), (c"1", &second)] {
        let idx = petsc_ints(field)?;
        let mut is = IndexSet(ptr::null_mut());
        call!(ISCreateGeneral(
            comm_self(),
            petsc_int(idx.len())?,
            idx.as_ptr(),
            sys::PetscCopyMode_PETSC_COPY_VALUES,
            &mut is.0
        ))?;
        call!(PCFieldSplitSetIS(pc, name.as_ptr(), is.0))?;
        splits.push(is);
    }
    Ok(splits)
}

/// Sets up the Krylov solver and its preconditioner for `a` (PETSc started and locked, the
/// solve's options pushed); the objects and the seconds of `KSPSetUp`.
fn set_up(
    (mat, near_null_space): (Mat, Option<NullSpace>),
    n: usize,
    options: &SolveOptions,
) -> Result<(Objects, f64), PetscError> {
    let mut ksp = Ksp(ptr::null_mut());
    call!(KSPCreate(comm_self(), &mut ksp.0))?;
    call!(KSPSetOperators(ksp.0, mat.0, mat.0))?;
    let method = CString::new(options.method.petsc_name()).expect("no NUL");
    call!(KSPSetType(ksp.0, method.as_ptr()))?;
    call!(KSPSetTolerances(
        ksp.0,
        options.rtol,
        options.atol,
        sys::PETSC_DEFAULT as f64,
        petsc_int(options.max_it)?
    ))?;
    let mut pc: sys::PC = ptr::null_mut();
    call!(KSPGetPC(ksp.0, &mut pc))?;
    let pc_name = CString::new(options.preconditioner.petsc_name()).expect("no NUL");
    call!(PCSetType(pc, pc_name.as_ptr()))?;
    // PETSc keeps its own references to the index sets; ours live as long as the solver.
    let splits = match &options.preconditioner {
        Preconditioner::FieldSplitSchur(split) => field_split(pc, split, n)?,
        _ => Vec::new(),
    };
    call!(KSPSetFromOptions(ksp.0))?;
    let t0 = Instant::now();
    call!(KSPSetUp(ksp.0))?;
    let objects = Objects {
        ksp,
        _splits: splits,
        mat,
        near_null_space,
    };
    Ok((objects, t0.elapsed().as_secs_f64()))
}

/// The options text of a solve: the typed options, `PETSC_OPTIONS`, the free-form ones.
fn option_text(options: &SolveOptions) -> String {
    let environment = std::env::var("PETSC_OPTIONS").ok();
    options.options_string_with_environment(environment.as_deref())
}

/// `|b - A x| / |b|` by PETSc's own product (0 for `b = 0` and `x` exact, infinite for
/// `b = 0` otherwise).
fn relative_residual(a: &Mat, b: &Vector, x: &Vector) -> Result<f64, PetscError> {
    let mut r = Vector(ptr::null_mut());
    call!(VecDuplicate(b.0, &mut r.0))?;
    call!(MatMult(a.0, x.0, r.0))?;
    // r = b - A x.
    call!(VecAYPX(r.0, -1.0, b.0))?;
    let (mut r_norm, mut b_norm) = (0.0, 0.0);
    call!(VecNorm(r.0, sys::NormType_NORM_2, &mut r_norm))?;
    call!(VecNorm(b.0, sys::NormType_NORM_2, &mut b_norm))?;
    Ok(if r_norm == 0.0 { 0.0 } else { r_norm / b_norm })
}

/// What a set-up solver gives for `b` (PETSc started and locked, the options pushed):
/// the solution and its report, `setup` the set-up seconds to report with it (`None`: the
/// set-up of an earlier solve, kept).
fn solve_set_up(
    objects: &Objects,
    b: &[f64],
    options: &SolveOptions,
    version: &str,
    option_text: &str,
    setup: Option<f64>,
) -> Result<(Vec<f64>, SolveReport), PetscError> {
    let ksp = &objects.ksp;
    let rhs = Vector::from_slice(b, 1)?;
    let mut x = Vector::from_slice(&vec![0.0; b.len()], 1)?;
    let t1 = Instant::now();
    call!(KSPSolve(ksp.0, rhs.0, x.0))?;
    let solve_seconds = t1.elapsed().as_secs_f64();

    let mut reason: sys::KSPConvergedReason::Type = 0;
    let mut iterations: PetscInt = 0;
    let mut residual_norm = 0.0;
    let mut ksp_type: *const c_char = ptr::null();
    let mut pc_type: *const c_char = ptr::null();
    let mut pc: sys::PC = ptr::null_mut();
    call!(KSPGetConvergedReason(ksp.0, &mut reason))?;
    call!(KSPGetIterationNumber(ksp.0, &mut iterations))?;
    call!(KSPGetResidualNorm(ksp.0, &mut residual_norm))?;
    call!(KSPGetType(ksp.0, &mut ksp_type))?;
    // The KSP's PC after the options were read (an option may have replaced it).
    call!(KSPGetPC(ksp.0, &mut pc))?;
    call!(PCGetType(pc, &mut pc_type))?;
    let (ksp_type, pc_type) = (type_name(ksp_type), type_name(pc_type));
    let reason = ConvergedReason::from_code(reason);
    let iterations = usize::try_from(iterations).unwrap_or(0);
    if !reason.is_converged() {
        return Err(PetscError::NotConverged {
            reason,
            iterations,
            residual_norm,
            ksp_type,
            pc_type,
        });
    }
    let mut solution = vec![0.0; b.len()];
    x.with_values(|v| solution.copy_from_slice(v))?;
    let relative_residual = relative_residual(&objects.mat, &rhs, &x)?;
    // `preonly` has no convergence test: a factorisation of a singular matrix "succeeds"
    // with a meaningless solution, which only the residual shows. A Krylov method tests the
    // preconditioned residual: a poor preconditioner (a near-zero pivot in it) lets that
    // converge while the true residual does not.
    // The tolerance PETSc solved to, after the options were read (`-ksp_rtol` may set it).
    let (mut rtol, mut atol, mut dtol, mut max_it): (f64, f64, f64, PetscInt) = (0.0, 0.0, 0.0, 0);
    call!(KSPGetTolerances(
        ksp.0,
        &mut rtol,
        &mut atol,
        &mut dtol,
        &mut max_it
    ))?;
    let bound = match options.method {
        KrylovMethod::PreOnly => options.rtol,
        _ => crate::accepted_residual(rtol.max(options.rtol)),
    };
    if relative_residual.is_nan() || relative_residual > bound {
        return Err(PetscError::Inaccurate {
            relative_residual,
            tolerance: bound,
            ksp_type,
            pc_type,
        });
    }
    let report = SolveReport {
        backend: version.to_owned(),
        ksp_type,
        pc_type,
        near_null_space: objects.near_null_space.is_some(),
        options: option_text.to_owned(),
        iterations,
        residual_norm,
        reason,
        relative_residual,
        setup_seconds: setup.unwrap_or(0.0),
        setup_kept: setup.is_none(),
        solve_seconds,
    };
    Ok((solution, report))
}

/// Solves `a x = b` with `options`, setting the solver up for this one solve; the caller
/// checked the sizes.
pub(crate) fn solve(
    a: &CsrParts<'_>,
    b: &[f64],
    options: &SolveOptions,
) -> Result<(Vec<f64>, SolveReport), PetscError> {
    with_petsc(|version| {
        let text = option_text(options);
        // Declared first, dropped last: every object below is destroyed while it is pushed.
        let _pushed = PushedOptions::push(&text)?;
        let (objects, setup) = set_up(operator(a, options, &[])?, a.nrows, options)?;
        solve_set_up(&objects, b, options, version, &text, Some(setup))
    })
}

/// A solver set up for one matrix and kept for all its solves: the preconditioner (an AMG
/// hierarchy, a factorisation) is built once, at [`prepare`] and at each [`update`] of the
/// matrix's values, not at every solve. Its PETSc objects are destroyed on drop (left to
/// PETSc's own end if PETSc was finalised first).
pub(crate) struct Prepared {
    objects: Option<Objects>,
    options: SolveOptions,
    /// The near null space given besides the options (orthonormal vectors).
    modes: Vec<Vec<f64>>,
    option_text: String,
    setup_seconds: f64,
    /// Whether a solve reported the set-up already.
    setup_reported: AtomicBool,
}

impl std::fmt::Debug for Prepared {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prepared")
            .field("options", &self.option_text)
            .field("setup_seconds", &self.setup_seconds)
            .finish_non_exhaustive()
    }
}

impl Drop for Prepared {
    fn drop(&mut self) {
        if let Some(objects) = self.objects.take() {
            let state = lock_state();
            if let State::Ready { .. } = *state {
                drop(objects);
            } else {
                // PETSc is gone: its objects went with it.
                std::mem::forget(objects);
            }
        }
    }
}

/// Sets up the solver for `a` with `options`; the caller checked the sizes.
///
/// Unless the options give rigid body modes, `modes` (orthonormal vectors over the unknowns,
/// none if empty) is the near null space.
///
/// `a` is dropped once PETSc holds its copy, before the preconditioner is built: one copy of
/// the matrix at a time.
pub(crate) fn prepare(
    a: SparseMatrix,
    options: &SolveOptions,
    modes: Vec<Vec<f64>>,
) -> Result<Prepared, PetscError> {
    with_petsc(move |_| {
        let text = option_text(options);
        let _pushed = PushedOptions::push(&text)?;
        let n = a.rows();
        let op = operator(&crate::csr::csr_parts(&a), options, &modes)?;
        drop(a);
        let (objects, setup_seconds) = set_up(op, n, options)?;
        Ok(Prepared {
            objects: Some(objects),
            options: options.clone(),
            modes,
            option_text: text,
            setup_seconds,
            setup_reported: AtomicBool::new(false),
        })
    })
}

/// Solves `a x = b` with the solver set up for `a` (the matrix `prepared` was made or
/// updated with).
pub(crate) fn solve_prepared(
    prepared: &Prepared,
    b: &[f64],
) -> Result<(Vec<f64>, SolveReport), PetscError> {
    with_petsc(|version| {
        let objects = prepared.objects.as_ref().ok_or(PetscError::Finalized)?;
        let _pushed = PushedOptions::push(&prepared.option_text)?;
        let first = !prepared.setup_reported.swap(true, Ordering::Relaxed);
        let setup = first.then_some(prepared.setup_seconds);
        solve_set_up(
            objects,
            b,
            &prepared.options,
            version,
            &prepared.option_text,
            setup,
        )
    })
}

/// Gives the solver the new values `a` of its matrix (the same pattern) and sets its
/// preconditioner up again for them.
pub(crate) fn update(prepared: &mut Prepared, a: &CsrParts<'_>) -> Result<(), PetscError> {
    let Prepared {
        objects,
        options,
        modes,
        option_text,
        ..
    } = prepared;
    let objects = objects.as_mut().ok_or(PetscError::Finalized)?;
    let seconds = with_petsc(|_| {
        let _pushed = PushedOptions::push(option_text)?;
        let (mat, near_null_space) = operator(a, options, modes)?;
        call!(KSPSetOperators(objects.ksp.0, mat.0, mat.0))?;
        objects.mat = mat;
        objects.near_null_space = near_null_space;
        let t0 = Instant::now();
        call!(KSPSetUp(objects.ksp.0))?;
        Ok(t0.elapsed().as_secs_f64())
    })?;
    prepared.setup_seconds = seconds;
    prepared.setup_reported = AtomicBool::new(false);
    Ok(())
}
