//! `proclaim check` for a whole behaviour: each machine's own problems (states never reached,
//! transitions never tried), then what only the whole shows: labels nobody answers, postings
//! nobody listens to, sub-machines that do not exist, theory outputs nobody queries and inputs
//! nobody posts, sub-machines nothing starts. Each finding names the file and line it is about.

use crate::load::{Behaviour, LoadedMachine};
use crate::manifest::{Schedule, MANIFEST};
use crate::modules::{modules, Module, ModuleKind};
use proclaim_experts::Script;
use proclaim_fsm::{lint, FileDiagnostic};
use proclaim_lower::RingletPlan;
use proclaim_runner::{machine_of_running_type, Command};
use proclaim_syntax::nearest;

pub fn check_behaviour(behaviour: &Behaviour) -> Vec<FileDiagnostic> {
    check_behaviour_with(behaviour, None, &[])
}

/// The same, for a run whose labels a script also answers (`proclaim run --script FILE`:
/// `(FILE as shown, the script)`) and a person answers `asked` (`proclaim run --ask`).
pub fn check_behaviour_with(
    behaviour: &Behaviour,
    script: Option<(&str, &Script)>,
    asked: &[String],
) -> Vec<FileDiagnostic> {
    let mut answered_elsewhere = script.map(|(_, s)| s.atoms()).unwrap_or_default();
    answered_elsewhere.extend(asked.iter().cloned());
    let check = CrossModuleCheck {
        behaviour,
        all: modules(behaviour),
        answered_elsewhere,
        shared: behaviour.shared_variables(),
    };
    let mut out = Vec::new();
    for loaded in &behaviour.machines {
        out.extend(check.machine_findings(loaded));
    }
    out.extend(script_warnings_of(behaviour, &check.all, script));
    out.extend(check.unstarted());
    out.extend(check.races());
    for module in &check.all {
        if let ModuleKind::Theory { file } = &module.kind {
            out.extend(check.theory_findings(module, file));
        }
    }
    out.extend(program_findings(behaviour, &check.all));
    out.extend(crate::team::findings(behaviour, &check.all));
    out
}

/// A behaviour and every module's declaration: what only the whole shows.
struct CrossModuleCheck<'b> {
    behaviour: &'b Behaviour,
    all: Vec<Module>,
    /// Atoms a script or a person answers.
    answered_elsewhere: Vec<String>,
    /// The machines' shared variables (a label's names that are variables ask nobody).
    shared: std::sync::Arc<proclaim_runner::Shared>,
}

