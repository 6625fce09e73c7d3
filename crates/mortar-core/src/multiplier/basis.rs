//! `LmBasis`, the multiplier basis on one slave face (`Phi_j = sum_k a[j][k] N_k`), and the
//! `MultiplierSpace` trait that builds it per face.

use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::geometry::ModelGeometry;
use crate::interface::FaceGeometry;
use crate::tolerances::Tolerances;

/// The multiplier basis on one slave face: `Phi_j = sum_k a[j][k] N_k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmBasis {
    /// Node count of the face.
    pub nodes: usize,
    /// `true` when `a` is the identity (standard multipliers): then `Phi = N`.
    pub identity: bool,
    /// The coefficients (the first `nodes` rows and columns are valid).
    pub a: [[f64; MAX_FACE_NODES]; MAX_FACE_NODES],
}

impl LmBasis {
    /// The identity transformation (standard multipliers) on a face of `nodes` nodes.
    pub fn identity(nodes: usize) -> Self {
        let mut a = [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES];
        for (i, row) in a.iter_mut().enumerate() {
            row[i] = 1.0;
        }
        Self {
            nodes,
            identity: true,
            a,
        }
    }

    /// Whether node `j` of the face carries a multiplier: `false` when its row of `a` is
    /// zero (the edge and centre nodes of [`LinearMultipliers`](super::LinearMultipliers)),
    /// whose rows of D and M the coupling leaves empty.
    #[inline]
    pub fn carries(&self, j: usize) -> bool {
        self.identity || self.a[j][..self.nodes].iter().any(|v| *v != 0.0)
    }

    /// Multiplier values from shape function values: `phi[j] = sum_k a[j][k] n[k]`.
    #[inline]
    pub fn eval_into(&self, n: &[f64], phi: &mut [f64]) {
        let k = self.nodes;
        if self.identity {
            phi[..k].copy_from_slice(&n[..k]);
            return;
        }
        for j in 0..k {
            let mut s = 0.0;
            for (i, ni) in n[..k].iter().enumerate() {
                s += self.a[j][i] * ni;
            }
            phi[j] = s;
        }
    }
}

/// A Lagrange multiplier space: how the multiplier basis is built on each slave face.
///
/// Implement this to add a space (for example a boundary-modified dual basis): its
/// [`name`](MultiplierSpace::name) and its [`basis`](MultiplierSpace::basis) on a face are
/// all the coupling needs to compute D and M, which it does by calling
/// [`basis_for`](MultiplierSpace::basis_for) once per slave face (a space whose basis depends
/// on the interface measure overrides that one too).
///
/// **Fast paths.** The coupling also has faster or tidier ways to the same D and M that rely
/// on facts about a space: that D comes out diagonal (it then folds D's round-off off the
/// diagonal into it and reports what is left), that the basis is biorthogonal to recombined
/// second-order functions (it then also gives D in that basis), that every face of a type has
/// the same basis (it then builds it once for a straight 2D interface). It cannot find them
/// from the bases it is handed, short of integrating or building every one, so a space states
/// them, apart from this trait: they are the methods of [`MultiplierFastPaths`], which a space
/// reaches the coupling through by returning itself from
/// [`fast_paths`](MultiplierSpace::fast_paths). The default, `None`, states none of them and is
/// always correct: a space of one's own computes the same D and M (to round-off) without
/// knowing of them. The shipped [`StandardMultipliers`] and [`DualMultipliers`] implement
/// them; [`LinearMultipliers`] states none.
///
/// (A trait of their own rather than a struct of flags: the facts depend on the element type
/// and the measure, and as methods with defaults a space states only those it has.)
///
/// [`StandardMultipliers`]: super::StandardMultipliers
/// [`DualMultipliers`]: super::DualMultipliers
/// [`LinearMultipliers`]: super::LinearMultipliers
pub trait MultiplierSpace: Send + Sync + std::fmt::Debug {
    /// A short name (`"standard"`, `"dual"`).
    fn name(&self) -> &'static str;

