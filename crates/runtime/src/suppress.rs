//! Subsumption on the whiteboard (Brooks' suppression): for a type declared suppressed with a
//! hold time, a posting of a higher priority holds the type for that long, and lower-priority
//! postings meanwhile are suppressed (never seen by readers). When the hold runs out, the newest
//! lower-priority posting takes over. Pure: the caller gives the time (the schedule's moment, so
//! a replay decides as the run did) and posts what this allows. Generic over the posting's value,
//! which it only keeps: the whiteboard's values on the interpreter, text in a compiled behaviour.

use rustc_hash::FxHashMap;
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Duration;

/// A posting as the suppressor keeps it: who, what, at which priority, when (since the
/// caller's epoch).
#[derive(Clone, Debug, PartialEq)]
pub struct Ranked<V> {
    pub module: Arc<str>,
    pub ty: Arc<str>,
    pub value: V,
    pub priority: u32,
    pub at: Duration,
}

/// What becomes of an offered posting.
#[derive(Clone, Debug, PartialEq)]
pub enum Visibility {
    /// Post it: the type is not suppressed, or nothing higher holds it.
    Shown,
    /// Do not post it: `by`'s posting at `priority` holds the type until `until`.
    Suppressed {
        by: Arc<str>,
        priority: u32,
        until: Duration,
    },
}

/// One suppressed type: its hold, the posting readers see, and the newest posting of each
/// priority (seen or suppressed), from which a lower one takes over.
#[derive(Debug)]
struct Line<V> {
    ty: Arc<str>,
    hold: Duration,
    shown: Option<Ranked<V>>,
    newest: BTreeMap<u32, Ranked<V>>,
    /// Whether the shown posting stands over some lower-priority posting, which takes over
    /// when its hold runs out.
    subsuming: bool,
}

impl<V: Clone> Line<V> {
    fn live(&self, posting: &Ranked<V>, now: Duration) -> bool {
        now < posting.at + self.hold
    }

    /// Whether some posting of a priority below `priority` is known.
    fn below(&self, priority: u32) -> bool {
        self.newest.range(..priority).next().is_some()
    }

    /// The posting that takes over once the shown one's hold has run out: of those below its
    /// priority, the highest whose own hold is still running (it would have held the type,
    /// had nothing been above it), else the newest (a lower layer goes on from where it was,
    /// even if it posted before it was subsumed).
    fn successor(&self, now: Duration) -> Option<Ranked<V>> {
        let shown = self.shown.as_ref()?;
        if !self.subsuming || self.live(shown, now) {
            return None;
        }
        let lower = || self.newest.range(..shown.priority).map(|(_, r)| r);
        lower()
            .filter(|r| self.live(r, now))
            .max_by_key(|r| r.priority)
            .or_else(|| lower().max_by_key(|r| r.at))
            .cloned()
    }
}

/// One suppressed type's holding as it stands (what a checkpoint keeps): the posting readers
/// see, the newest posting of each priority, and whether the one shown stands over a lower one.
#[derive(Clone, Debug, PartialEq)]
pub struct Holding<V> {
    pub ty: Arc<str>,
    pub shown: Option<Ranked<V>>,
    pub newest: Vec<Ranked<V>>,
    pub subsuming: bool,
}

/// The suppressed types of one behaviour and what holds each.
#[derive(Debug)]
pub struct Suppressor<V> {
    lines: FxHashMap<Arc<str>, Line<V>>,
}

impl<V> Default for Suppressor<V> {
    fn default() -> Self {
        Suppressor {
            lines: FxHashMap::default(),
        }
    }
}

