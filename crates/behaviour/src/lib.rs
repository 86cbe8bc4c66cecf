//! Behaviours: a folder under `machines/` whose `behaviour.toml` names its machines, theories,
//! sensor wrappers and impersonator script. [`load`] reads and checks every file (every problem
//! reported with file and line; a behaviour with errors never starts), [`launch`] starts it on a
//! whiteboard, experts before machines, and merges the machines' events into one trace, which
//! [`TraceView`] prints for people and [`read_trace`] reads back from JSON lines.
//!
//! Reads files (through [`Files`]: a folder, or texts built into the program) and opens the
//! sockets its sensors need; it does not watch files or print: the binary does.

mod analysis;
mod branch;
mod checkpoint;
mod coverage;
mod deps;
mod draw;
mod edited;
mod error;
mod files;
mod from_trace;
mod launch;
mod linking;
mod liveness;
mod load;
mod loaded;
mod manifest;
mod modules;
mod program_entries;
mod programs;
mod range_watch;
mod ranges;
mod recorded;
mod replaced;
mod rerecord;
mod runners;
mod skeleton;
mod subsumption;
mod team;
pub mod testing;
mod trace;
mod tried;
mod why;

pub use analysis::{check_behaviour, check_behaviour_with, script_warnings};
pub use branch::Branch;
pub use checkpoint::{
    Checkpoint, CheckpointPlan, RangeWarning, ScriptImage, TheoryImage, CHECKPOINT_FORMAT,
    CHECKPOINT_VERSION,
};
pub use coverage::{coverage, Coverage, Covered, CoveredPlace};
pub use deps::{launch_manifest, module_diagram, overall_diagram};
pub use draw::behaviour_to_dot;
pub use edited::check_edited;
pub use error::BehaviourError;
pub use files::{Embedded, Files, Folder};
pub use launch::{launch, LaunchOptions, Running};
pub use liveness::{parse_liveness, Definition, GaiaFormula};
pub use load::{
    load, load_manifest, read_machines, Behaviour, LoadedMachine, LoadedSensor, LoadedTheory,
};
pub use manifest::{
    parse_manifest, split_leads_to, ImpersonatorEntry, MachineEntry, Manifest, PropertyEntry,
    PropertyKind, Schedule, SensorEntry, SensorKind, Simulator, TeamEntry, TheoryEntry, LEADS_TO,
    MANIFEST,
};
pub use modules::{modules, Module, ModuleKind};
pub use program_entries::{ProgramEntry, PrologEntry};
pub use programs::{LoadedProgram, ProgramKind};
pub use ranges::DeclaredRange;
pub use recorded::{
    message_line, read_recording, replay_recording, ringlet_line, BranchOf, Difference, Recording,
    RecordingError, ReplayOutcome,
};
pub use rerecord::{rerecord, Rerecorded, RoundChange};
pub use skeleton::{liveness_machines, Skeleton};
pub use team::name_error as team_name_error;
pub use trace::{read_trace, TraceView};
pub use tried::{tried, Outcome, Tried, TriedError, TriedTransition};
pub use why::{held_at, theory_answers, Held, TheoryAnswer, WhyError};

/// The guide's Rust snippets (`docs/book`), compiled (and run) as doctests so they stay true.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/book/src/embedding.md")]
pub struct GuideEmbeddingDoctests;

/// The guide's testing chapter's Rust snippets, compiled as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/book/src/testing.md")]
pub struct GuideTestingDoctests;
