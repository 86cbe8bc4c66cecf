//! The verification issue's random behaviours (`crates/verify/tests/common/random_behaviour.rs`,
//! used as is), compiled: every seed compiles, and its C program's trace is the interpreter's
//! byte for byte on the behaviour's own script (its Rust program's in `compiled_rust.rs`'s one
//! workspace). They read whiteboard values by name alone (inputs, globals nobody assigns, a
//! posted type), machines' `IsRunning` states, atoms nobody answers and theory inputs posted as
//! whole numbers. The interpreter runs them with `--force`, as a compiled program runs
//! (`check` finds an atom no script sets an error).

#[path = "../crates/verify/tests/common/random_behaviour.rs"]
#[allow(dead_code)]
mod random_behaviour;

use super::compiled::{assert_same, build, gcc_missing, scratch};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How many trace lines of a run that spins are held equal. A label that stays true on a state's
/// own loop (`when e0 == 0 -> S0`, `e0` never posted) moves round after round at one instant,
/// until both programs halt it 10,000 rounds on (the interpreter writing why in its trace, the
/// compiled program on stderr), or the test stops the slower one.
const SPIN_LINES: usize = 5_000;

/// Runs `command` until it ends, or until `trace` holds more than `SPIN_LINES` lines (then it
/// is stopped); the trace, and whether the run ended by itself.
pub(crate) fn bounded_run(mut command: Command, trace: &Path) -> (String, bool) {
    let mut child = command
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("the run starts");
    let started = Instant::now();
    let ended = loop {
        if child.try_wait().expect("the run is watched").is_some() {
            break true;
        }
        let lines = std::fs::read(trace)
            .map(|t| t.iter().filter(|b| **b == b'\n').count())
            .unwrap_or(0);
        if lines > SPIN_LINES || started.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            let _ = child.wait();
            break false;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    (std::fs::read_to_string(trace).unwrap_or_default(), ended)
}

/// Holds two runs' traces equal: whole when both ended short of `SPIN_LINES` lines, else their
/// first `SPIN_LINES` lines (a run may end while the other spins only by halting the spin,
/// past that many lines).
pub(crate) fn assert_same_bounded(
    name: &str,
    interpreted: (String, bool),
    compiled: (String, bool),
) {
    let spun = |t: &str| t.lines().count() >= SPIN_LINES;
    if !spun(&interpreted.0) && !spun(&compiled.0) {
        assert!(
            interpreted.1 && compiled.1,
            "{name}: one run ended and the other went on (interpreted ended: {})",
            interpreted.1
        );
        assert_same(name, &interpreted.0, &compiled.0);
        return;
    }
    let head = |t: &str| t.lines().take(SPIN_LINES).collect::<Vec<_>>().join("\n");
    let (a, b) = (head(&interpreted.0), head(&compiled.0));
    assert_eq!(a.lines().count(), SPIN_LINES, "{name}: the run spins");
    assert_same(name, &a, &b);
}

/// The interpreter's run of `g` on its own script, bounded.
pub(crate) fn interpreted(g: &Generated, dir: &Path) -> (String, bool) {
    let script = dir.join(format!("{}.script", g.name));
    std::fs::write(&script, &g.script).unwrap();
    let trace = dir.join(format!("{}.interpreted.jsonl", g.name));
    let mut command = Command::new(env!("CARGO_BIN_EXE_proclaim"));
    command.args([
        "run",
        g.folder.to_str().unwrap(),
        "--virtual-clock",
        "--force",
        "--script",
        script.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
        "--for",
        &g.run_for,
    ]);
    bounded_run(command, &trace)
}

/// The seeds the suite compiles to C.
const SEEDS: std::ops::Range<u64> = 20..52;

/// Seeds whose interpreted trace once noted the impersonator's first answer late (its script's
/// reporter ran only when the round next waited), where the compiled program notes it at the
/// query.
const ANSWER_NOTED_LATE: [u64; 2] = [757, 1108];

/// The seeds of the Rust workspace (each is a crate of its one build).
const RUST_SEEDS: std::ops::Range<u64> = 20..32;

/// A seed's behaviour written out, and its run: the behaviour's own script for as long as the
/// verifier's rounds take.
pub(crate) struct Generated {
    pub name: String,
    pub folder: PathBuf,
    pub script: String,
    pub run_for: String,
}

fn generated(seed: u64) -> Generated {
    let generated = random_behaviour::generate(seed);
    let folder = scratch(&format!("verify-random{seed}"));
    generated.write(&folder);
    let total: std::time::Duration = generated.waits.iter().sum();
    Generated {
        name: format!("verify-random{seed}"),
        folder,
        script: generated.script,
        run_for: format!("{}ms", total.as_millis().max(1)),
    }
}

/// Compiles `g` to C into `out`: `Err` with the refusal.
fn compile(g: &Generated, out: &std::path::Path) -> Result<(), String> {
    let o = crate::proclaim(&[
        "compile",
        g.folder.to_str().unwrap(),
        "--target",
        "c",
        "-o",
        out.to_str().unwrap(),
    ]);
    if o.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&o.stderr).into_owned())
    }
}

/// The seeds of the Rust workspace, written out.
pub(crate) fn compiled_seeds() -> Vec<Generated> {
    RUST_SEEDS.map(generated).collect()
}

/// Compiles seed `seed` to C, runs it on its own script and holds its trace to the
/// interpreter's.
fn holds_to_the_interpreter(seed: u64) {
    let g = generated(seed);
    let dir = scratch(&format!("verify-random{seed}-c"));
    if let Err(refusal) = compile(&g, &dir) {
        panic!("seed {seed} is refused: {refusal}");
    }
    build(g.folder.to_str().unwrap(), &dir);
    let interpreted = interpreted(&g, &dir);
    let script = dir.join(format!("{}.script", g.name));
    let trace = dir.join(format!("{}.compiled.jsonl", g.name));
    let mut command = Command::new("sh");
    command.arg("-c").arg(format!(
        "exec ./behaviour {} < {} > {}",
        g.run_for,
        script.display(),
        trace.display()
    ));
    command.current_dir(&dir);
    let program = bounded_run(command, &trace);
    assert_same_bounded(&g.name, interpreted, program);
}

#[test]
fn the_verifiers_random_behaviours_compile_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    SEEDS
        .chain(ANSWER_NOTED_LATE)
        .for_each(holds_to_the_interpreter);
}

/// The same for a thousand seeds (`cargo nextest run --run-ignored only -E
/// 'test(/thousand/)'`).
#[test]
#[ignore = "a thousand random behaviours compiled by gcc: run before a release"]
fn a_thousand_of_the_verifiers_random_behaviours_compile_to_the_interpreters_trace() {
    if gcc_missing() {
        return;
    }
    (1000..2000).for_each(holds_to_the_interpreter);
}
