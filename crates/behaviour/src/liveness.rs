//! Liveness formulas (the Kouretes paper, Section 3; Gaia's operators) turned into a skeleton
//! behaviour: one machine for the first formula, one for each branch of a `||`.
//!
//! ```text
//! TestBehavior = (Play | NoPlay)+
//! Play = SitDownAndStare | StandUpAndScan
//! ```
//!
//! Operators, loosest first: `A || B` (concurrently), `A | B` (one of them), `A . B` (A then B),
//! then `A*` (zero or more times), `A+` (one or more), `A~` (for ever), `[A]` (optional), and
//! parentheses. An activity defined by a formula of its own is expanded in place; the others are
//! basic activities: a state whose OnEntry calls a host function of the same name, left to fill
//! in. The choices the formulas leave open become labels nobody answers yet (`choosePlay`,
//! `SitDownAndStareDone`, `againPlay`), which `proclaim check` lists. `A || B` becomes a state
//! that starts sub-machines `A` and `B` and waits until both post `AFinished` / `BFinished`.

use proclaim_fsm::BinOp;
use proclaim_fsm::FileDiagnostic;
use proclaim_fsm::Label;
use proclaim_fsm::{finished_type, Command};
use proclaim_fsm::{Action, Machine, State, StateId, Transition};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GaiaFormula {
    Activity(String),
    Sequence(Vec<GaiaFormula>),
    Choice(Vec<GaiaFormula>),
    Parallel(Vec<GaiaFormula>),
    /// `A*`
    Many(Box<GaiaFormula>),
    /// `A+`
    OneOrMore(Box<GaiaFormula>),
    /// `A~`
    Forever(Box<GaiaFormula>),
    /// `[A]`
    Optional(Box<GaiaFormula>),
}

/// One `Name = formula` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Definition {
    pub name: String,
    pub formula: GaiaFormula,
    pub line: usize,
}

/// Reads formulas, one a line (`#` and `//` comments). Every bad line is reported.
pub fn parse_liveness(file: &str, text: &str) -> (Vec<Definition>, Vec<FileDiagnostic>) {
    let mut defs = Vec::new();
    let mut diagnostics = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let code = raw.split('#').next().unwrap_or("");
        let code = code.split("//").next().unwrap_or("").trim();
        if code.is_empty() {
            continue;
        }
        let Some((name, formula)) = code.split_once('=') else {
            diagnostics.push(FileDiagnostic::error(
                file,
                line,
                "a formula is `Name = activities` (no `=` here)",
            ));
            continue;
        };
        let name = name.trim();
        if !is_name(name) {
            diagnostics.push(FileDiagnostic::error(
                file,
                line,
                format!("`{name}` is not an activity name (letters, digits, `_` and `-`)"),
            ));
            continue;
        }
        let mut p = Parser {
            tokens: tokenize(formula),
            at: 0,
        };
        match p.parallel().and_then(|f| match p.peek() {
            None => Ok(f),
            Some(t) => Err(format!("unexpected `{t}`")),
        }) {
            Ok(_) if defs.iter().any(|d: &Definition| d.name == name) => {
                diagnostics.push(FileDiagnostic::error(
                    file,
                    line,
                    format!("`{name}` is defined twice"),
                ));
            }
            Ok(formula) => defs.push(Definition {
                name: name.to_string(),
                formula,
                line,
            }),
            Err(message) => diagnostics.push(FileDiagnostic::error(
                file,
                line,
                format!("in the formula of `{name}`: {message}"),
            )),
        }
    }
    (defs, diagnostics)
}

fn is_name(text: &str) -> bool {
    text.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && text
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
}

fn tokenize(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '|' && chars.get(i + 1) == Some(&'|') {
            out.push("||".into());
            i += 2;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_alphanumeric() || chars[i] == '_' || chars[i] == '-')
            {
                i += 1;
            }
            out.push(chars[start..i].iter().collect());
        } else {
            // `∼` (the paper's tilde) reads as `~`.
            out.push(if c == '∼' {
                "~".into()
            } else {
                c.to_string()
            });
            i += 1;
        }
    }
    out
}

struct Parser {
    tokens: Vec<String>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&str> {
        self.tokens.get(self.at).map(String::as_str)
    }

