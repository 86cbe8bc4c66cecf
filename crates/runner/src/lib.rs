//! Runs machines on the whiteboard (`docs/spec/behaviour.md` §3): [`Rounds`] gives every
//! machine of a behaviour one ringlet per round in order (§3.1), or a [`MachineRunner`] runs one
//! machine on a task of its own. A ringlet: OnEntry on arrival, the snapshot, transitions tried in
//! priority order with each label proved (conditions by their expert, variables and values on
//! the spot), OnExit on leaving, Internal when nothing fired; between rounds, wait for news a
//! current label reads, the next time test, or the ring period. Activities run gufsm's activity language over variables with gufsm's
//! scoping ([`Shared`], [`Locals`]). Sub-machines obey the [`Command`]s posted to their name
//! and post `NameIsRunning`; `reload` / `reread` read the machine's file again through a
//! [`Loader`] (a failure leaves the machine untouched). What happens is reported as
//! [`Event`]s, data a trace can record. No file I/O of its own: loaders come from the caller.

mod activity;
mod checkpoint;
mod eval;
mod event;
mod feed;
mod host;
mod label;
mod machine;
mod rounds;
mod seen;
mod step;
mod team;
mod variables;

pub use activity::SharedSuppressor;
pub use checkpoint::{
    AskedImage, Checkpoints, CompositeImage, Fit, HoldImage, MachineImage, RankedImage,
    RoundsImage, SeenImage, StatusName, VariableImage,
};
pub use event::{Answerer, Event};
pub use feed::{Feed, RoundCounter};
pub use host::{HostFunction, Hosts};
pub use machine::{asked, declaration, Loader, MachineRunner, RunOptions};
pub use proclaim_fsm::control::{machine_of_running_type, running_type, Command};
pub use proclaim_runtime::Ringlet;
pub use rounds::{Rounds, RoundsEnd};
pub use step::Stepper;
pub use variables::{Locals, Shared};
