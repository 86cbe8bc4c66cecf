//! Liveness formulas written as a skeleton behaviour of statecharts, as the Kouretes tool
//! draws them: an activity that has a formula of its own is a state holding that formula's
//! states (left by `when done` once its last one is reached), a basic activity a state calling
//! the host function of its name, and each branch of a `||` a sub-machine announcing the
//! outcome `finished`, started together and waited for together. The choices the formulas
//! leave open are labels nobody answers yet (`choosePlay`, `SitDownAndStareDone`,
//! `againPlay`), which `proclaim check` lists.

use crate::liveness::{Definition, GaiaFormula};
use proclaim_fsm::{BinOp, FileDiagnostic, Label};
use std::fmt::Write;

/// The outcome a branch of a `||` announces when it has run its formula.
pub const FINISHED: &str = "finished";

/// One machine of the skeleton, as the text of its native file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skeleton {
    pub name: String,
    pub text: String,
    /// Whether it starts with the behaviour (the first formula's machine) or is a branch of a
    /// `||`, started by the state that runs it.
    pub start: bool,
}

/// A state of the chart being drawn up: inside `parent` (`None`: at the top).
struct Node {
    name: String,
    parent: Option<usize>,
    entry: Vec<String>,
    whens: Vec<(Label, usize)>,
    /// The state it holds that is entered first, for a state holding states.
    initial: Option<usize>,
    outcome: Option<&'static str>,
}

/// A machine being drawn up: its states, and where new ones go.
struct Draft {
    name: String,
    /// The outcomes it announces (a branch of a `||`: `finished`).
    outcomes: Vec<&'static str>,
    nodes: Vec<Node>,
    counters: Vec<(String, usize)>,
    into: Option<usize>,
}

impl Draft {
    fn new(name: &str) -> Draft {
        Draft {
            name: name.to_string(),
            outcomes: Vec::new(),
            nodes: Vec::new(),
            counters: Vec::new(),
            into: None,
        }
    }

    /// A state named `base`, or `base2`, `base3`… when taken anywhere in the machine (so a
    /// target's name finds one state wherever it is), by this base or another (`Kick2`).
    fn state(&mut self, base: &str, entry: Vec<String>) -> usize {
        let at = match self.counters.iter().position(|(b, _)| b == base) {
            Some(at) => at,
            None => {
                self.counters.push((base.to_string(), 0));
                self.counters.len() - 1
            }
        };
        let name = loop {
            self.counters[at].1 += 1;
            let n = self.counters[at].1;
            let name = if n == 1 {
                base.to_string()
            } else {
                format!("{base}{n}")
            };
            if self.nodes.iter().all(|node| node.name != name) {
                break name;
            }
        };
        self.nodes.push(Node {
            name,
            parent: self.into,
            entry,
            whens: Vec::new(),
            initial: None,
            outcome: None,
        });
        self.nodes.len() - 1
    }

    fn go(&mut self, source: usize, label: Label, target: usize) {
        self.nodes[source].whens.push((label, target));
    }

    /// The machine's text, `initial` its first state; each level's states in the order its
    /// transitions reach them from the one entered first.
    fn text(&self, initial: usize) -> String {
        let mut out = format!("machine {}\n", self.name);
        if !self.outcomes.is_empty() {
            let _ = writeln!(out, "outcome {}", self.outcomes.join(", "));
        }
        let _ = writeln!(out, "initial {}", self.nodes[initial].name);
        self.level(&mut out, None, Some(initial), "");
        out
    }

    fn level(&self, out: &mut String, parent: Option<usize>, first: Option<usize>, indent: &str) {
        let inside: Vec<usize> = (0..self.nodes.len())
            .filter(|&n| self.nodes[n].parent == parent)
            .collect();
        let mut order: Vec<usize> = first.into_iter().collect();
        let mut next = 0;
        while next < order.len() {
            for &(_, t) in &self.nodes[order[next]].whens {
                if inside.contains(&t) && !order.contains(&t) {
                    order.push(t);
                }
            }
            next += 1;
        }
        let rest: Vec<usize> = inside.into_iter().filter(|n| !order.contains(n)).collect();
        order.extend(rest);
        for n in order {
            self.write_state(out, n, indent);
        }
    }

