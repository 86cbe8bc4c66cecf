//! What the whiteboard benchmarks share: the microwave theory's expert on a board, and label
//! round trips through it.

use proclaim_board::{QueryOutcome, Whiteboard};
use proclaim_experts::ReasonerExpert;
use std::time::{Duration, Instant};

/// The runtime every whiteboard bench runs on: two workers, as many as the machine has cores.
pub fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .expect("a tokio runtime")
}

/// Whether the bench was started as a smoke check (`cargo test --benches`, `cargo bench
/// --no-run` runs), which wants short runs.
pub fn quick() -> bool {
    std::env::args().any(|a| a == "--test")
}

pub fn microwave() -> proclaim_cdl::Theory {
    let text = include_str!("../../theories/microwave.dl");
    proclaim_cdl::load(text, proclaim_cdl::Language::Dl).expect("the microwave theory loads")
}

/// A board with the microwave theory's expert on it, registered, and `timeLeft` set.
pub async fn oven() -> Whiteboard {
    let board = Whiteboard::local();
    tokio::spawn(ReasonerExpert::new("oven", microwave(), &Default::default()).run(board.clone()));
    while board.registry().answerers("cook").is_empty() {
        tokio::task::yield_now().await;
    }
    board.post("sensors", "timeLeft", true);
    board
}

/// `samples` queries of `cook`, each timed from the query to its answer; an input change now
/// and then, so answers are re-proved, not only cached.
pub async fn round_trips(board: &Whiteboard, samples: usize) -> Vec<Duration> {
    let mut out = Vec::with_capacity(samples);
    for i in 0..samples {
        if i % 100 == 0 {
            board.post("sensors", "doorOpen", i % 200 == 0);
        }
        let start = Instant::now();
        let answer = board.query("machine", "cook", Duration::from_secs(1)).await;
        out.push(start.elapsed());
        assert!(matches!(answer, QueryOutcome::Answered { .. }));
    }
    out
}
