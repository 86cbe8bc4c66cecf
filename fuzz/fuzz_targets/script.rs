//! Fuzz target: any bytes through the line-based readers (an impersonator's script, durations,
//! a GameController game script, an expert's atom mapping) must not panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = proclaim_runtime::parse_script(&text);
    let _ = proclaim_runtime::parse_duration(&text);
    let _ = proclaim_gcsim::parse_game(&text);
    let _ = proclaim_experts::parse_mapping(&text);
});
