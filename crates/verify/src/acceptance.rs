//! What a fair run must visit for ever, and the failing run a liveness search finds: the
//! acceptance sets (one a clock of each machine whose time must pass, one a `fair`
//! expression), shared by the search (`liveness.rs`) and the drawing of its lasso (`lasso.rs`).

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

/// How many acceptance sets a fair run of `property` meets infinitely often: one a clock of
/// each machine (its states', then each timed composite's: [`crate::model::MachineModel::clocks`]),
/// then one a `fair` expression.
pub fn acceptance_sets(model: &Search, property: &Property) -> usize {
    clock_sets(model) + property.fair_terms().len()
}

/// How many acceptance sets time has: one a clock of each machine.
pub(crate) fn clock_sets(model: &Search) -> usize {
    model.machines.iter().map(|m| m.clocks.len()).sum()
}

/// The machine and clock of acceptance set `set`, when it is time's.
pub(crate) fn clock_of(model: &Search, mut set: usize) -> Option<(usize, Option<usize>)> {
    for (k, m) in model.machines.iter().enumerate() {
        match m.clocks.get(set) {
            Some(&clock) => return Some((k, clock)),
            None => set -= m.clocks.len(),
        }
    }
    None
}

/// Whether `world` is in acceptance set `set` (see [`acceptance_sets`]).
pub fn meets(model: &Search, property: &Property, world: &SystemState, set: usize) -> bool {
    let Some((k, clock)) = clock_of(model, set) else {
        return property.fair_holds_in(set - clock_sets(model), model, world);
    };
    time_passes(model, world, k, clock)
}

/// Machine `k` lets the time of `clock` pass in `world`: it is not running, or its state has no
/// test of that clock, or every such test is due, or the clock has just started.
pub(crate) fn time_passes(
    model: &Search,
    world: &SystemState,
    k: usize,
    clock: Option<usize>,
) -> bool {
    let control = &world.machines[k];
    let state = &model.machines[k].states[usize::from(control.state)];
    let mask = state.clock_mask(clock);
    control.status != Status::Running
        || (control.just_entered && state.arrival_starts(clock))
        || control.time & mask == mask
}
