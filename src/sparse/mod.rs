//! Sparse Cholesky factorisation `P A P^T = L L^T` of symmetric positive definite matrices,
//! split the way a per-frame solver needs it:
//!
//! 1. [`Symbolic::analyse`], once per sparsity pattern: a fill-reducing ordering
//!    ([`Ordering`]: approximate minimum degree or minimum fill, a given order such as
//!    one from [`fill_reducing_order`] or [`nested_dissection_order`], or natural; the
//!    policy that chooses among orders is in `ordering`), the elimination
//!    tree and its postorder, column counts, supernodes and the row pattern of every
//!    supernode of `L`, and a map from each entry of `A` to its slot in `L`.
//! 2. [`Numeric::factor`] / [`Numeric::refactor`], for every new set of values on that
//!    pattern: a left-looking supernodal factorisation that allocates nothing when
//!    refactoring, and reports a non-positive pivot with its column instead of producing
//!    NaNs ([`Numeric::refactor_values`] takes the values alone, for callers whose pattern
//!    is fixed by construction, and skips the comparison of patterns).
//! 3. [`Numeric::solve_in_place`]: the two triangular solves with the permutation applied,
//!    in place and without allocating.
//!
//! Beside it, [`eigen::smallest_eigenpairs`]: the smallest eigenpairs of a sparse symmetric
//! generalised problem by shift-invert subspace iteration on this factorisation.
//!
//! The module knows nothing about meshes: matrices are sprs [`CsMatView`]s in compressed
//! sparse column form, of which only the lower triangle (row >= column) is read, so either
//! a full symmetric matrix or its lower half can be passed.

mod amd;
mod dense;
pub mod eigen;
mod graph;
mod nested_dissection;
mod numeric;
mod ordering;
mod priority;
mod separator;
mod symbolic;

use std::fmt;

pub use amd::{amd_order, amf_order};
pub use nested_dissection::nested_dissection_order;
pub use numeric::Numeric;
pub use ordering::{
    cheaper_order, dissection_if_large, expand_blocks, fill_or_dissection, fill_reducing_order, order_flops,
    DISSECTION_MIN_NODES,
};
pub use symbolic::{Ordering, Symbolic};

use crate::error_code::ErrorCode;

/// A matrix view in compressed sparse column form with `usize` indices.
pub type CsMatView<'a> = sprs::CsMatView<'a, f64>;

/// `out = A x` for `A` in compressed sparse column form (all of it: both triangles of a
/// symmetric matrix must be stored).
pub fn mul_into(a: CsMatView<'_>, x: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|y| *y = 0.0);
    for (j, column) in a.outer_iterator().enumerate() {
        for (i, &value) in column.iter() {
            out[i] += value * x[j];
        }
    }
}

/// Why a factorisation could not be computed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FactorError {
    /// The matrix is not square, or not in compressed sparse column form.
    NotSquareCsc {
        /// Rows of the matrix.
        rows: usize,
        /// Columns of the matrix.
        cols: usize,
    },
    /// The matrix's sparsity pattern differs from the analysed one.
    PatternMismatch,
    /// A given ordering is not a permutation of `0..n`.
    InvalidOrdering,
    /// A pivot was not positive (the matrix is not positive definite) or not finite.
    NotPositiveDefinite {
        /// The column of the original (unpermuted) matrix whose pivot failed.
        column: usize,
        /// The pivot value found.
        pivot: f64,
    },
    /// A solve was asked of a factor whose last factorisation failed or never ran.
    NotFactored,
    /// A value map ([`Symbolic::reading_values_through`]) does not have one slot per entry
    /// of the analysed pattern, or names a slot outside its source.
    ValueMap {
        /// Entries of the analysed pattern.
        entries: usize,
        /// Length of the source.
        source_len: usize,
    },
    /// The factor's storage could not be allocated.
    OutOfMemory {
        /// Bytes asked for.
        bytes: usize,
    },
    /// A right-hand side has the wrong length.
    DimensionMismatch {
        /// Expected length.
        expected: usize,
        /// Given length.
        found: usize,
    },
}

impl fmt::Display for FactorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotSquareCsc { rows, cols } => {
                write!(f, "expected a square matrix in compressed sparse column form, got {rows} x {cols}")
            }
            Self::PatternMismatch => write!(f, "the matrix's sparsity pattern differs from the analysed one"),
            Self::InvalidOrdering => write!(f, "the given ordering is not a permutation of the unknowns"),
            Self::NotPositiveDefinite { column, pivot } => write!(
                f,
                "the matrix is not positive definite: pivot {pivot} at column {column} (of the original matrix)"
            ),
            Self::NotFactored => write!(f, "no valid factorisation: the last one failed or none was computed"),
            Self::ValueMap { entries, source_len } => {
                write!(f, "a value map must give a slot below {source_len} for each of the pattern's {entries} entries")
            }
            Self::OutOfMemory { bytes } => {
                write!(f, "out of memory: the factor needs {:.0} MB more", (*bytes as f64 / 1e6).ceil())
            }
            Self::DimensionMismatch { expected, found } => {
                write!(f, "right-hand side has length {found}, expected {expected}")
            }
        }
    }
}

impl std::error::Error for FactorError {}

impl FactorError {
    /// The kind of error: [`ErrorCode::NotPositiveDefinite`] for a failed pivot,
    /// [`ErrorCode::OutOfMemory`], and otherwise [`ErrorCode::InvalidArgument`] (a matrix,
    /// ordering or right-hand side that does not fit, or a solve without a factor: only
    /// direct callers of [`crate::sparse`] can cause these).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::NotPositiveDefinite { .. } => ErrorCode::NotPositiveDefinite,
            Self::OutOfMemory { .. } => ErrorCode::OutOfMemory,
            _ => ErrorCode::InvalidArgument,
        }
    }
}
