//! Which labels are answered from outside the behaviour's own modules (a person at the
//! terminal, the script's impersonator, the embedding program's experts), decided before any
//! module starts. A reasoner or a program expert gives up exactly those labels and keeps
//! answering the rest; a sensor wrapper any of whose labels is taken is left out whole, before
//! it opens a socket, since whoever takes its labels stands in for the device.

use rustc_hash::FxHashMap;

/// Label → who answers it instead (the reason, as a note says it).
#[derive(Default)]
pub(crate) struct Replaced {
    by: FxHashMap<String, &'static str>,
}

impl Replaced {
    /// `labels` are answered by someone else: `why` says who (a later call takes a label from
    /// an earlier one).
    pub(crate) fn take(&mut self, labels: Vec<String>, why: &'static str) {
        for label in labels {
            self.by.insert(label, why);
        }
    }

    /// `answers` without the labels answered from outside, noting what `module` gave up (or
    /// that it is left out, when it gave up every label it had).
    pub(crate) fn narrow(
        &self,
        module: &str,
        answers: &[String],
        notes: &mut Vec<String>,
    ) -> Vec<String> {
        let (taken, kept): (Vec<&String>, Vec<&String>) =
            answers.iter().partition(|a| self.by.contains_key(*a));
        if !taken.is_empty() {
            let whom = self.whom(&taken);
            notes.push(if kept.is_empty() {
                format!("left out {module}: {whom}")
            } else {
                format!("{module} answers the rest of its labels: {whom}")
            });
        }
        kept.into_iter().cloned().collect()
    }

    /// Whether a sensor wrapper answering `answers` is left out (a note says why).
    pub(crate) fn leaves_out(
        &self,
        module: &str,
        answers: &[String],
        notes: &mut Vec<String>,
    ) -> bool {
        let taken: Vec<&String> = answers
            .iter()
            .filter(|a| self.by.contains_key(*a))
            .collect();
        if taken.is_empty() {
            return false;
        }
        notes.push(format!("left out {module}: {}", self.whom(&taken)));
        true
    }

    /// Who answers `taken` instead: `the script impersonates a, b; the embedding program
    /// answers c`, in the order the labels come.
    fn whom(&self, taken: &[&String]) -> String {
        let mut groups: Vec<(&'static str, Vec<&str>)> = Vec::new();
        for label in taken {
            let why = self.by[label.as_str()];
            match groups.iter_mut().find(|(w, _)| *w == why) {
                Some((_, labels)) => labels.push(label),
                None => groups.push((why, vec![label.as_str()])),
            }
        }
        let said: Vec<String> = groups
            .into_iter()
            .map(|(why, labels)| format!("{why} {}", labels.join(", ")))
            .collect();
        said.join("; ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn replaced(pairs: &[(&str, &'static str)]) -> Replaced {
        Replaced {
            by: pairs.iter().map(|(l, w)| (l.to_string(), *w)).collect(),
        }
    }

    fn labels(names: &[&str]) -> Vec<String> {
        names.iter().map(|n| n.to_string()).collect()
    }

    #[test]
    fn a_module_gives_up_exactly_the_labels_taken_and_says_so() {
        let r = replaced(&[
            ("comeOut", "the embedding program answers"),
            ("dive", "the script impersonates"),
        ]);
        let mut notes = Vec::new();
        let kept = r.narrow(
            "goalie",
            &labels(&["stay", "comeOut", "dive", "block"]),
            &mut notes,
        );
        assert_eq!(kept, labels(&["stay", "block"]));
        assert_eq!(
            notes,
            ["goalie answers the rest of its labels: the embedding program answers comeOut; the script impersonates dive"]
        );
        let kept = r.narrow("diver", &labels(&["dive"]), &mut notes);
        assert!(kept.is_empty());
        assert_eq!(notes[1], "left out diver: the script impersonates dive");
        assert_eq!(
            r.narrow("other", &labels(&["x"]), &mut notes),
            labels(&["x"])
        );
        assert_eq!(
            notes.len(),
            2,
            "a module that gives up nothing says nothing"
        );
    }

    #[test]
    fn a_sensor_any_of_whose_labels_is_taken_is_left_out_whole() {
        let r = replaced(&[("playing", "the script impersonates")]);
        let mut notes = Vec::new();
        assert!(r.leaves_out("gamecontroller", &labels(&["ready", "playing"]), &mut notes));
        assert!(!r.leaves_out("button", &labels(&["pressed"]), &mut notes));
        assert_eq!(
            notes,
            ["left out gamecontroller: the script impersonates playing"]
        );
    }
}