    fn write_state(&self, out: &mut String, n: usize, indent: &str) {
        let node = &self.nodes[n];
        let _ = writeln!(out, "\n{indent}state {} {{", node.name);
        let inner = format!("{indent}    ");
        if let Some(initial) = node.initial {
            let _ = writeln!(out, "{inner}initial {}", self.nodes[initial].name);
        }
        if !node.entry.is_empty() {
            let _ = writeln!(out, "{inner}entry {{");
            for line in &node.entry {
                let _ = writeln!(out, "{inner}    {line}");
            }
            let _ = writeln!(out, "{inner}}}");
        }
        if let Some(outcome) = node.outcome {
            let _ = writeln!(out, "{inner}outcome {outcome}");
        }
        for (label, target) in &node.whens {
            let _ = writeln!(out, "{inner}when {label} -> {}", self.nodes[*target].name);
        }
        if node.initial.is_some() {
            self.level(out, Some(n), node.initial, &inner);
        }
        let _ = writeln!(out, "{indent}}}");
    }
}

/// Words a chart keeps for itself beside the native format's own ([`proclaim_fsm::KEYWORDS`]):
/// no activity's state can be named one.
const CHART_WORDS: [&str; 3] = ["done", "history", "deep_history"];

/// A name usable as a state, machine and message type: `center-for` → `center_for`, and a
/// reserved word with `_` after it (`entry_`).
fn ident(name: &str) -> String {
    let id = name.replace('-', "_");
    if proclaim_fsm::KEYWORDS.contains(&id.as_str()) || CHART_WORDS.contains(&id.as_str()) {
        id + "_"
    } else {
        id
    }
}

/// The first activity a formula names (to name the choice that leads to it).
fn first_activity(f: &GaiaFormula) -> String {
    match f {
        GaiaFormula::Activity(a) => ident(a),
        GaiaFormula::Sequence(fs) | GaiaFormula::Choice(fs) | GaiaFormula::Parallel(fs) => {
            fs.first().map(first_activity).unwrap_or_default()
        }
        GaiaFormula::Many(f)
        | GaiaFormula::OneOrMore(f)
        | GaiaFormula::Forever(f)
        | GaiaFormula::Optional(f) => first_activity(f),
    }
}

struct Generator<'a> {
    defs: &'a [Definition],
    /// The branches' machines, finished.
    machines: Vec<Skeleton>,
    taken: Vec<String>,
    expanding: Vec<String>,
    diagnostics: Vec<FileDiagnostic>,
    file: String,
}

