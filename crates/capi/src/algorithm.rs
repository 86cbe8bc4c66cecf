//! The five proof algorithms as numbers C can pass.

use crate::detail::fail;
use crate::status::ProclaimStatus;
use proclaim_cdl::Algorithm;
use std::ffi::c_int;

/// The proof algorithm of a question (cdl.md §4). The header declares the functions' parameter
/// as this enum, so a C++ caller cannot pass a plain number nor C a value of another enum
/// unwarned; the library receives it as an `int` ([`AlgorithmArgument`]), so a number outside
/// this list is an error the call reports rather than undefined behaviour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProclaimAlgorithm {
    /// Definite provability: strict rules and facts only.
    Mu = 0,
    /// Ambiguity propagating.
    Pi = 1,
    /// Ambiguity blocking.
    Beta = 2,
    /// Proved by both β and π.
    Alpha = 3,
    /// Proved by β or π.
    Delta = 4,
}

/// A [`ProclaimAlgorithm`] as C passes it: any `int`, checked by [`AlgorithmArgument::algorithm`].
/// cbindgen writes it as `ProclaimAlgorithm` (`[export.rename]` in cbindgen.toml): the same size
/// and passing convention as `int`.
///
/// cbindgen:ignore
#[repr(transparent)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AlgorithmArgument(pub c_int);

impl AlgorithmArgument {
    /// The algorithm, or `BAD_ARGUMENT` saying what number came instead.
    pub(crate) fn algorithm(self) -> Result<Algorithm, ProclaimStatus> {
        ProclaimAlgorithm::from_code(self.0).ok_or_else(|| {
            fail(
                ProclaimStatus::BadArgument,
                format!(
                    "the algorithm is {}, which is none of PROCLAIM_ALGORITHM_MU (0) to \
                     PROCLAIM_ALGORITHM_DELTA (4)",
                    self.0
                ),
            )
        })
    }
}

impl From<ProclaimAlgorithm> for AlgorithmArgument {
    fn from(algorithm: ProclaimAlgorithm) -> AlgorithmArgument {
        AlgorithmArgument(algorithm as c_int)
    }
}

impl ProclaimAlgorithm {
    /// The algorithm a number from C stands for, if any.
    pub fn from_code(code: c_int) -> Option<Algorithm> {
        Some(match code {
            0 => Algorithm::Mu,
            1 => Algorithm::Pi,
            2 => Algorithm::Beta,
            3 => Algorithm::Alpha,
            4 => Algorithm::Delta,
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_numbers_follow_the_enum_and_nothing_else_is_an_algorithm() {
        for (variant, algorithm) in [
            (ProclaimAlgorithm::Mu, Algorithm::Mu),
            (ProclaimAlgorithm::Pi, Algorithm::Pi),
            (ProclaimAlgorithm::Beta, Algorithm::Beta),
            (ProclaimAlgorithm::Alpha, Algorithm::Alpha),
            (ProclaimAlgorithm::Delta, Algorithm::Delta),
        ] {
            assert_eq!(
                ProclaimAlgorithm::from_code(variant as c_int),
                Some(algorithm)
            );
        }
        assert_eq!(ProclaimAlgorithm::from_code(5), None);
        assert_eq!(ProclaimAlgorithm::from_code(-1), None);
    }
}