impl CrossModuleCheck<'_> {
    fn answered(&self, atom: &str) -> bool {
        self.answered_elsewhere.iter().any(|a| a == atom)
            || self
                .all
                .iter()
                .any(|m| m.decl.answers.iter().any(|a| a == atom))
    }

    fn posted_by_other(&self, ty: &str, me: &str) -> bool {
        self.all
            .iter()
            .any(|m| m.decl.name != me && m.decl.posts.iter().any(|p| p == ty))
    }

    /// A machine may read back what it posts itself; the team hears the types it shares.
    fn read_by(&self, ty: &str) -> bool {
        let shared = self.behaviour.manifest.team.iter();
        shared.flat_map(|t| &t.shared).any(|s| s.get_ref() == ty)
            || self.all.iter().any(|m| {
                m.decl.reads.iter().any(|r| r == ty) || m.decl.waits_on.iter().any(|w| w == ty)
            })
    }

    fn is_machine(&self, name: &str) -> bool {
        self.behaviour
            .machines
            .iter()
            .any(|m| m.machine.name == name)
    }

    /// One machine's own problems, then labels nobody answers and postings nobody hears.
    fn machine_findings(&self, loaded: &LoadedMachine) -> Vec<FileDiagnostic> {
        let m = &loaded.machine;
        let file = self.behaviour.files.show(&loaded.file);
        let mut out = lint(m, &file);
        let mut reported: Vec<String> = Vec::new();
        // An arm that joins regions' labels says each atom at the first transition's line:
        // every atom is also in the arm of its own transition alone, at its own line.
        for t in m.transitions.iter().filter(|t| t.joined.is_empty()) {
            for atom in proclaim_runner::asked(&t.label, m, &self.shared) {
                let own_status = machine_of_running_type(atom).is_some_and(|n| self.is_machine(n));
                // A teammate's value (`robot2.ballSeen`) is the team's to check (team.rs).
                let teammates = atom.contains('.');
                if self.answered(atom)
                    || own_status
                    || teammates
                    || self.posted_by_other(atom, &m.name)
                    || reported.iter().any(|r| r == atom)
                {
                    continue;
                }
                reported.push(atom.to_string());
                out.push(FileDiagnostic::error(
                    &file,
                    t.line,
                    format!("label `{atom}` is answered by no expert and posted by no module"),
                ));
            }
        }
        out.extend(self.values_nobody_gives(loaded, &file));
        out.extend(self.postings_nobody_hears(loaded, &file, &mut reported));
        out
    }

    /// The postings of `loaded`'s activities that no module reads (`reported`: the types
    /// already reported, each once).
    fn postings_nobody_hears(
        &self,
        loaded: &LoadedMachine,
        file: &str,
        reported: &mut Vec<String>,
    ) -> Vec<FileDiagnostic> {
        let m = &loaded.machine;
        let mut out = Vec::new();
        for state in &m.states {
            for action in RingletPlan::of_state(m, state)
                .activities()
                .into_iter()
                .flatten()
            {
                for (ty, content) in action.literal_postings() {
                    if reported.contains(&ty) || self.is_machine(&ty) || self.read_by(&ty) {
                        continue;
                    }
                    let line = m.line_of(state, action);
                    out.push(self.posting_nobody_hears(file, line, &ty, &content));
                    reported.push(ty);
                }
            }
        }
        out
    }

    /// A posting of `ty: content` that no machine or module hears. Only a machine obeys
    /// `suspend` or `restart`, so one sent to nobody is a machine missing; but `On` and `Off`
    /// are what a lamp, a speech module or a sensor wrapper is told too (the Griffith machines
    /// post `sensors_postJoints: On`), and the runner hands them to the board as any posting:
    /// a machine is missing only where one is a letter away. Anything else may be for a module
    /// outside the behaviour.
    fn posting_nobody_hears(
        &self,
        file: &str,
        line: usize,
        ty: &str,
        content: &str,
    ) -> FileDiagnostic {
        let machines = self.behaviour.machines.iter();
        let near = nearest(machines.map(|m| m.machine.name.as_str()), ty);
        let missing = match Command::parse(content) {
            Some(Command::On | Command::Off) => near.is_some(),
            Some(_) => true,
            None => false,
        };
        if !missing {
            let plain = if Command::parse(content).is_some() {
                format!("; `{ty}: {content}` is a plain posting, no machine is named `{ty}`")
            } else {
                String::new()
            };
            return FileDiagnostic::warning(
                file,
                line,
                format!(
                    "nobody listens to `{ty}` postings (name the module that does in the manifest's [[module]] or dictionary{plain})"
                ),
            );
        }
        let hint = near.map_or_else(
            || format!("and no module reads `{ty}`"),
            |near| format!("did you mean `{near}`?"),
        );
        FileDiagnostic::error(
            file,
            line,
            format!(
                "`{ty}: {content}` controls a machine `{ty}` the behaviour does not have ({hint})"
            ),
        )
    }

    /// The whiteboard values `loaded`'s labels compare that no module posts, no machine
    /// assigns and no one answers: such a value is never there, so the comparison never holds.
    /// (The global a launch manifest left its setter out of reads as one.)
    fn values_nobody_gives(&self, loaded: &LoadedMachine, file: &str) -> Vec<FileDiagnostic> {
        let m = &loaded.machine;
        let Some(me) = self.all.iter().find(|x| x.decl.name == m.name) else {
            return Vec::new();
        };
        let team = self.behaviour.manifest.team.iter().flat_map(|t| &t.shared);
        let team: Vec<&str> = team.map(|s| s.get_ref().as_str()).collect();
        let mut out = Vec::new();
        for ty in me.decl.reads.iter().filter(|ty| **ty != m.name) {
            let given = self.answered(ty)
                || self.is_machine(ty)
                || machine_of_running_type(ty).is_some_and(|n| self.is_machine(n))
                // A teammate's value or the team's (`robot2.x`, `team.x`) is team.rs's to check.
                || ty.contains('.')
                || team.contains(&ty.as_str())
                || self.all.iter().any(|x| x.decl.posts.iter().any(|p| p == ty));
            if given {
                continue;
            }
            let mut named = false;
            let line = m.transitions.iter().find(|t| {
                t.label.visit_names(&mut |name, _| named |= name == ty);
                named
            });
            out.push(FileDiagnostic::warning(
                file,
                line.map_or(1, |t| t.line),
                format!(
                    "a label reads `{ty}`, which nothing in this behaviour posts, assigns or answers, so a comparison with it never holds (was the machine that sets it left out? a script, or a module the manifest's [[module]] names, may post it)"
                ),
            ));
        }
        out
    }

    /// Sub-machines with `start = false` that no module posts `On` to.
    fn unstarted(&self) -> Vec<FileDiagnostic> {
        let mut out = Vec::new();
        for loaded in self.behaviour.machines.iter().filter(|m| !m.start) {
            let name = &loaded.machine.name;
            if !self.posted_by_other(name, name) {
                out.push(FileDiagnostic::warning(
                    &self.behaviour.files.show(&loaded.file),
                    1,
                    format!(
                        "sub-machine `{name}` has `start = false` and no module posts `{name}: On`, so it never runs"
                    ),
                ));
            }
        }
        out
    }

    /// Under `schedule = "concurrent"`, each variable that several machines use and one of
    /// them writes: which write wins depends on which task the runtime runs first.
    fn races(&self) -> Vec<FileDiagnostic> {
        if self.behaviour.manifest.schedule != Schedule::Concurrent {
            return Vec::new();
        }
        // Variable → (the machines that use it, those that write it), in manifest order.
        let mut users: Vec<(String, Vec<&str>, Vec<&str>)> = Vec::new();
        for loaded in &self.behaviour.machines {
            let m = &loaded.machine;
            let own = proclaim_runner::Locals::declared(m);
            let shared = |name: &str| {
                !own.contains(name) && (self.shared.is_global(name) || self.shared.is_extern(name))
            };
            let mut note = |name: &str, writes: bool| {
                if !shared(name) {
                    return;
                }
                let at = match users.iter().position(|(v, _, _)| v == name) {
                    Some(at) => at,
                    None => {
                        users.push((name.to_string(), Vec::new(), Vec::new()));
                        users.len() - 1
                    }
                };
                let (_, used, written) = &mut users[at];
                if !used.contains(&m.name.as_str()) {
                    used.push(&m.name);
                }
                if writes && !written.contains(&m.name.as_str()) {
                    written.push(&m.name);
                }
            };
            for t in &m.transitions {
                t.label.visit_names(&mut |name, _| note(name, false));
            }
            for statement in m.statements() {
                if let proclaim_fsm::Statement::Assign { name, .. } = statement {
                    note(name, true);
                }
                for e in statement.expressions() {
                    e.visit_names(&mut |name, _| note(name, false));
                }
            }
        }
        let manifest = self.behaviour.files.show(crate::manifest::MANIFEST);
        let text = self
            .behaviour
            .files
            .read(crate::manifest::MANIFEST)
            .unwrap_or_default();
        let line = text
            .lines()
            .position(|l| l.trim_start().starts_with("schedule"))
            .map_or(1, |i| i + 1);
        users
            .into_iter()
            .filter(|(_, used, written)| used.len() > 1 && !written.is_empty())
            .map(|(variable, used, written)| {
                FileDiagnostic::warning(
                    &manifest,
                    line,
                    format!(
                        "machines {} share `{variable}` (written by {}) under schedule = \"concurrent\": what each sees of it depends on which task the runtime runs first",
                        used.join(", "),
                        written.join(", ")
                    ),
                )
                .with_hint("leave out `schedule` to run the machines in rounds of ringlets, in manifest order")
            })
            .collect()
    }

    /// A theory's outputs nobody queries and inputs nobody posts, at their declarations.
    fn theory_findings(&self, module: &Module, file: &str) -> Vec<FileDiagnostic> {
        let shown = self.behaviour.files.show(file);
        let line_of = declared_lines(self.behaviour, file);
        let mut out = Vec::new();
        for output in &module.decl.answers {
            if queried(&self.all, output) {
                continue;
            }
            let mut message = format!(
                "output `{output}` of theory {} is queried by no machine",
                module.decl.name
            );
            // `~x` in a label asks for `x` and negates the answer: it never asks for `~x`.
            if let Some(atom) = output.strip_prefix('~').filter(|a| queried(&self.all, a)) {
                message.push_str(&format!(
                    "; a label `~{atom}` asks for `{atom}` and negates its answer, so declare `output{{{atom}}}` for it"
                ));
            }
            out.push(FileDiagnostic::warning(&shown, line_of(output), message));
        }
        for input in module
            .decl
            .reads
            .iter()
            .filter(|r| *r != proclaim_board::QUERY_TYPE)
        {
            if !self.posted_by_other(input, &module.decl.name) {
                out.push(FileDiagnostic::warning(
                    &shown,
                    line_of(input),
                    format!(
                        "input `{input}` of theory {} is posted by no module",
                        module.decl.name
                    ),
                ));
            }
        }
        out
    }
}