impl Generator<'_> {
    fn machine_name(&mut self, base: &str) -> String {
        let mut name = ident(base);
        let mut n = 1;
        while self.taken.contains(&name) {
            n += 1;
            name = format!("{}_{n}", ident(base));
        }
        self.taken.push(name.clone());
        name
    }

    /// Draws `f`'s states into `draft`, every way out leading to `next`; returns the state
    /// where `f` begins.
    fn compile(&mut self, draft: &mut Draft, f: &GaiaFormula, next: usize) -> usize {
        let atom = Label::Name;
        match f {
            GaiaFormula::Activity(name) => self.activity(draft, name, next),
            GaiaFormula::Sequence(parts) => {
                let mut at = next;
                for part in parts.iter().rev() {
                    at = self.compile(draft, part, at);
                }
                at
            }
            GaiaFormula::Choice(options) => self.choice(draft, options, next),
            GaiaFormula::Many(inner) => {
                let l = draft.state("Repeat", Vec::new());
                let start = self.compile(draft, inner, l);
                draft.go(l, atom(format!("again{}", first_activity(inner))), start);
                draft.go(l, Label::TRUE, next);
                l
            }
            GaiaFormula::OneOrMore(inner) => {
                let l = draft.state("Repeat", Vec::new());
                let start = self.compile(draft, inner, l);
                draft.go(l, atom(format!("again{}", first_activity(inner))), start);
                draft.go(l, Label::TRUE, next);
                start
            }
            GaiaFormula::Forever(inner) => {
                let l = draft.state("Again", Vec::new());
                let start = self.compile(draft, inner, l);
                draft.go(l, Label::TRUE, start);
                start
            }
            GaiaFormula::Optional(inner) => {
                let m = draft.state("Maybe", Vec::new());
                let start = self.compile(draft, inner, next);
                draft.go(m, atom(format!("do{}", first_activity(inner))), start);
                draft.go(m, Label::TRUE, next);
                m
            }
            GaiaFormula::Parallel(branches) => self.parallel(draft, branches, next),
        }
    }

    /// A defined activity: a state holding its formula's states, left by `when done` once the
    /// last is reached (once: a definition in terms of itself is a basic activity inside). A
    /// basic one: a state calling its host function until `NameDone`.
    fn activity(&mut self, draft: &mut Draft, name: &str, next: usize) -> usize {
        let id = ident(name);
        if let Some(def) = self.defs.iter().find(|d| d.name == *name) {
            if !self.expanding.iter().any(|e| e == name) {
                self.expanding.push(name.to_string());
                let holder = draft.state(&id, Vec::new());
                let around = draft.into.replace(holder);
                let end = draft.state(&format!("{id}End"), Vec::new());
                let formula = def.formula.clone();
                let start = self.compile(draft, &formula, end);
                draft.into = around;
                draft.nodes[holder].initial = Some(start);
                draft.go(holder, Label::Name("done".into()), next);
                self.expanding.pop();
                return holder;
            }
            self.diagnostics.push(FileDiagnostic::warning(
                &self.file,
                def.line,
                format!(
                    "`{name}` is defined in terms of itself; its inner use is a basic activity"
                ),
            ));
        }
        let s = draft.state(&id, vec![format!("call {id}")]);
        draft.go(s, Label::Name(format!("{id}Done")), next);
        s
    }

    /// A state choosing among the options by labels nobody answers yet (`chooseA`).
    fn choice(&mut self, draft: &mut Draft, options: &[GaiaFormula], next: usize) -> usize {
        let c = draft.state("Choose", Vec::new());
        let mut named: Vec<String> = Vec::new();
        for option in options {
            let start = self.compile(draft, option, next);
            let mut label = format!("choose{}", first_activity(option));
            while named.contains(&label) {
                label.push('_');
            }
            named.push(label.clone());
            draft.go(c, Label::Name(label), start);
        }
        c
    }

    /// A state starting one sub-machine per branch and waiting until each has announced
    /// `finished` (a restart clears it, so a branch run again is waited for again).
    fn parallel(&mut self, draft: &mut Draft, branches: &[GaiaFormula], next: usize) -> usize {
        let mut entry = Vec::new();
        let mut finished = Vec::new();
        for (k, branch) in branches.iter().enumerate() {
            let base = match branch {
                GaiaFormula::Activity(a) => a.clone(),
                _ => format!("{}Branch{}", draft.name, k + 1),
            };
            let name = self.machine_name(&base);
            self.branch_machine(&name, branch);
            entry.push(format!("{name}: restart"));
            finished.push(Label::Name(format!("{name}.{FINISHED}")));
        }
        let p = draft.state("Parallel", entry);
        let all = Label::fold(BinOp::And, finished).unwrap_or(Label::TRUE);
        draft.go(p, all, next);
        p
    }

    /// A sub-machine running `f` once, then announcing `finished` in its final state.
    fn branch_machine(&mut self, name: &str, f: &GaiaFormula) {
        let mut draft = Draft::new(name);
        draft.outcomes.push(FINISHED);
        let end = draft.state("End", Vec::new());
        draft.nodes[end].outcome = Some(FINISHED);
        let start = self.compile(&mut draft, f, end);
        self.machines.push(Skeleton {
            name: name.to_string(),
            text: draft.text(start),
            start: false,
        });
    }
}

/// The skeleton behaviour of the formulas: the first formula's machine (started at once) first,
/// then one dormant machine for each branch of a `||`.
pub fn liveness_machines(file: &str, defs: &[Definition]) -> (Vec<Skeleton>, Vec<FileDiagnostic>) {
    let Some(root) = defs.first() else {
        return (
            Vec::new(),
            vec![FileDiagnostic::error(
                file,
                1,
                "no formula: write `Behaviour = A . B`",
            )],
        );
    };
    let mut g = Generator {
        defs,
        machines: Vec::new(),
        taken: Vec::new(),
        expanding: vec![root.name.clone()],
        diagnostics: Vec::new(),
        file: file.to_string(),
    };
    let name = g.machine_name(&root.name);
    let mut draft = Draft::new(&name);
    let end = draft.state("End", Vec::new());
    let start = g.compile(&mut draft, &root.formula, end);
    let mut machines = vec![Skeleton {
        name,
        text: draft.text(start),
        start: true,
    }];
    machines.append(&mut g.machines);
    for d in &defs[1..] {
        let used = g.expanding.contains(&d.name)
            || defs
                .iter()
                .any(|o| o.name != d.name && mentions(&o.formula, &d.name));
        if !used {
            g.diagnostics.push(FileDiagnostic::warning(
                file,
                d.line,
                format!("`{}` is defined but no formula uses it", d.name),
            ));
        }
    }
    (machines, g.diagnostics)
}

fn mentions(f: &GaiaFormula, name: &str) -> bool {
    match f {
        GaiaFormula::Activity(a) => a == name,
        GaiaFormula::Sequence(fs) | GaiaFormula::Choice(fs) | GaiaFormula::Parallel(fs) => {
            fs.iter().any(|f| mentions(f, name))
        }
        GaiaFormula::Many(f)
        | GaiaFormula::OneOrMore(f)
        | GaiaFormula::Forever(f)
        | GaiaFormula::Optional(f) => mentions(f, name),
    }
}
