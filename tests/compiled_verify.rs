//! The verification issue's random behaviours (`crates/verify/tests/common/random_behaviour.rs`,
//! used as is), compiled: each seed either compiles, its C program's trace the interpreter's
//! byte for byte on the behaviour's own script (its Rust program's in `compiled_rust.rs`'s one
//! workspace), or is refused at the file and line of a construct no compiled program has yet:
//! a whiteboard read of a name no machine binds with `extern` (an input, a global nobody
//! assigns, the posted type), a machine's `IsRunning` status, a label atom nothing answers (an
//! input the script never sets), a posting to a theory input of what is no truth word (README,
//! "Deploying a behaviour").

#[path = "../crates/verify/tests/common/random_behaviour.rs"]
#[allow(dead_code)]
mod random_behaviour;

use super::compiled::{assert_same, build, gcc_missing, scratch};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How many trace lines of a run that never ends are held equal. The verifier paces its rounds;
/// `proclaim run --virtual-clock` does not, so a label that stays true on a state's own loop
/// (`when e0 == 0 -> S0`, `e0` never posted) moves round after round at one instant, forever,
/// and both programs write events until stopped.
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

/// Holds two runs' traces equal: whole when both ended, else their first `SPIN_LINES` lines
/// (neither may end while the other spins).
pub(crate) fn assert_same_bounded(
    name: &str,
    interpreted: (String, bool),
    compiled: (String, bool),
) {
    if interpreted.1 && compiled.1 {
        assert_same(name, &interpreted.0, &compiled.0);
        return;
    }
    assert!(
        !interpreted.1 && !compiled.1,
        "{name}: one run ended and the other went on (interpreted ended: {})",
        interpreted.1
    );
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
        "--script",
        script.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
        "--for",
        &g.run_for,
    ]);
    bounded_run(command, &trace)
}

/// The seeds the suite compiles.
const SEEDS: std::ops::Range<u64> = 20..32;

/// Why a seed may be refused: what its refusal must say.
const NOT_YET: [&str; 4] = [
    "which is no variable: reading the whiteboard is not compiled yet",
    "which is no variable and which no theory of the behaviour answers",
    "a theory input posted as",
    "a computed posting to the theory input",
];

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

/// The seeds that compile, for the Rust workspace.
pub(crate) fn compiled_seeds() -> Vec<Generated> {
    SEEDS
        .filter_map(|seed| {
            let g = generated(seed);
            let out = scratch(&format!("verify-random{seed}-probe"));
            compile(&g, &out).ok().map(|_| g)
        })
        .collect()
}

#[test]
fn the_verifiers_random_behaviours_compile_to_the_interpreters_trace_or_are_refused_at_their_line()
{
    if gcc_missing() {
        return;
    }
    let mut compiled = 0;
    for seed in SEEDS {
        let g = generated(seed);
        let dir = scratch(&format!("verify-random{seed}-c"));
        match compile(&g, &dir) {
            Ok(()) => {
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
                compiled += 1;
            }
            Err(refusal) => {
                let line = refusal
                    .lines()
                    .find(|l| l.contains(": cannot be compiled: "))
                    .unwrap_or_else(|| panic!("seed {seed}: no refusal: {refusal}"));
                assert!(
                    line.contains(".machine:") && NOT_YET.iter().any(|why| line.contains(why)),
                    "seed {seed}: refused for a reason not known: {line}"
                );
            }
        }
    }
    assert!(compiled >= 1, "some seed compiles");
}
