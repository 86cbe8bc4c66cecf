//! A behaviour's machines as runners sharing its variables, epoch and suppressor: what a run
//! (`launch.rs`) and a replay (`recorded.rs`) both start.

use crate::load::Behaviour;
use proclaim_board::Suppressor;
use proclaim_runner::{Event, Hosts, MachineRunner, RunOptions, Shared, Stepper};
use std::sync::Arc;
use tokio::sync::mpsc;

/// How the machines are driven: their host functions, whether a label with no answer in time
/// halts them, and what steps them.
#[derive(Clone, Copy)]
pub(crate) struct Driving<'o> {
    pub hosts: &'o Hosts,
    pub halt_on_timeout: bool,
    pub stepper: Option<&'o Stepper>,
}

/// A runner for every machine, in manifest order, sharing the behaviour's variables and
/// epoch, with its events into `tx`.
pub(crate) fn machine_runners(
    behaviour: &Behaviour,
    options: Driving<'_>,
    tx: &mpsc::UnboundedSender<Event>,
    epoch: tokio::time::Instant,
    shared: &Arc<Shared>,
) -> Vec<MachineRunner> {
    // One per run: what holds each suppressed type is the run's own.
    let suppressor = (!behaviour.suppress.is_empty()).then(|| {
        let holds = behaviour
            .suppress
            .iter()
            .map(|(ty, hold)| (ty.as_str(), *hold));
        Arc::new(parking_lot::Mutex::new(Suppressor::new(holds)))
    });
    behaviour
        .machines
        .iter()
        .map(|loaded| {
            let mut runner = MachineRunner::new(
                loaded.machine.clone(),
                options.hosts.clone(),
                RunOptions {
                    ring_period: behaviour.ring_period,
                    answer_timeout: behaviour.answer_timeout,
                    start_running: loaded.start,
                    halt_on_timeout: options.halt_on_timeout,
                    stepper: options.stepper.cloned(),
                    shared: Some(shared.clone()),
                    epoch: Some(epoch),
                    priority: loaded.priority,
                    suppressor: suppressor.clone(),
                },
            )
            .with_loader(loaded.loader.clone());
            runner.events_into(tx.clone());
            runner
        })
        .collect()
}
