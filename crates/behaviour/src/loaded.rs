//! A behaviour as loaded: the manifest with every file it names read and checked, ready to
//! start. The types alone, apart from `load.rs`'s reading, so that what reads a behaviour
//! (modules, program experts, subsumption) does not depend on how it was loaded.

use crate::files::Files;
use crate::manifest::{Manifest, ModuleEntry, SensorEntry};
use proclaim_cdl::Theory;
use proclaim_experts::Script;
use proclaim_fsm::Machine;
use proclaim_gcsim::GameScript;
use proclaim_runner::Loader;
use proclaim_syntax::FileDiagnostic;
use rustc_hash::FxHashMap;
use std::sync::Arc;
use std::time::Duration;

/// A behaviour ready to start.
pub struct Behaviour {
    pub name: String,
    pub manifest: Manifest,
    pub machines: Vec<LoadedMachine>,
    pub theories: Vec<LoadedTheory>,
    pub sensors: Vec<LoadedSensor>,
    /// Prolog knowledge bases and programs answering labels (`programs.rs`).
    pub programs: Vec<crate::programs::LoadedProgram>,
    pub script: Option<Script>,
    pub ring_period: Duration,
    pub answer_timeout: Duration,
    pub run_for: Option<Duration>,
    /// Modules outside the behaviour (the manifest's `[[module]]` and its dictionary's).
    pub outside: Vec<ModuleEntry>,
    /// The types under subsumption with their hold times (the manifest's `[suppress]`).
    pub suppress: Vec<(String, Duration)>,
    /// The manifest's `[ranges]`: whole numbers the world posts to a type.
    pub ranges: Vec<crate::ranges::DeclaredRange>,
    /// Warnings of its files, each with its place.
    pub warnings: Vec<FileDiagnostic>,
    pub files: Arc<dyn Files>,
}

impl Behaviour {
    /// The variables its machines share: globals and externs, from every machine's activities.
    pub fn shared_variables(&self) -> std::sync::Arc<proclaim_runner::Shared> {
        proclaim_runner::Shared::for_machines(self.machines.iter().map(|m| &m.machine))
    }
}

pub struct LoadedMachine {
    pub machine: Machine,
    pub file: String,
    pub start: bool,
    /// Its subsumption layer (the manifest's `priority`).
    pub priority: u32,
    /// Reads the file again (for `reload`, `reread` and `--watch`).
    pub loader: Loader,
}

pub struct LoadedTheory {
    pub name: String,
    pub file: String,
    pub theory: Theory,
    /// Input atom → message type.
    pub mapping: FxHashMap<String, String>,
    /// Bounds on the search inside attack cycles (the manifest's `budget`).
    pub limits: proclaim_cdl::SearchLimits,
}

pub struct LoadedSensor {
    pub entry: SensorEntry,
    /// The game the simulator plays, when it plays one.
    pub game: Option<GameScript>,
}
