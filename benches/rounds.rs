//! What a round of the interpreter costs on the virtual clock, as `proclaim run
//! --virtual-clock` runs it: one machine that asks a theory and posts in every ringlet and moves
//! on a 100 ms timeout (`benches/rounds/`), for ten minutes of virtual time, five times; the
//! median microseconds a round. The compiled program's figure for the same behaviour is in
//! README's speed section. Figures, never asserts: `cargo bench --bench rounds`.

use proclaim_behaviour::testing::RoundByRound;
use std::time::{Duration, Instant};

/// Virtual time a sample runs for.
const VIRTUAL: Duration = Duration::from_secs(600);

fn main() {
    let folder = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/rounds");
    let mut per_round = Vec::new();
    let mut rounds = 0;
    for _ in 0..5 {
        let mut run = RoundByRound::start(folder, "").expect("the bench's behaviour loads");
        let started = Instant::now();
        run.run_for(VIRTUAL);
        let took = started.elapsed();
        rounds = run.rounds();
        per_round.push(took.as_secs_f64() * 1e6 / rounds.max(1) as f64);
    }
    per_round.sort_by(f64::total_cmp);
    println!(
        "interpreter, one machine asking a theory and posting every ringlet: {rounds} rounds in {} s of virtual time, median {:.2} µs a round (min {:.2}, max {:.2})",
        VIRTUAL.as_secs(),
        per_round[per_round.len() / 2],
        per_round[0],
        per_round[per_round.len() - 1]
    );
}
