//! What a fair run must visit for ever, and the failing run a liveness search finds: the
//! acceptance sets (one a machine that must get its turn, one a `fair` expression), shared by
//! the search (`liveness.rs`) and the drawing of its lasso (`lasso.rs`).

use crate::property::Property;
use crate::search::Search;
use crate::world::{Status, SystemState};

/// A failing run found: where it enters the bad states, the bad states (`inside`), and the
/// component where it stays for ever.
pub struct FailingRun {
    /// The state the run starts staying bad from.
    pub seed: u32,
    pub inside: Vec<bool>,
    /// The states of the component the run ends in (one, with no successors, for a run that
    /// ends).
    pub component: Vec<u32>,
}

/// How many acceptance sets a fair run of `property` meets infinitely often: one a machine,
/// then one a `fair` expression.
pub fn acceptance_sets(model: &Search, property: &Property) -> usize {
    model.machines.len() + property.fair_terms().len()
}

/// Whether `world` is in acceptance set `set` (see [`acceptance_sets`]).
pub fn meets(model: &Search, property: &Property, world: &SystemState, set: usize) -> bool {
    let machines = model.machines.len();
    if set >= machines {
        return property.fair_holds_in(set - machines, model, world);
    }
    let control = &world.machines[set];
    let tests = model.machines[set].states[usize::from(control.state)]
        .time_tests
        .len();
    let all_due = (1u32 << tests) - 1;
    control.status != Status::Running
        || control.just_entered
        || tests == 0
        || u32::from(control.time) & all_due == all_due
}
