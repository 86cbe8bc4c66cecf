//! Liveness formulas written as a skeleton behaviour of statecharts, as the Kouretes tool
//! draws them: an activity that has a formula of its own is a state holding that formula's
//! states (left by `when done` once its last one is reached), a basic activity a state calling
//! the host function of its name, and a `||` a parallel state whose regions run its branches
//! side by side, left by `when done` once every branch has ended (an AND-state,
//! `docs/spec/behaviour.md` §3.2). The choices the formulas leave open are labels nobody
//! answers yet (`choosePlay`, `SitDownAndStareDone`, `againPlay`), which `proclaim check`
//! lists.

use crate::liveness::{Definition, GaiaFormula};
use proclaim_fsm::{FileDiagnostic, Label};
use std::fmt::Write;

/// One machine of the skeleton, as the text of its native file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skeleton {
    pub name: String,
    pub text: String,
    /// Whether it starts with the behaviour (the first formula's machine does).
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
    /// A parallel state: the states it holds are regions, all entered with it.
    parallel: bool,
}

/// A machine being drawn up: its states, and where new ones go.
struct Draft {
    name: String,
    nodes: Vec<Node>,
    counters: Vec<(String, usize)>,
    into: Option<usize>,
}

impl Draft {
    fn new(name: &str) -> Draft {
        Draft {
            name: name.to_string(),
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
            parallel: false,
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
        let keyword = if node.parallel { "parallel" } else { "state" };
        let _ = writeln!(out, "\n{indent}{keyword} {} {{", node.name);
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
        for (label, target) in &node.whens {
            let _ = writeln!(out, "{inner}when {label} -> {}", self.nodes[*target].name);
        }
        if node.initial.is_some() || node.parallel {
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
    expanding: Vec<String>,
    diagnostics: Vec<FileDiagnostic>,
    file: String,
}

impl Generator<'_> {
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

    /// A parallel state with a region a branch, each running its branch once to a final
    /// state, left by `when done` once every region has (§3.2).
    fn parallel(&mut self, draft: &mut Draft, branches: &[GaiaFormula], next: usize) -> usize {
        let p = draft.state("Parallel", Vec::new());
        draft.nodes[p].parallel = true;
        let around = draft.into.replace(p);
        for (k, branch) in branches.iter().enumerate() {
            let base = match branch {
                GaiaFormula::Activity(a) => format!("{}Branch", ident(a)),
                _ => format!("Branch{}", k + 1),
            };
            let region = draft.state(&base, Vec::new());
            let outside = draft.into.replace(region);
            let end = draft.state(&format!("{base}End"), Vec::new());
            let start = self.compile(draft, branch, end);
            draft.into = outside;
            draft.nodes[region].initial = Some(start);
        }
        draft.into = around;
        draft.go(p, Label::Name("done".into()), next);
        p
    }
}

/// The skeleton behaviour of the formulas: one machine, the first formula's, started at once.
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
        expanding: vec![root.name.clone()],
        diagnostics: Vec::new(),
        file: file.to_string(),
    };
    let name = ident(&root.name);
    let mut draft = Draft::new(&name);
    let end = draft.state("End", Vec::new());
    let start = g.compile(&mut draft, &root.formula, end);
    let machines = vec![Skeleton {
        name,
        text: draft.text(start),
        start: true,
    }];
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
