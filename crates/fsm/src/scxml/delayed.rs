//! SCXML's way to time a state: `<send event="t" delay="2s"/>` on entering it and a transition
//! on `t`. Where that is all the event does, it means what a time test means, so the event
//! reads as `after_ms(2000)` and the send (and a `<cancel>` of it on leaving) as nothing. An
//! event whose delayed send does more is refused, saying why.

use super::tree::Element;
use std::collections::HashMap;

/// A delayed send that maps, by its event's name as written.
#[derive(Clone, Debug)]
pub(super) struct Timer {
    /// The time test its event reads as.
    pub label: String,
    /// The send's `id`, which a `<cancel sendid>` on leaving names.
    pub id: Option<String>,
}

/// What the document does with one event.
#[derive(Default)]
struct Uses<'e> {
    /// Its delayed sends, with the state whose entry sends it (if one does).
    delayed: Vec<(&'e Element, Option<&'e Element>)>,
    /// Its sends and raises that are not delayed.
    posted: usize,
    /// The transitions that wait on it, with the state they are on.
    transitions: Vec<(&'e Element, &'e Element)>,
}

/// The delayed sends of `root` that map, by event, and the refusals of those that do not
/// (line, reason).
pub(super) fn timers(root: &Element) -> (HashMap<String, Timer>, Vec<(usize, String)>) {
    let mut uses: HashMap<&str, Uses<'_>> = HashMap::new();
    gather(root, None, false, &mut uses);
    let mut timers = HashMap::new();
    let mut refusals = Vec::new();
    let mut events: Vec<&&str> = uses.keys().collect();
    events.sort();
    for event in events {
        let u = &uses[*event];
        let Some((send, owner)) = u.delayed.first() else {
            continue;
        };
        match timer(event, send, *owner, u) {
            Ok(t) => {
                timers.insert(event.to_string(), t);
            }
            Err(why) => refusals.push((
                send.line,
                format!("<send event=\"{event}\"> with a delay: {why}"),
            )),
        }
    }
    (timers, refusals)
}

fn timer(
    event: &str,
    send: &Element,
    owner: Option<&Element>,
    u: &Uses<'_>,
) -> Result<Timer, String> {
    let state = owner.ok_or("only a send on entering a state maps (it times that state)")?;
    if u.delayed.len() > 1 {
        return Err(format!(
            "`{event}` is sent with a delay {} times; only one send times a state",
            u.delayed.len()
        ));
    }
    if u.posted > 0 {
        return Err(format!("`{event}` is also sent or raised at once; only an event the delay alone sends reads as a time test"));
    }
    for (t, on) in &u.transitions {
        if !std::ptr::eq(*on, state) {
            let other = on.attribute("id").unwrap_or_default();
            return Err(format!(
                "`{other}` (line {}) waits on `{event}` too; only the state that sends it may",
                t.line
            ));
        }
        if t.attribute("cond").is_some() {
            return Err(format!("the transition on line {} has a `cond`: SCXML drops the event if it is false then, while a time test stays true", t.line));
        }
    }
    if let Some((unmapped, value)) = super::unmapped_send(send) {
        return Err(format!("{unmapped}=\"{value}\" does not map"));
    }
    if !send.children.is_empty() {
        return Err("parameters or content: an event carries no data here".into());
    }
    let delay = send.attribute("delay").unwrap_or_default();
    let ms = milliseconds(delay)
        .ok_or_else(|| format!("delay=\"{delay}\" is no duration (write `2s` or `500ms`, a whole number of milliseconds)"))?;
    // Whole seconds written as seconds read as `after(2)`, as the native writer writes it.
    let seconds = delay.trim().strip_suffix('s').filter(|n| !n.ends_with('m'));
    let label = match seconds.and_then(|n| n.trim().parse::<u64>().ok()) {
        Some(n) => format!("after({n})"),
        None => format!("after_ms({ms})"),
    };
    Ok(Timer {
        label,
        id: send.attribute("id").map(str::to_string),
    })
}

/// Walks `e`: `state` is the innermost state around it, `entering` whether it is in that
/// state's `<onentry>`.
fn gather<'e>(
    e: &'e Element,
    state: Option<&'e Element>,
    entering: bool,
    uses: &mut HashMap<&'e str, Uses<'e>>,
) {
    match e.name.as_str() {
        "send" | "raise" => {
            if let Some(event) = e.attribute("event") {
                let u = uses.entry(event).or_default();
                if e.name == "send" && e.attribute("delay").is_some() {
                    u.delayed.push((e, state.filter(|_| entering)));
                } else {
                    u.posted += 1;
                }
            }
        }
        "transition" => {
            if let (Some(events), Some(on)) = (e.attribute("event"), state) {
                for event in events.split_whitespace() {
                    uses.entry(event).or_default().transitions.push((e, on));
                }
            }
        }
        _ => {}
    }
    let (state, entering) = match e.name.as_str() {
        "state" | "final" | "parallel" => (Some(e), false),
        "onentry" => (state, true),
        "onexit" | "transition" => (state, false),
        _ => (state, entering),
    };
    for child in &e.children {
        gather(child, state, entering, uses);
    }
}

/// A CSS2 duration as SCXML writes a delay (`2s`, `1.5s`, `500ms`), in whole milliseconds.
fn milliseconds(text: &str) -> Option<u64> {
    let text = text.trim();
    let (number, scale) = match text.strip_suffix("ms") {
        Some(n) => (n, 1.0),
        None => (text.strip_suffix('s')?, 1000.0),
    };
    let value: f64 = number.trim().parse().ok()?;
    let ms = value * scale;
    (ms.is_finite() && ms >= 0.0 && ms.fract() == 0.0 && ms <= u32::MAX as f64).then_some(ms as u64)
}
