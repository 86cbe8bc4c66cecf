//! The compiled runtime on a behaviour written by hand as the Rust printer writes one (its
//! tables and its machine's functions over `calls`): a door that opens when told or after 5 s,
//! run by the schedule a host runs (`CompiledBehaviour`).

use proclaim_runtime::calls::*;
use proclaim_runtime::host::CompiledBehaviour;
use proclaim_runtime::world::{Scalar, World};
use proclaim_runtime::{Event, Tables};
use std::cell::RefCell;
use std::rc::Rc;

struct Door;

impl Tables for Door {
    const MACHINE_NAME: &'static [&'static str] = &["Door"];
    const INITIAL: &'static [i64] = &[1];
    const STARTS: &'static [bool] = &[true];
    const PRIORITY: &'static [u32] = &[0];
    const STATUS_BOARD: &'static [Option<usize>] = &[None];
    const OUTPUT_NAME: &'static [&'static str] = &["open"];
    const OUTPUT_EXPERT: &'static [&'static str] = &["impersonator"];
    const THEORY_OUTPUTS: usize = 0;
    const OUTPUT_BOARD: &'static [Option<usize>] = &[None];
    const EXTERN_NAME: &'static [&'static str] = &["ballRR"];
    const EXTERN_BOUND: &'static [bool] = &[true];
    const SUPPRESSED: &'static [(&'static str, u64)] = &[];
    const SENSORS: &'static [(&'static str, &'static [&'static str])] = &[];
    const SCRIPT: Option<(&'static str, &'static str)> = None;
    const INPUTS: usize = 2;
    const PERIOD_MS: u64 = 100;
    const COMMANDS: usize = 1;
    const ANSWER_TIMEOUT_MS: u64 = 100;
    const RANGES: &'static [(&'static str, i64, i64)] = &[("ballRR", -50, 50)];

    fn var_inits() -> Vec<Scalar> {
        Vec::new()
    }
    fn answer(w: &World, _k: usize) -> bool {
        // The atom from outside: known, then true.
        w.input[1]
    }
    fn apply_input(w: &mut World, ty: &str, content: &str) -> bool {
        if same(ty, "open") {
            set_input(w, 0, content);
            return true;
        }
        false
    }
    fn ring_machines(w: &mut World) -> bool {
        obey::<Door>(w);
        ringlet_due::<Door>(w, 0) && ring_door(w)
    }
    fn final_state(w: &World, _m: usize) -> bool {
        w.state[0] == 2
    }
    fn due_of(w: &World, m: usize, due: u64) -> u64 {
        if w.state[m] == 1 {
            due_after(w, m, 5000, due)
        } else {
            due
        }
    }
    fn reads(w: &World, _m: usize, k: usize) -> bool {
        w.state[0] == 1 && k == 0
    }
    fn reads_globals(_w: &World, _m: usize) -> bool {
        false
    }
    fn reads_extern(_w: &World, _m: usize, _e: usize) -> bool {
        false
    }
}

/// Shut, it opens on `open || timeout(5s)`, posting the light on; Open is final.
fn ring_door(w: &mut World) -> bool {
    if begin_ringlet::<Door>(w, 0) {
        let (id, name) = (w.state[0], ["Shut", "Open"][w.state[0] as usize - 1]);
        w.entered("Door", name, id);
        if id == 2 {
            report_finished::<Door>(w, 0, "Open");
        }
    }
    take_snapshot::<Door>(w, 0);
    if w.state[0] == 1
        && proved::<Door>(w, 0, |w| {
            ask::<Door>(w, 0, 0) || elapsed_at_least(w, 0, 5000)
        })
    {
        w.fired("Door", 1, 2, "open || timeout(5s)");
        post::<Door>(w, 0, "Light", "on");
        w.state[0] = 2;
        w.just_entered[0] = true;
        return true;
    }
    false
}

/// The door's world, and the events it reports as the trace's JSON names them, with a
/// star for each that [`Event::is_change`] calls a change.
fn door() -> (World, Rc<RefCell<Vec<String>>>) {
    let events = Rc::new(RefCell::new(Vec::new()));
    let kept = events.clone();
    let sink = Box::new(move |e: Event| {
        let json = serde_json::to_value(&e).unwrap();
        let name = json["event"].as_str().unwrap();
        let star = if e.is_change() { "*" } else { "" };
        kept.borrow_mut().push(format!("{name}{star}"));
    });
    (Door::init(Some(sink)), events)
}

