//! `FitError`: why a deformation operator could not be fitted or evaluated. Lengths are
//! counted in numbers (two per point), as the flat arrays of the JavaScript API hold them.

use std::fmt;

use crate::error_code::ErrorCode;
use crate::message::Number;
use crate::sparse::eigen::EigenError;
use crate::sparse::FactorError;

/// Why a deformation operator could not be fitted, or an operator refused an input.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FitError {
    /// The number of values does not match, counted in numbers.
    Length {
        /// What was given, e.g. "targets".
        what: &'static str,
        /// How many numbers are expected.
        expected: usize,
        /// How many numbers were given.
        found: usize,
    },
    /// A value is NaN or infinite.
    NonFinite {
        /// What holds it, e.g. "targets" or "ground truth".
        what: &'static str,
        /// Its index in that array (in numbers).
        index: usize,
    },
    /// There is no handle.
    NoHandles,
    /// There is no training sample.
    NoSamples,
    /// A handle is not a point of the mesh (the deformers' check).
    InvalidHandle(crate::deform::DeformError),
    /// An operator's puppet does not fit the mesh it is written with (why).
    InvalidPuppet(String),
    /// Two handles have the same rest position.
    CoincidentHandles {
        /// The first handle.
        first: usize,
        /// The second handle.
        second: usize,
    },
    /// A polynomial handle basis has more functions than there are samples and no
    /// regularisation was asked for, or there are fewer samples than the k + 1 linear
    /// functions (k handle coordinates, 2n unless canonical or with fixed handles; the
    /// regularisation does not act on them): the fit is not unique.
    TooFewSamples {
        /// The number of samples.
        samples: usize,
        /// The number of handle basis functions |Ψ|.
        basis_size: usize,
    },
    /// A system of the fit is singular: the samples do not determine the handle basis
    /// (they lie on a polynomial hypersurface, or repeat), or the spatial basis cannot
    /// interpolate at the handles.
    Singular {
        /// Which system, e.g. "samples" or "handles".
        what: &'static str,
    },
    /// The reduced spatial basis is not valid: not M-orthonormal, or 1, x, y not in its span.
    InvalidSpatialBasis {
        /// What is wrong.
        reason: &'static str,
    },
    /// An option is out of range.
    InvalidOption {
        /// The option's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be accepted.
        expected: &'static str,
    },
    /// Canonical coordinates and fixed handles together: a rigid motion of all targets
    /// moves the fixed handles.
    CanonicalWithFixed,
    /// A fixed handle's index is out of range or repeated.
    InvalidFixedHandle {
        /// The index.
        index: usize,
    },
    /// A sample's target for a fixed handle is not the handle's rest position.
    FixedHandleMoved {
        /// The sample.
        sample: usize,
        /// The fixed handle.
        handle: usize,
    },
    /// A sparse factorisation failed.
    Factor(FactorError),
    /// The eigenproblem of a reduced spatial basis failed.
    Eigen(crate::sparse::eigen::EigenError),
    /// An operator cannot be carried to a fine mesh, or a carried one is not consistent
    /// (`carry`): why.
    Carry {
        /// Why.
        reason: String,
    },
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Length { what, expected, found } => write!(f, "{what}: expected {expected} numbers, got {found}"),
            Self::NonFinite { what, index } => write!(f, "{what}: value {index} is not a finite number"),
            Self::NoHandles => write!(f, "a deformation operator needs at least one handle"),
            Self::NoSamples => write!(f, "a deformation operator needs at least one training sample"),
            Self::InvalidHandle(e) => e.fmt(f),
            Self::InvalidPuppet(why) => write!(f, "the operator's puppet does not fit the mesh: {why}"),
            Self::CoincidentHandles { first, second } => {
                write!(f, "handles {first} and {second} have the same rest position")
            }
            Self::TooFewSamples { samples, basis_size } => write!(
                f,
                "{samples} samples cannot determine a handle basis of {basis_size} functions: \
                 give at least {basis_size} samples, or a regularisation"
            ),
            Self::Singular { what } => write!(f, "the fit's system for the {what} is singular"),
            Self::InvalidSpatialBasis { reason } => write!(f, "invalid reduced spatial basis: {reason}"),
            Self::InvalidOption { name, value, expected } => {
                write!(f, "option {name} = {} is out of range: expected {expected}", Number(*value))
            }
            Self::CanonicalWithFixed => f.write_str(
                "canonical coordinates and fixed handles cannot be combined: a rigid motion moves the fixed handles",
            ),
            Self::InvalidFixedHandle { index } => {
                write!(f, "fixed handle {index} is not a handle, or is given twice")
            }
            Self::FixedHandleMoved { sample, handle } => {
                write!(f, "sample {sample} moves fixed handle {handle} away from its rest position")
            }
            Self::Factor(e) => e.fmt(f),
            Self::Eigen(e) => write!(f, "the reduced basis could not be computed: {e}"),
            Self::Carry { reason } => write!(f, "the rig cannot be carried to the fine mesh: {reason}"),
        }
    }
}

impl std::error::Error for FitError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Factor(e) => Some(e),
            Self::Eigen(e) => Some(e),
            Self::InvalidHandle(e) => Some(e),
            _ => None,
        }
    }
}

impl FitError {
    /// The kind of error: [`ErrorCode::InvalidOption`] for options (fixed handles and the
    /// canonical option included) and too few samples for the basis, the factorisation's
    /// own, [`ErrorCode::NoConvergence`] for a reduced basis's eigenproblem that did not
    /// converge, otherwise [`ErrorCode::InvalidArgument`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::InvalidOption { .. }
            | Self::TooFewSamples { .. }
            | Self::CanonicalWithFixed
            | Self::InvalidFixedHandle { .. } => ErrorCode::InvalidOption,
            Self::Factor(e) => e.code(),
            Self::InvalidHandle(e) => e.code(),
            Self::Eigen(EigenError::NotConverged { .. }) => ErrorCode::NoConvergence,
            Self::Eigen(EigenError::Factor(e)) => e.code(),
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl From<FactorError> for FitError {
    fn from(e: FactorError) -> Self {
        Self::Factor(e)
    }
}

/// `Err(NonFinite)` naming the first value of `values` that is NaN or infinite.
pub(crate) fn check_finite(what: &'static str, values: &[f64]) -> Result<(), FitError> {
    match values.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(FitError::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// `Err(Length)` unless `values` has `expected` numbers.
pub(crate) fn check_length(what: &'static str, values: &[f64], expected: usize) -> Result<(), FitError> {
    if values.len() == expected {
        Ok(())
    } else {
        Err(FitError::Length { what, expected, found: values.len() })
    }
}