impl<V: Clone> Suppressor<V> {
    /// The types declared suppressed, each with its hold time.
    pub fn new<'a>(holds: impl IntoIterator<Item = (&'a str, Duration)>) -> Suppressor<V> {
        Suppressor {
            lines: holds
                .into_iter()
                .map(|(ty, hold)| {
                    let ty: Arc<str> = Arc::from(ty);
                    let line = Line {
                        ty: ty.clone(),
                        hold,
                        shown: None,
                        newest: BTreeMap::new(),
                        subsuming: false,
                    };
                    (ty, line)
                })
                .collect(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    /// The hold time of a suppressed type; `None` for a type that is not.
    pub fn hold(&self, ty: &str) -> Option<Duration> {
        self.lines.get(ty).map(|l| l.hold)
    }

    /// Judges a posting at `now`: a lower priority than the posting that holds the type is
    /// suppressed (and remembered, to take over later); anything else is shown and, for a
    /// suppressed type, holds it from now. A type not declared is always shown.
    pub fn offer(
        &mut self,
        module: &str,
        ty: &str,
        value: &V,
        priority: u32,
        now: Duration,
    ) -> Visibility {
        let Some(line) = self.lines.get_mut(ty) else {
            return Visibility::Shown;
        };
        let ranked = Ranked {
            module: Arc::from(module),
            ty: line.ty.clone(),
            value: value.clone(),
            priority,
            at: now,
        };
        line.newest.insert(priority, ranked.clone());
        if let Some(holder) = line
            .shown
            .as_ref()
            .filter(|h| priority < h.priority && line.live(h, now))
        {
            let verdict = Visibility::Suppressed {
                by: holder.module.clone(),
                priority: holder.priority,
                until: holder.at + line.hold,
            };
            line.subsuming = true;
            return verdict;
        }
        line.subsuming = line.below(priority);
        line.shown = Some(ranked);
        Visibility::Shown
    }

    /// The postings that take over at `now`, each to be posted: for every type whose hold ran
    /// out with a lower-priority posting behind it, that posting (`Line::successor`), which
    /// holds in turn for what is left of its own hold, counted from when it was posted. Types
    /// in name order, so the same run posts them in the same order.
    pub fn release(&mut self, now: Duration) -> Vec<Ranked<V>> {
        let mut released = Vec::new();
        for line in self.lines.values_mut() {
            if let Some(successor) = line.successor(now) {
                line.subsuming = line.live(&successor, now) && line.below(successor.priority);
                line.shown = Some(successor.clone());
                released.push(successor);
            }
        }
        released.sort_by(|a, b| a.ty.cmp(&b.ty));
        released
    }

    /// Every suppressed type's holding, in name order.
    pub fn holdings(&self) -> Vec<Holding<V>> {
        let mut all: Vec<Holding<V>> = self
            .lines
            .values()
            .map(|line| Holding {
                ty: line.ty.clone(),
                shown: line.shown.clone(),
                newest: line.newest.values().cloned().collect(),
                subsuming: line.subsuming,
            })
            .collect();
        all.sort_by(|a, b| a.ty.cmp(&b.ty));
        all
    }

    /// Holds each type as `holdings` say (a run taken up from a checkpoint); a type no longer
    /// declared suppressed is left out, and its hold time is the one declared now.
    pub fn hold_as(&mut self, holdings: Vec<Holding<V>>) {
        for holding in holdings {
            if let Some(line) = self.lines.get_mut(&holding.ty) {
                line.shown = holding.shown;
                line.newest = holding
                    .newest
                    .into_iter()
                    .map(|r| (r.priority, r))
                    .collect();
                line.subsuming = holding.subsuming;
            }
        }
    }

    /// The earliest moment some type's hold runs out with a lower posting waiting behind it
    /// (when the schedule must look again even if nothing else happens).
    pub fn next_release(&self) -> Option<Duration> {
        self.lines
            .values()
            .filter(|line| line.subsuming)
            .filter_map(|line| Some(line.shown.as_ref()?.at + line.hold))
            .min()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    /// Steps of one run on `walk` (hold 500 ms): (time ms, poster, priority, value) offered,
    /// or a release at a time; and what each gives.
    enum Step {
        Offer(u64, &'static str, u32, &'static str, Option<&'static str>),
        Release(u64, &'static [&'static str]),
    }
    use Step::*;

    fn play(steps: &[Step]) {
        let mut s = Suppressor::new([("walk", ms(500))]);
        for (i, step) in steps.iter().enumerate() {
            match step {
                Offer(at, who, priority, value, suppressed_by) => {
                    let verdict = s.offer(who, "walk", value, *priority, ms(*at));
                    let by = match &verdict {
                        Visibility::Shown => None,
                        Visibility::Suppressed { by, .. } => Some(by.to_string()),
                    };
                    assert_eq!(by.as_deref(), *suppressed_by, "step {i}: {verdict:?}");
                }
                Release(at, expected) => {
                    let got: Vec<String> = s
                        .release(ms(*at))
                        .iter()
                        .map(|r| format!("{}={}", r.module, r.value))
                        .collect();
                    assert_eq!(got, *expected, "step {i}");
                }
            }
        }
    }

    #[test]
    fn a_reflex_subsumes_a_walk_for_its_hold() {
        play(&[
            Offer(0, "Walk", 0, "forward", None),
            Offer(100, "Reflex", 2, "stop", None),
            Offer(200, "Walk", 0, "left", Some("Reflex")),
            Release(599, &[]),
            // The newest lower posting takes over when the hold runs out.
            Release(600, &["Walk=left"]),
            Release(700, &[]),
            Offer(800, "Walk", 0, "forward", None),
        ]);
    }

    #[test]
    fn a_lower_layer_that_posted_before_goes_on_after_the_hold() {
        play(&[
            Offer(0, "Walk", 0, "forward", None),
            Offer(100, "Reflex", 2, "stop", None),
            Release(600, &["Walk=forward"]),
        ]);
    }

    #[test]
    fn the_higher_layer_refreshes_its_hold_by_posting_again() {
        play(&[
            Offer(0, "Reflex", 2, "stop", None),
            Offer(300, "Walk", 0, "forward", Some("Reflex")),
            Offer(400, "Reflex", 2, "back", None),
            Release(600, &[]),
            Offer(850, "Walk", 0, "left", Some("Reflex")),
            Release(900, &["Walk=left"]),
        ]);
    }

    #[test]
    fn equal_and_higher_priorities_are_never_suppressed() {
        play(&[
            Offer(0, "Walk", 1, "forward", None),
            Offer(10, "Other", 1, "left", None),
            Offer(20, "Reflex", 2, "stop", None),
            Offer(30, "Walk", 1, "forward", Some("Reflex")),
            Offer(40, "Panic", 3, "fall", None),
        ]);
    }

    #[test]
    fn a_taken_over_posting_holds_from_when_it_was_posted() {
        // Avoid (2) holds; Follow (1), posted during it and still within its own hold when
        // Avoid's runs out, takes over and holds Wander off until its own hold runs out.
        play(&[
            Offer(0, "Avoid", 2, "stop", None),
            Offer(10, "Follow", 1, "ball", Some("Avoid")),
            Offer(20, "Wander", 0, "left", Some("Avoid")),
            Release(500, &["Follow=ball"]),
            Offer(505, "Wander", 0, "right", Some("Follow")),
            Release(510, &["Wander=right"]),
            Release(2000, &[]),
        ]);
    }

    #[test]
    fn with_every_hold_out_the_newest_lower_posting_takes_over() {
        play(&[
            Offer(0, "Avoid", 2, "stop", None),
            Offer(10, "Follow", 1, "ball", Some("Avoid")),
            Offer(20, "Wander", 0, "left", Some("Avoid")),
            Release(1000, &["Wander=left"]),
            Release(2000, &[]),
        ]);
    }

    #[test]
    fn a_type_not_declared_is_always_shown_and_never_released() {
        let mut s = Suppressor::new([("walk", ms(500))]);
        assert_eq!(s.offer("Reflex", "say", &1, 9, ms(0)), Visibility::Shown);
        assert_eq!(s.offer("Walk", "say", &2, 0, ms(1)), Visibility::Shown);
        assert!(s.release(ms(10_000)).is_empty());
        assert_eq!(s.next_release(), None);
        assert_eq!(s.hold("walk"), Some(ms(500)));
        assert_eq!(s.hold("say"), None);
    }

    #[test]
    fn the_next_release_is_when_a_hold_with_something_behind_it_runs_out() {
        let mut s = Suppressor::new([("walk", ms(500))]);
        s.offer("Reflex", "walk", &1, 2, ms(100));
        assert_eq!(s.next_release(), None, "nothing lower waits");
        s.offer("Walk", "walk", &0, 0, ms(200));
        assert_eq!(s.next_release(), Some(ms(600)));
        s.release(ms(600));
        assert_eq!(s.next_release(), None);
    }
}
