//! Writes one of the verifier's families of behaviours to a folder, for `proclaim verify` (and
//! SPIN) to be timed on: `cargo run -p proclaim-verify --example families -- DIR sensors 24`,
//! `… DIR press`, `… DIR minepump`, `… DIR odometer 4 12`.

#[path = "../tests/common/families.rs"]
mod families;
#[path = "../tests/common/odometer.rs"]
mod odometer;

use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize, default: usize| {
        args.get(i)
            .map_or(Some(default), |a| a.parse().ok())
            .filter(|&n| n > 0)
    };
    let (Some(dir), Some(family)) = (args.first(), args.get(1)) else {
        eprintln!("usage: families DIR sensors N | press | minepump | odometer N K");
        return ExitCode::from(2);
    };
    let dir = Path::new(dir);
    match (family.as_str(), number(2, 3), number(3, 10)) {
        ("sensors", Some(n), _) => families::write_sensors(dir, n),
        ("press", _, _) => families::write_press(dir),
        ("minepump", _, _) => families::write_minepump(dir),
        ("odometer", Some(n), Some(k)) => odometer::write_odometer(dir, n, k),
        _ => {
            eprintln!("unknown family or size `{}`", args[1..].join(" "));
            return ExitCode::from(2);
        }
    }
    ExitCode::SUCCESS
}
