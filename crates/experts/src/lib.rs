//! Experts: modules that own transition labels and proclaim them on the whiteboard
//! (`../shared/spec/behaviour.md` §2). A machine cannot tell one from another.
//!
//! - [`ReasonerExpert`]: a `.dl` theory whose inputs are whiteboard messages and whose outputs are
//!   the atoms it answers;
//! - [`Impersonator`]: answers from a script, from Rust, or from a person at a prompt;
//! - [`GameControllerReceiver`]: the RoboCup SPL GameController on a real UDP socket, and
//!   [`simulator`] to play a game to it;
//! - [`ButtonWrapper`] and [`FallWrapper`]: debounced propositions from raw sensor postings.
//!
//! Scripts and mapping files are parsed purely (`script`, `mapping`); sockets and the terminal
//! are touched only by the `run` methods.

mod answers;
mod buttons;
mod gamecontroller;
mod impersonator;
mod lines;
mod mapping;
mod reasoner;
mod script;
pub mod simulator;

pub use buttons::{ButtonWrapper, FallWrapper};
pub use gamecontroller::{GameControllerReceiver, ReceiverConfig, ReceiverCounters};
pub use impersonator::Impersonator;
pub use lines::{LineError, LineErrors};
pub use mapping::parse_mapping;
pub use reasoner::ReasonerExpert;
pub use script::{parse_script, Script, ScriptStep, When};

/// Parses a duration written `250ms`, `2s`, `1.5s` or `3` (seconds).
pub fn parse_duration(text: &str) -> Option<std::time::Duration> {
    let t = text.trim();
    let (number, scale) = if let Some(ms) = t.strip_suffix("ms") {
        (ms, 1e-3)
    } else if let Some(us) = t.strip_suffix("us") {
        (us, 1e-6)
    } else if let Some(s) = t.strip_suffix('s') {
        (s, 1.0)
    } else {
        (t, 1.0)
    };
    let value: f64 = number.trim().parse().ok()?;
    (value.is_finite() && value >= 0.0).then(|| std::time::Duration::from_secs_f64(value * scale))
}