#[test]
fn the_door_opens_when_told_as_the_schedule_rings_it() {
    let (mut w, events) = door();
    assert!(Door::supply(&mut w, "open") && !Door::supply(&mut w, "shut"));
    assert!(!Door::round(&mut w, |_| {}), "nothing told yet");
    assert_eq!(*events.borrow(), ["entered*", "answered"]);
    assert!(!Door::news(&w));
    assert!(
        Door::outside(&mut w, "impersonator", "open", "true"),
        "news to the label"
    );
    assert!(Door::round(&mut w, |_| {}));
    assert!(!Door::finished(&w), "Open's OnEntry has not run");
    assert!(!Door::round(&mut w, |_| {}));
    assert!(Door::finished(&w));
    let tail: Vec<String> = events.borrow()[2..].to_vec();
    assert_eq!(
        tail,
        ["answered", "fired*", "posted*", "entered*", "finished*"]
    );
    // The world counts the changes the events say they are.
    let starred = events.borrow().iter().filter(|e| e.ends_with('*')).count();
    assert_eq!(w.changes, starred as u64);
}

#[test]
fn a_timeout_comes_due_from_the_states_entry_and_only_a_change_is_counted() {
    let (mut w, _) = door();
    Door::round(&mut w, |_| {});
    assert_eq!(Door::next_test_ms(&w), Some(5000));
    assert_eq!(Door::next_due_ms(&w), Some(100), "the period comes first");
    w.now_ms = 4900;
    let changes = w.changes;
    assert!(!Door::round(&mut w, |_| {}));
    assert_eq!(
        w.changes, changes,
        "a round of answers read changes nothing"
    );
    assert_eq!(Door::next_test_ms(&w), Some(100));
    w.now_ms = 5000;
    assert!(Door::round(&mut w, |_| {}), "the timeout fires");
    assert!(w.changes > changes);
    Door::round(&mut w, |_| {});
    assert_eq!(
        Door::next_test_ms(&w),
        None,
        "a final state waits on no clock"
    );
    assert_eq!(Door::next_due_ms(&w), Some(100));
}

/// A value from outside is a truth or a whole number, as the runner reads a posting's; what a
/// compiled behaviour cannot hold (text, a fraction) is said and changes nothing, and a value
/// beyond the declared range is said once per value, in the runner's words.
#[test]
fn numbers_from_outside_are_held_and_what_cannot_be_is_said() {
    let warned = Rc::new(RefCell::new(Vec::new()));
    let kept = warned.clone();
    let sink = Box::new(move |e: Event| {
        if let Event::Warned {
            machine, message, ..
        } = e
        {
            kept.borrow_mut().push(format!("{machine}: {message}"));
        }
    });
    let mut w = Door::init(Some(sink));
    Door::outside(&mut w, "sensor", "ballRR", "-12");
    assert_eq!(w.ext[0].map(|v| (v.i, v.is_bool)), Some((-12, false)));
    Door::outside(&mut w, "sensor", "ballRR", "true");
    assert_eq!(w.ext[0].map(|v| (v.i, v.is_bool)), Some((1, true)));
    assert!(warned.borrow().is_empty(), "{:?}", warned.borrow());
    for text in ["left", "1.5", "99999999999999999999"] {
        assert!(!Door::outside(&mut w, "sensor", "ballRR", text));
        assert_eq!(w.ext[0].map(|v| v.i), Some(1), "{text} changes nothing");
    }
    Door::outside(&mut w, "sensor", "ballRR", "80");
    Door::outside(&mut w, "sensor", "ballRR", "80");
    Door::outside(&mut w, "sensor", "ballRR", "-80");
    assert_eq!(w.ext[0].map(|v| v.i), Some(-80), "the value is still read");
    let warned = warned.borrow();
    assert_eq!(warned.len(), 8, "{warned:?}");
    assert!(
        warned[1]
            .starts_with("sensor: posted ballRR = left, which a compiled behaviour cannot hold"),
        "{warned:?}"
    );
    assert!(warned[6] == "sensor: posted ballRR = 80, outside its declared range -50..50 (the manifest's [ranges]): what `verify` proved assumed it", "{warned:?}");
    assert!(
        warned[7].contains("posted ballRR = -80, outside"),
        "{warned:?}"
    );
}
