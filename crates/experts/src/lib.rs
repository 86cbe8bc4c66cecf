//! Experts: modules that own transition labels and proclaim them on the whiteboard
//! (`docs/spec/behaviour.md` §2). A machine cannot tell one from another.
//!
//! - [`ReasonerExpert`]: a `.dl` theory whose inputs are whiteboard messages and whose outputs are
//!   the atoms it answers;
//! - [`Impersonator`]: answers from a script, from Rust, or from a person at a prompt;
//! - [`FunctionExpert`]: answers by calling a function of the embedding program when asked;
//! - [`GameControllerReceiver`]: the RoboCup SPL GameController on a real UDP socket (the
//!   simulator that plays a game to it, answering nothing, is `proclaim-gcsim`);
//! - [`ButtonWrapper`] and [`FallWrapper`]: debounced propositions from raw sensor postings;
//! - [`ProgramExpert`]: any program as an expert, a supervised child process speaking JSON
//!   lines (`protocol`);
//! - the Prolog expert ([`prolog_expert`]): a `.pl` knowledge base proved by SWI-Prolog, a
//!   program expert running a driver shipped inside proclaim.
//!
//! Scripts and mapping files are parsed purely (`proclaim_syntax::parse_script`, `mapping`); sockets and the terminal
//! are touched only by the `run` methods.

mod answers;
mod buttons;
mod function;
mod gamecontroller;
mod impersonator;
mod mapping;
mod program;
mod prolog;
pub mod protocol;
mod reasoner;

pub use buttons::{ButtonWrapper, FallWrapper};
pub use function::{AnswerFunction, FunctionExpert};
pub use gamecontroller::{GameControllerReceiver, ReceiverConfig, ReceiverCounters};
pub use impersonator::{value_of as script_value, HeldAnswer, Impersonator, ScriptPosition};
pub use mapping::parse_mapping;
pub use proclaim_syntax::{parse_duration, LineError, LineErrors};
pub use proclaim_syntax::{parse_script, Script, ScriptStep, ScriptValue, When};
pub use program::{Backoff, ProgramCounters, ProgramExpert};
pub use prolog::{
    check_knowledge_base, find_program, find_swipl, prolog_expert, KnowledgeBase, PrologError,
};
pub use reasoner::{HeldInput, LastAnswer, ReasonerExpert, ReasonerMemory};
