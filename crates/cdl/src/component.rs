//! What deciding a component with a cycle is given and gives: the component, its internal
//! reads, the search's limits, the outcome and how it was reached. Apart from `cycle.rs`, which
//! decides, so that the strategies it calls (`ring.rs`, `layers.rs`, `relevance.rs`) and the
//! session that asks it read these types without reading `cycle.rs` back.

use crate::engine::Engine;
use crate::goal::Goal;

/// Bounds on the search inside one component (cdl.md §4: no algorithm is polynomial on every
/// theory, so the search is bounded and says when the bound was hit).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SearchLimits {
    /// Goals the top-down search may expand inside one component before its remaining members
    /// are left undecided.
    pub steps: u64,
    /// Memory the search's memo of answers under a history may take, in bytes.
    pub memo_bytes: usize,
}

impl Default for SearchLimits {
    fn default() -> SearchLimits {
        SearchLimits {
            steps: 10_000_000,
            memo_bytes: 256 << 20,
        }
    }
}

/// How a component was decided (for `check`'s warnings and the tests).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Method {
    /// Support only inside: the least fixpoint.
    Fixpoint,
    /// Every member reads exactly one other: composed around the cycle.
    SimpleCycle,
    /// Members attack each other symmetrically and nothing else: maximum matchings.
    Geography,
    /// A ring of small single-entry blocks: each block's transfer function, composed round it.
    Ring,
    /// A ring of layers of two goals, each reading only the next layer: one pass over the
    /// layers per member.
    Layers,
    /// Bounds, then a top-down search for the members between them.
    Search,
}

/// What evaluating a component gave.
pub(crate) enum Outcome {
    Evaluated(Evaluated),
    /// Without the reads its members' conditions ignore, the component is several: these, as
    /// positions, in the order they can be evaluated (each reads only itself and earlier ones).
    Parts(Vec<Vec<u32>>),
}

/// Each member's value (`TRUE`, `FALSE` or `UNDECIDED`).
pub(crate) struct Evaluated {
    pub values: Vec<u8>,
    pub method: Method,
    /// Goals the search expanded.
    pub steps: u64,
}

/// One component to evaluate. Its members are `PENDING` in `values`; every other goal it reads
/// is settled.
pub(crate) struct Component<'a> {
    pub engine: &'a Engine,
    pub mu: &'a [bool],
    pub values: &'a [u8],
    /// A member's position in `members`, by goal.
    pub position: &'a [u32],
    pub members: &'a [Goal],
}

/// An internal read: (reader, read member, through an attacker).
pub(crate) type Edge = (u32, u32, bool);