/// The line where a theory file of the behaviour declares an output or an input (1 when
/// unknown).
fn declared_lines<'b>(behaviour: &'b Behaviour, file: &str) -> impl Fn(&str) -> usize + 'b {
    let text = behaviour.files.read(file).unwrap_or_default();
    let theory = behaviour.theories.iter().find(|t| t.file == file);
    move |name: &str| {
        let Some(t) = theory else { return 1 };
        let theory = &t.theory;
        let output = theory
            .outputs()
            .iter()
            .find(|o| theory.show(o.lit).to_string() == name)
            .map(|o| o.span);
        let input = || {
            theory
                .inputs()
                .iter()
                .find(|g| g.atoms.iter().any(|&a| theory.atom_name(a) == name))
                .map(|g| g.span)
        };
        output.or_else(input).map_or(1, |span| {
            proclaim_syntax::line_column(&text, span.start as usize).0
        })
    }
}

fn queried(all: &[Module], atom: &str) -> bool {
    all.iter()
        .any(|m| m.decl.waits_on.iter().any(|w| w == atom))
}

/// What the script a run uses sets that no machine asks and no module reads: the one given
/// (`(FILE as shown, script)`, from `run --script`), else the manifest's impersonator's.
pub fn script_warnings(
    behaviour: &Behaviour,
    script: Option<(&str, &Script)>,
) -> Vec<FileDiagnostic> {
    script_warnings_of(behaviour, &modules(behaviour), script)
}

