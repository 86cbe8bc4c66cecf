//! The verdicts a run decided, checked again with the clocks of different machines ordered
//! (§6, time; [`crate::clocks`]). Unordered, the model is small but a counterexample or a
//! witness it finds may need one machine's longer timeout up before another's shorter one,
//! which no run shows; ordered, it is exact in that but may be far larger. So the search is
//! unordered first, and only where a verdict rests on a run (a `never`/`always` or liveness
//! property that fails, a `reachable` that holds) is that property checked again ordered, by
//! the explicit engine with a budget as large. A verdict found there replaces the first; where
//! that search runs out, the run itself is followed through the ordered model (`confirm.rs`);
//! where neither decides, the property is undecided ([`PropertyOutcome::unconfirmed`]), since
//! its run may be none a robot makes. A verdict that rests on an absence stands as it is: the
//! ordered model's runs are some of the unordered one's. A deadlock's run is followed; where
//! it does not follow, the report names the machines whose clocks it took unordered.

use crate::confirm::Found;
use crate::outcome::{Finding, OrderedCheck, PropertyOutcome, Report, Run, Trace, Verdict};
use crate::property::PropertySource;
use crate::{Options, SearchEngine, VerifyError};
use std::time::Instant;

/// A check of some properties with some options, deciding those it leaves undecided by
/// their runs where they follow through its model (`confirm.rs`).
pub(crate) type Check<'c> =
    dyn FnMut(&[PropertySource], Options, &[Option<Found>]) -> Result<Report, VerifyError> + 'c;

/// A deadlock's run followed through the ordered model, as that model's trace (`confirm.rs`).
pub(crate) type Follows<'c> = dyn FnMut(&Run) -> Result<Option<Trace>, VerifyError> + 'c;

/// `report`, of `properties` checked with clocks unordered where `ordered` names the
/// machines that would be ordered (none: nothing to check again), with the verdicts a run
/// decided checked again by `check` (the properties and options it is given), and a
/// deadlock's run followed by `follows`.
pub(crate) fn check_ordered(
    mut report: Report,
    properties: &[PropertySource],
    ordered: Vec<String>,
    options: Options,
    check: &mut Check<'_>,
    follows: &mut Follows<'_>,
) -> Result<Report, VerifyError> {
    if ordered.is_empty() {
        return Ok(report);
    }
    let rests: Vec<usize> = (report.properties.iter().enumerate())
        .filter(|(_, p)| p.trace.is_some() || p.cycle.is_some())
        .map(|(i, _)| i)
        .collect();
    // A world from which no transition can ever fire again, with the clocks unordered, is one
    // with them ordered too (its ordered steps are some of its unordered ones): only the way to
    // it needs following.
    let mut unconfirmed = false;
    for finding in &mut report.findings {
        if let Finding::Deadlock { trace, .. } = finding {
            match follows(&trace.run)? {
                Some(ordered) => *trace = ordered,
                None => unconfirmed = true,
            }
        }
    }
    if !rests.is_empty() {
        let again: Vec<PropertySource> = rests.iter().map(|&i| properties[i].clone()).collect();
        let found: Vec<Option<Found>> = (rests.iter())
            .map(|&i| Found::of(&report.properties[i]))
            .collect();
        let options = Options {
            clock_order: true,
            // Bounded by the budget: the ordered model may be far larger than the first.
            engine: SearchEngine::Explicit,
            ..options
        };
        let started = Instant::now();
        let second = check(&again, options, &found)?;
        let seconds = started.elapsed().as_secs_f64();
        for (&i, outcome) in rests.iter().zip(second.properties) {
            debug_assert_eq!(report.properties[i].name, outcome.name);
            report.properties[i] = match outcome.verdict {
                Verdict::Holds | Verdict::Fails => outcome,
                Verdict::Incomplete => {
                    unconfirmed = true;
                    undecided(outcome)
                }
            };
        }
        report.clocks_ordered = Some(OrderedCheck {
            stats: second.stats,
            seconds,
        });
    }
    if unconfirmed {
        report.unordered_clocks = ordered;
    }
    Ok(report)
}

/// A property the ordered check left undecided, its unordered run not confirmed.
fn undecided(outcome: PropertyOutcome) -> PropertyOutcome {
    PropertyOutcome {
        verdict: Verdict::Incomplete,
        trace: None,
        cycle: None,
        unconfirmed: true,
        ..outcome
    }
}
