//! Fuzz target: any bytes as a whiteboard value on the wire (JSON, as recordings, traces and the
//! Zenoh board carry it) and as a value or pattern typed by a person must not panic, and a value
//! read from JSON must write JSON that reads back to the same value.
#![no_main]

use libfuzzer_sys::fuzz_target;
use proclaim_board::{Pattern, Value};

fuzz_target!(|data: &[u8]| {
    if let Ok(json) = serde_json::from_slice::<serde_json::Value>(data) {
        let value = Value::from_json(&json);
        let again = Value::from_json(&value.to_json());
        assert_eq!(format!("{value:?}"), format!("{again:?}"));
    }
    let text = String::from_utf8_lossy(data);
    let _ = Value::parse(&text);
    let _ = Pattern::parse(&text);
});
