//! Fuzz target: any bytes through a behaviour's manifest (`behaviour.toml`) and its liveness
//! formulas must not panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = proclaim_behaviour::parse_manifest("behaviour.toml", &text);
    let _ = proclaim_behaviour::parse_liveness("gaia.txt", &text);
});