    fn list(
        &mut self,
        op: &str,
        part: fn(&mut Parser) -> Result<GaiaFormula, String>,
        make: fn(Vec<GaiaFormula>) -> GaiaFormula,
    ) -> Result<GaiaFormula, String> {
        let mut parts = vec![part(self)?];
        while self.peek() == Some(op) {
            self.at += 1;
            parts.push(part(self)?);
        }
        Ok(if parts.len() == 1 {
            parts.remove(0)
        } else {
            make(parts)
        })
    }

    fn parallel(&mut self) -> Result<GaiaFormula, String> {
        self.list("||", Parser::choice, GaiaFormula::Parallel)
    }

    fn choice(&mut self) -> Result<GaiaFormula, String> {
        self.list("|", Parser::sequence, GaiaFormula::Choice)
    }

    fn sequence(&mut self) -> Result<GaiaFormula, String> {
        self.list(".", Parser::postfix, GaiaFormula::Sequence)
    }

    fn postfix(&mut self) -> Result<GaiaFormula, String> {
        let mut f = self.atom()?;
        loop {
            f = match self.peek() {
                Some("*") => GaiaFormula::Many(Box::new(f)),
                Some("+") => GaiaFormula::OneOrMore(Box::new(f)),
                Some("~") => GaiaFormula::Forever(Box::new(f)),
                _ => return Ok(f),
            };
            self.at += 1;
        }
    }

    fn atom(&mut self) -> Result<GaiaFormula, String> {
        let Some(token) = self.peek().map(str::to_string) else {
            return Err("the formula ends too early".into());
        };
        self.at += 1;
        match token.as_str() {
            "(" => {
                let f = self.parallel()?;
                self.expect(")")?;
                Ok(f)
            }
            "[" => {
                let f = self.parallel()?;
                self.expect("]")?;
                Ok(GaiaFormula::Optional(Box::new(f)))
            }
            name if is_name(name) => Ok(GaiaFormula::Activity(name.to_string())),
            other => Err(format!("expected an activity, `(` or `[`, found `{other}`")),
        }
    }

    fn expect(&mut self, token: &str) -> Result<(), String> {
        match self.peek() {
            Some(t) if t == token => {
                self.at += 1;
                Ok(())
            }
            Some(t) => Err(format!("expected `{token}`, found `{t}`")),
            None => Err(format!("missing `{token}`")),
        }
    }
}

/// A machine being generated.
struct Draft {
    name: String,
    states: Vec<State>,
    transitions: Vec<Transition>,
    counters: Vec<(String, usize)>,
}

impl Draft {
    fn new(name: &str) -> Draft {
        Draft {
            name: name.to_string(),
            states: Vec::new(),
            transitions: Vec::new(),
            counters: Vec::new(),
        }
    }

    /// A state named `base`, or `base2`, `base3`… when taken.
    fn state(&mut self, base: &str, on_entry: Vec<Action>) -> StateId {
        let n = match self.counters.iter_mut().find(|(b, _)| b == base) {
            Some((_, n)) => {
                *n += 1;
                *n
            }
            None => {
                self.counters.push((base.to_string(), 1));
                1
            }
        };
        let name = if n == 1 {
            base.to_string()
        } else {
            format!("{base}{n}")
        };
        let id = self.states.len() as StateId + 1;
        self.states.push(State {
            id,
            name,
            on_entry,
            on_exit: Vec::new(),
            internal: Vec::new(),
            line: 0,
            arrives_through: 0,
        });
        id
    }

    fn go(&mut self, source: StateId, label: Label, target: StateId) {
        self.transitions.push(Transition {
            source,
            target,
            label,
            line: 0,
            leaving: None,
            composite: None,
            written: None,
        });
    }

    /// The machine, its states renumbered in the order they are reached from `initial`.
    fn finish(self, initial: StateId) -> Machine {
        let mut order = vec![initial];
        let mut next = 0;
        while next < order.len() {
            let at = order[next];
            next += 1;
            for t in self.transitions.iter().filter(|t| t.source == at) {
                if !order.contains(&t.target) {
                    order.push(t.target);
                }
            }
        }
        for s in &self.states {
            if !order.contains(&s.id) {
                order.push(s.id);
            }
        }
        let new_id =
            |old: StateId| order.iter().position(|&o| o == old).unwrap_or(0) as StateId + 1;
        let mut states: Vec<State> = order
            .iter()
            .filter_map(|&old| self.states.iter().find(|s| s.id == old).cloned())
            .collect();
        for s in &mut states {
            s.id = new_id(s.id);
        }
        let mut transitions = self.transitions;
        for t in &mut transitions {
            t.source = new_id(t.source);
            t.target = new_id(t.target);
        }
        transitions.sort_by_key(|t| t.source);
        Machine {
            name: self.name,
            states,
            transitions,
            initial: 1,
            ..Machine::default()
        }
    }
}

