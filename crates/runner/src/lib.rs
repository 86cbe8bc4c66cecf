//! Runs machines on the whiteboard (`../shared/spec/behaviour.md` §3): one ring at a time, OnEntry
//! on arrival, transitions tried in priority order with each label proved by its expert, OnExit
//! on leaving, Internal when nothing fired; between rings, wait for a message a label of the
//! state depends on, or the ring period. Sub-machines obey `Name: On/Off/suspend/resume/restart`
//! and post `NameIsRunning`; `Name: reload` / `Name: reread` read the machine's file again
//! through a [`Loader`] (a failure leaves the machine untouched). What happens is reported as
//! [`Event`]s, data a trace can record. No file I/O of its own: loaders come from the caller.

mod event;
mod host;
mod label;
mod machine;
mod step;

pub use event::{Answerer, Event};
pub use host::{HostFunction, Hosts};
pub use machine::{declaration, Loader, MachineRunner, RunOptions};
pub use step::Stepper;
