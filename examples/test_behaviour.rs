//! Testing a behaviour from Rust: the behaviour's folder and an impersonator script in, the
//! states each machine went through out, on a virtual clock. `cargo run --example
//! test_behaviour` prints the run; `cargo test --example test_behaviour` (and the project's test
//! command) runs the test below, which is the whole template: a plain `#[test]`, one call.

use proclaim_behaviour::testing::run_scripted;
use std::time::Duration;

/// The kitchen: the door opens for two seconds, then someone presses the one-minute button.
const KITCHEN: &str = "
    doorOpen = false
    timeLeft = false
    at 1s doorOpen = true
    at 3s doorOpen = false
    at 4s timeLeft = true
";

fn microwave() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("machines/microwave")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let run = run_scripted(microwave(), KITCHEN, Duration::from_secs(120))?;
    for line in &run.trace {
        println!("{line}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_microwave_cooks_for_a_minute_once_the_door_is_shut(
    ) -> Result<(), Box<dyn std::error::Error>> {
        let run = run_scripted(microwave(), KITCHEN, Duration::from_secs(120))?;
        assert_eq!(
            run.states_of("Microwave"),
            ["IDLE", "OPEN", "IDLE", "COOKING", "DONE"]
        );
        let done = run.visits.last().expect("a visit");
        assert_eq!(
            done.at,
            Duration::from_secs(64),
            "a minute after the button"
        );
        assert!(run.finished);
        Ok(())
    }
}
