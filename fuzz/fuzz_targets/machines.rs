//! Fuzz target: any bytes through the machine readers (native `.machine`, Qfsm XML, SCXML, T/A
//! pairs, labels, activity code) and the SCXML writer must not panic, and a flat machine read
//! cleanly from native text must write back to text that reads again without errors (a machine
//! that nests states is written as written, by its own file or `to_scxml`, not by
//! `to_native`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(label) = proclaim_fsm::parse_label(&text) {
        assert_eq!(proclaim_fsm::parse_label(&label.to_string()), Ok(label));
    }
    let _ = proclaim_fsm::code::parse_statements(&text);
    let read = proclaim_fsm::parse_machine("f.machine", &text);
    // A machine read with errors may hold what was refused (kept so nothing is lost).
    let clean = read.diagnostics.iter().all(|d| !d.is_error());
    for machine in read.machines.into_iter().filter(|_| clean) {
        if !machine.composites.is_empty() {
            continue;
        }
        let again = proclaim_fsm::parse_machine("f.machine", &proclaim_fsm::to_native(&machine));
        // A warning the machine had it has again (an outcome no state announces); no error.
        assert!(
            again.diagnostics.iter().all(|d| !d.is_error()),
            "{:?}",
            again.diagnostics
        );
    }
    let _ = proclaim_fsm::import_qfsm("f.fsm", &text, "f");
    let _ = proclaim_fsm::import_scxml("f.scxml", &text, "f");
    if let Ok(scxml) = proclaim_fsm::to_scxml("f.machine", &text) {
        let _ = proclaim_fsm::import_scxml("f.scxml", &scxml, "f");
    }
    // Split anywhere so the transitions file and the activities file both vary.
    let cut = text.char_indices().map(|(i, _)| i).nth(text.chars().count() / 2).unwrap_or(0);
    let _ = proclaim_fsm::import_ta("f", "T", &text[..cut], "A", &text[cut..]);
});