/// A name usable as a state, machine and message type: `center-for` → `center_for`.
fn ident(name: &str) -> String {
    name.replace('-', "_")
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
    /// Finished machines, with whether each starts at once.
    machines: Vec<(Machine, bool)>,
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

    /// Builds `f`'s states into `draft`, every way out leading to `next`; returns the state
    /// where `f` begins.
    fn compile(&mut self, draft: &mut Draft, f: &GaiaFormula, next: StateId) -> StateId {
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

    /// A defined activity expanded in place (once: a definition in terms of itself is a basic
    /// activity inside), or a basic one: a state calling its host function until `NameDone`.
    fn activity(&mut self, draft: &mut Draft, name: &str, next: StateId) -> StateId {
        let atom = Label::Name;
        if let Some(def) = self.defs.iter().find(|d| d.name == *name) {
            if !self.expanding.iter().any(|e| e == name) {
                self.expanding.push(name.to_string());
                let formula = def.formula.clone();
                let start = self.compile(draft, &formula, next);
                self.expanding.pop();
                return start;
            }
            self.diagnostics.push(FileDiagnostic::warning(
                &self.file,
                def.line,
                format!(
                    "`{name}` is defined in terms of itself; its inner use is a basic activity"
                ),
            ));
        }
        let id = ident(name);
        let s = draft.state(
            &id,
            vec![Action::Call {
                function: id.clone(),
                argument: None,
            }],
        );
        draft.go(s, atom(format!("{id}Done")), next);
        s
    }

    /// A state choosing among the options by labels nobody answers yet (`chooseA`).
    fn choice(&mut self, draft: &mut Draft, options: &[GaiaFormula], next: StateId) -> StateId {
        let atom = Label::Name;
        let c = draft.state("Choose", Vec::new());
        let mut named: Vec<String> = Vec::new();
        for option in options {
            let start = self.compile(draft, option, next);
            let mut label = format!("choose{}", first_activity(option));
            while named.contains(&label) {
                label.push('_');
            }
            named.push(label.clone());
            draft.go(c, atom(label), start);
        }
        c
    }

    /// A state starting one sub-machine per branch and waiting for all their `NameFinished`.
    fn parallel(&mut self, draft: &mut Draft, branches: &[GaiaFormula], next: StateId) -> StateId {
        let atom = Label::Name;
        let mut entry = Vec::new();
        let mut done = Vec::new();
        for (k, branch) in branches.iter().enumerate() {
            let base = match branch {
                GaiaFormula::Activity(a) => a.clone(),
                _ => format!("{}Branch{}", draft.name, k + 1),
            };
            let name = self.machine_name(&base);
            self.branch_machine(&name, branch);
            entry.push(Action::Post {
                ty: finished_type(&name),
                content: "false".into(),
            });
            entry.push(Action::Post {
                ty: name.clone(),
                content: Command::On.word().into(),
            });
            done.push(atom(finished_type(&name)));
        }
        let p = draft.state("Parallel", entry);
        draft.go(
            p,
            Label::fold(BinOp::And, done).unwrap_or(Label::TRUE),
            next,
        );
        p
    }

    /// A sub-machine running `f` once, then posting `NameFinished` and turning itself off.
    fn branch_machine(&mut self, name: &str, f: &GaiaFormula) {
        let mut draft = Draft::new(name);
        let end = draft.state(
            "End",
            vec![
                Action::Post {
                    ty: finished_type(name),
                    content: "true".into(),
                },
                Action::Post {
                    ty: name.to_string(),
                    content: Command::Off.word().into(),
                },
            ],
        );
        let start = self.compile(&mut draft, f, end);
        self.machines.push((draft.finish(start), false));
    }
}

/// The skeleton behaviour of the formulas: the first formula's machine (started at once) first,
/// then one dormant machine for each branch of a `||`.
pub fn liveness_machines(
    file: &str,
    defs: &[Definition],
) -> (Vec<(Machine, bool)>, Vec<FileDiagnostic>) {
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
    let mut machines = vec![(draft.finish(start), true)];
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
