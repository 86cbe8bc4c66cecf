//! What `proclaim compile --target rust` prints of a behaviour: its tables and the functions
//! of its machines, behind the one trait [`Tables`] that the runtime's calls (`calls.rs`) and
//! its round schedule (`schedule.rs`) are generic over. Everything else a compiled behaviour
//! runs is this crate's code, compiled, linted and tested here.

use crate::world::{Scalar, World};

/// A behaviour compiled to Rust: the generated `behaviour.rs` implements it on its `Behaviour`.
/// Each table has an entry a machine, an output (the theories' answers first, then the atoms
/// from outside), or a whiteboard value the machines read, in the plan's order.
pub trait Tables: 'static {
    /// The machines' names, in schedule (manifest) order.
    const MACHINE_NAME: &'static [&'static str];
    /// Each machine's initial state, and whether it runs from the start (else it is dormant
    /// until started).
    const INITIAL: &'static [i64];
    const STARTS: &'static [bool];
    /// Each machine's subsumption layer, which its postings carry.
    const PRIORITY: &'static [u32];
    /// The whiteboard value each machine's running state is posted to (`NameIsRunning`).
    const STATUS_BOARD: &'static [Option<usize>];
    /// Each output's atom and its expert; the outputs a theory answers come first.
    const OUTPUT_NAME: &'static [&'static str];
    const OUTPUT_EXPERT: &'static [&'static str];
    const THEORY_OUTPUTS: usize;
    /// The whiteboard value of each output's atom: an expert's answer is posted there.
    const OUTPUT_BOARD: &'static [Option<usize>];
    /// Each whiteboard value's type, and whether it is bound with `extern` (read as a whole 0
    /// while unposted).
    const EXTERN_NAME: &'static [&'static str];
    const EXTERN_BOUND: &'static [bool];
    /// The types under subsumption and how long a higher layer's posting holds each, in ms.
    const SUPPRESSED: &'static [(&'static str, u64)];
    /// Each sensor wrapper and the atoms it answers: the host's script must set one of them.
    const SENSORS: &'static [(&'static str, &'static [&'static str])];
    /// The behaviour's own script (`[impersonator]`): its file and text.
    const SCRIPT: Option<(&'static str, &'static str)>;
    /// The theories' decision variables, then a known/true pair for each atom from outside
    /// (the world's `input`).
    const INPUTS: usize;
    /// The period of rounds without news, in milliseconds.
    const PERIOD_MS: u64;
    /// How many control commands a machine keeps waiting in one ringlet.
    const COMMANDS: usize;
    /// How long a query to an expert in another process waits, in milliseconds.
    const ANSWER_TIMEOUT_MS: u64;
    /// The composite states of the machines' charts, numbered across the behaviour: the
    /// machine each is in. The time tests of a composite's transitions count from its entry.
    const COMPOSITE_MACHINE: &'static [usize] = &[];
    /// The manifest's `[ranges]`: the whole numbers (lowest, highest) the world posts to each
    /// type, which what `verify` proved assumed.
    const RANGES: &'static [(&'static str, i64, i64)] = &[];

    /// Each value slot's start: the machines' variables, then the globals.
    fn var_inits() -> Vec<Scalar>;
    /// Output `k`'s answer, from the theories' inputs as they are now.
    fn answer(w: &World, k: usize) -> bool;
    /// A posting's content applied to the theory inputs of its type; whether there were any.
    fn apply_input(w: &mut World, ty: &str, content: &str) -> bool;
    /// A ringlet of every machine due to ring, in manifest order; whether one fired.
    fn ring_machines(w: &mut World) -> bool;
    /// Whether machine `m`'s current state has no way out.
    fn final_state(w: &World, m: usize) -> bool;
    /// The soonest of `due` and machine `m`'s time tests still to come due, in ms from now.
    fn due_of(w: &World, m: usize, due: u64) -> u64;
    /// Whether machine `m`'s current labels read output `k`, the globals, whiteboard value `e`.
    fn reads(w: &World, m: usize, k: usize) -> bool;
    fn reads_globals(w: &World, m: usize) -> bool;
    fn reads_extern(w: &World, m: usize, e: usize) -> bool;
}
