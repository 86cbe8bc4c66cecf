//! The fixed text of a behaviour compiled to a Cargo project, with `@NAME@` where
//! `print_rust.rs` fills in the behaviour's own parts: its tables and the functions of its
//! machines. Everything they call, the round schedule and the host are `proclaim-runtime`'s.

/// `src/behaviour.rs` around its machines' code.
pub(crate) const BODY: &str = r#"//! The behaviour `@name@` compiled by proclaim (generated: do not edit): its tables and a
//! ringlet a machine. What they call (`proclaim_runtime::calls`), the round schedule and the
//! program around them are `proclaim_runtime`'s.

use crate::runtime::*;
use proclaim_runtime::calls::*;

/// The machines' names, in schedule order.
const MACHINE_NAME: &[&str] = &[@machine_names@];
const LOOP_LIMIT: u32 = @loop_limit@;

/// The behaviour as `proclaim_runtime` runs it.
pub struct Behaviour;

impl proclaim_runtime::Tables for Behaviour {
    const MACHINE_NAME: &'static [&'static str] = MACHINE_NAME;
    const INITIAL: &'static [i64] = &[@initials@];
    const STARTS: &'static [bool] = &[@starts@];
    const PRIORITY: &'static [u32] = &[@priorities@];
    const STATUS_BOARD: &'static [Option<usize>] = &[@status_board@];
    const OUTPUT_NAME: &'static [&'static str] = &[@output_names@];
    const OUTPUT_EXPERT: &'static [&'static str] = &[@experts@];
    const THEORY_OUTPUTS: usize = @theory_outputs@;
    const OUTPUT_BOARD: &'static [Option<usize>] = &[@output_board@];
    const EXTERN_NAME: &'static [&'static str] = &[@extern_names@];
    const EXTERN_BOUND: &'static [bool] = &[@extern_bound@];
    const SUPPRESSED: &'static [(&'static str, u64)] = &[@suppressed@];
    const SENSORS: &'static [(&'static str, &'static [&'static str])] = &[@sensors@];
    const SCRIPT: Option<(&'static str, &'static str)> = @script@;
    const INPUTS: usize = @inputs@;
    const PERIOD_MS: u64 = @period_ms@;
    const COMMANDS: usize = @commands@;
    const ANSWER_TIMEOUT_MS: u64 = @answer_timeout_ms@;
    const COMPOSITE_MACHINE: &'static [usize] = &[@composite_machine@];
    const RANGES: &'static [(&'static str, i64, i64)] = &[@ranges@];

    fn var_inits() -> Vec<Scalar> {
        vec![@var_inits@]
    }
    fn answer(w: &World, k: usize) -> bool {
        answer(w, k)
    }
    fn apply_input(w: &mut World, ty: &str, content: &str) -> bool {
        apply_input(w, ty, content)
    }
    fn ring_machines(w: &mut World) -> bool {
        ring_machines(w)
    }
    fn final_state(w: &World, m: usize) -> bool {
        final_state(w, m)
    }
    fn due_of(w: &World, m: usize, due: u64) -> u64 {
        due_of(w, m, due)
    }
    fn reads(w: &World, m: usize, k: usize) -> bool {
        reads(w, m, k)
    }
    fn reads_globals(w: &World, m: usize) -> bool {
        reads_globals(w, m)
    }
    fn reads_extern(w: &World, m: usize, e: usize) -> bool {
        reads_extern(w, m, e)
    }
}

// `answer`: each output's answer; `apply_input`: whether a posting's type is a theory input
// (then applied).
@answers@
@code@"#;
