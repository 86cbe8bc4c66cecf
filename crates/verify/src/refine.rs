//! The verdicts a run decided, checked again with the clocks of different machines ordered
//! (§6, time; [`crate::clocks`]). Unordered, the model is small but a counterexample or a
//! witness it finds may need one machine's longer timeout up before another's shorter one,
//! which no run shows; ordered, it is exact in that but may be far larger. So the search is
//! unordered first, and only where a verdict rests on a run (a `never`/`always` or liveness
//! property that fails, a `reachable` that holds) is that property checked again ordered,
//! by the explicit engine within the same budget. A verdict found there replaces the first;
//! where none is found the first stands, and the report names the machines whose clocks it
//! took unordered. A verdict that rests on an absence stands as it is: the ordered model's
//! runs are some of the unordered one's.

use crate::outcome::{Report, Verdict};
use crate::property::PropertySource;
use crate::{Options, SearchEngine, VerifyError};

/// A check of some properties with some options: [`crate::verify_with_progress`].
pub(crate) type Check<'c> =
    dyn FnMut(&[PropertySource], Options) -> Result<Report, VerifyError> + 'c;

/// `report`, of `properties` checked with clocks unordered where `ordered` names the
/// machines that would be ordered (none: nothing to check again), with the verdicts a run
/// decided checked again by `check` (the properties and options it is given).
pub(crate) fn check_ordered(
    mut report: Report,
    properties: &[PropertySource],
    ordered: Vec<String>,
    options: Options,
    check: &mut Check<'_>,
) -> Result<Report, VerifyError> {
    let rests: Vec<usize> = (report.properties.iter().enumerate())
        .filter(|(_, p)| p.trace.is_some() && p.verdict != Verdict::Incomplete)
        .map(|(i, _)| i)
        .collect();
    if ordered.is_empty() || rests.is_empty() {
        return Ok(report);
    }
    let again: Vec<PropertySource> = rests.iter().map(|&i| properties[i].clone()).collect();
    let options = Options {
        clock_order: true,
        // Bounded by the budget: the ordered model may be far larger than the first.
        engine: SearchEngine::Explicit,
        ..options
    };
    let second = check(&again, options)?;
    let mut unconfirmed = false;
    for (&i, outcome) in rests.iter().zip(second.properties) {
        debug_assert_eq!(report.properties[i].name, outcome.name);
        match outcome.verdict {
            Verdict::Holds | Verdict::Fails => report.properties[i] = outcome,
            _ => unconfirmed = true,
        }
    }
    if unconfirmed {
        report.unordered_clocks = ordered;
    }
    report.clocks_ordered = Some(second.stats);
    Ok(report)
}