fn script_warnings_of(
    behaviour: &Behaviour,
    all: &[Module],
    script: Option<(&str, &Script)>,
) -> Vec<FileDiagnostic> {
    let manifest_script = behaviour
        .script
        .as_ref()
        .zip(behaviour.manifest.impersonator.as_ref())
        .map(|(s, i)| (behaviour.files.show(&i.script), s));
    // A machine's activities read the whiteboard types it binds as `extern` (`rr = ballRR`).
    let externs: Vec<&str> = behaviour
        .machines
        .iter()
        .flat_map(|m| m.machine.statements())
        .filter_map(|s| match s {
            proclaim_fsm::Statement::Extern { name, .. } => Some(name.as_str()),
            _ => None,
        })
        .collect();
    match (script, &manifest_script) {
        (Some((file, s)), _) => unheard(all, &externs, file, s),
        (None, Some((file, s))) => unheard(all, &externs, file, s),
        (None, None) => Vec::new(),
    }
}

/// Atoms a script sets that no machine asks, binds as `extern` or reads and no module reads:
/// a typo, most likely.
fn unheard(all: &[Module], externs: &[&str], file: &str, script: &Script) -> Vec<FileDiagnostic> {
    let heard: Vec<&str> = all
        .iter()
        .flat_map(|m| m.decl.waits_on.iter().chain(&m.decl.reads))
        .map(String::as_str)
        .chain(externs.iter().copied())
        .collect();
    let mut out = Vec::new();
    let mut said: Vec<&str> = Vec::new();
    for step in &script.steps {
        let atom = step.atom.trim_start_matches('~');
        if heard.contains(&atom) || said.contains(&atom) {
            continue;
        }
        said.push(atom);
        let hint = proclaim_syntax::nearest(heard.iter().copied(), atom)
            .map(|n| format!("; did you mean `{n}`?"))
            .unwrap_or_default();
        out.push(FileDiagnostic::warning(
            file,
            step.line,
            format!("`{atom}` is asked by no machine and read by no module{hint}"),
        ));
    }
    out
}

/// What `check` says of the program experts, as of a theory's outputs and inputs: a label no
/// machine queries and an input no module posts, each at the manifest line that names it.
fn program_findings(behaviour: &Behaviour, all: &[Module]) -> Vec<FileDiagnostic> {
    let manifest = behaviour.files.show(MANIFEST);
    let text = behaviour.files.read(MANIFEST).unwrap_or_default();
    let line_of = |name: &str| {
        let quoted = format!("\"{name}\"");
        text.lines()
            .position(|l| l.contains(&quoted))
            .map_or(1, |i| i + 1)
    };
    let mut out = Vec::new();
    for p in &behaviour.programs {
        let namesakes = all.iter().filter(|m| m.decl.name == p.name).count();
        if namesakes > 1 {
            out.push(
                FileDiagnostic::error(
                    &manifest,
                    p.answers.first().map_or(1, |a| line_of(a)),
                    format!(
                        "two modules are named `{}`: the expert's name is how the whiteboard knows it",
                        p.name
                    ),
                )
                .with_hint("give the expert a name of its own with `name = \"…\"`"),
            );
        }
        for label in &p.answers {
            if !all.iter().any(|m| m.decl.waits_on.contains(label)) {
                out.push(FileDiagnostic::warning(
                    &manifest,
                    line_of(label),
                    format!(
                        "label `{label}` of expert {} is queried by no machine",
                        p.name
                    ),
                ));
            }
        }
        for input in &p.inputs {
            let posted = all
                .iter()
                .any(|m| m.decl.name != p.name && m.decl.posts.contains(input));
            if !posted {
                out.push(FileDiagnostic::warning(
                    &manifest,
                    line_of(input),
                    format!(
                        "input `{input}` of expert {} is posted by no module",
                        p.name
                    ),
                ));
            }
        }
    }
    out
}