    /// The basis on one slave face.
    ///
    /// # Errors
    /// [`MortarError::MultiplierSpace`](crate::error::MortarError::MultiplierSpace) when the
    /// space cannot be built on the face.
    fn basis(&self, face: &FaceGeometry, tol: &Tolerances) -> Result<LmBasis>;

    /// The basis on one slave face for the interface measure `geometry` (see
    /// [`CouplingOptions::geometry`](crate::CouplingOptions::geometry)); the coupling calls
    /// this one. A space whose basis depends on the measure (a biorthogonal one) must
    /// override it.
    ///
    /// The default gives [`basis`](MultiplierSpace::basis) for the Cartesian measure, and for
    /// the axisymmetric one too unless the space claims a diagonal D
    /// ([`MultiplierFastPaths::diagonal_d`]): such a space is biorthogonal with respect to a
    /// measure, which the default cannot know, so it is refused rather than silently giving a
    /// D that is not diagonal.
    ///
    /// # Errors
    /// As [`basis`](MultiplierSpace::basis);
    /// [`MortarError::MultiplierSpace`] for a space with a diagonal D that does not override
    /// this method, asked for the axisymmetric measure.
    fn basis_for(
        &self,
        face: &FaceGeometry,
        tol: &Tolerances,
        geometry: ModelGeometry,
    ) -> Result<LmBasis> {
        let diagonal = self.fast_paths().is_some_and(|f| f.diagonal_d());
        if geometry.is_axisymmetric() && diagonal {
            return Err(MortarError::MultiplierSpace {
                space: self.name(),
                face: face.location(),
                reason: "the space does not implement the axisymmetric measure 2 pi r \
                         (MultiplierSpace::basis_for)"
                    .into(),
            });
        }
        self.basis(face, tol)
    }

    /// The facts about this space that the coupling's fast paths rely on (see the trait's
    /// documentation), if it states any. The default, `None`, states none: always correct.
    fn fast_paths(&self) -> Option<&dyn MultiplierFastPaths> {
        None
    }
}

/// Facts about a [`MultiplierSpace`] that let the coupling take a fast path or give more,
/// reached through [`MultiplierSpace::fast_paths`]. Every method has a default that claims
/// nothing and is always correct; a space overrides those it knows to hold. A claim that does
/// not hold gives wrong results (a basis built once where faces differ) or misreports (round-off
/// dropped from a D that is not diagonal), so claim only what the space guarantees.
pub trait MultiplierFastPaths {
    /// Whether D is diagonal for this space on a fully covered interface (so that the slave
    /// unknowns condense out cheaply). The coupling then adds the round-off off the diagonal
    /// to it (see [`CouplingStats::d_roundoff_dropped`](crate::CouplingStats::d_roundoff_dropped)),
    /// counts what is left and warns of it
    /// ([`CouplingWarning::DualNotDiagonal`](crate::CouplingWarning::DualNotDiagonal)). The
    /// default, `false`, leaves D as integrated.
    fn diagonal_d(&self) -> bool {
        false
    }

    /// Whether the basis on a second-order face whose corner functions do not all integrate
    /// to a positive value (Tri6, Quad8) is biorthogonal to the recombined functions
    /// `N~ = T N` of [`recombination`](super::recombination) rather than to the face's own:
    /// then the coupling of a space that also claims [`diagonal_d`](Self::diagonal_d) gives
    /// D in that basis, `D T^T` ([`Coupling::recombined`](crate::Coupling::recombined)),
    /// diagonal where D itself is not. The default, `false`, gives none.
    fn recombines(&self) -> bool {
        false
    }

    /// Whether [`basis_for`](MultiplierSpace::basis_for) gives every face of type `element`
    /// the same basis (to round-off), whatever the face's position, size and orientation,
    /// for the measure `geometry`: the coupling may then build it once for a whole interface
    /// (the sorted merge of a straight 2D interface; see
    /// [`assemble_coupling`](crate::assemble_coupling)). The default, `false`, is always
    /// correct.
    fn basis_is_uniform(&self, element: ElementRef, geometry: ModelGeometry) -> bool {
        let _ = (element, geometry);
        false
    }
}
