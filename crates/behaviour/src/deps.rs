//! The module-dependency diagram of the seed paper (Section III, Figure 4), and the smallest
//! behaviour that runs one machine with exactly the modules it needs (the seed's generated test
//! script).

use crate::error::BehaviourError;
use crate::load::Behaviour;
use crate::manifest::{ImpersonatorEntry, MachineEntry, Manifest, Simulator, TheoryEntry};
use crate::modules::{Module, ModuleKind};
use std::fmt::Write;
use std::time::Duration;

/// One module at the centre: the experts it queries above it (green arrows, blocking: they
/// proclaim its labels), the modules that listen to its postings below it (black arrows,
/// non-blocking), and a red **unknown** for a label nobody answers or a posting nobody hears.
pub fn module_diagram(modules: &[Module], centre: &str) -> Result<String, BehaviourError> {
    let Some(me) = modules.iter().find(|m| m.decl.name == centre) else {
        return Err(BehaviourError::NoSuch {
            kind: "module",
            name: centre.to_string(),
            known: modules.iter().map(|m| m.decl.name.clone()).collect(),
        });
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "digraph {} {{",
        quote(&format!("dependencies of {centre}"))
    );
    out.push_str("  rankdir=TB;\n  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n  edge [fontname=\"Helvetica\", fontsize=9];\n");
    let _ = writeln!(
        out,
        "  {} [style=\"rounded,bold\", penwidth=2];",
        quote(centre)
    );
    let mut above: Vec<String> = Vec::new();
    let mut below: Vec<String> = Vec::new();
    let experts_missing = link_side(modules, me, Side::Experts, &mut above, &[], &mut out);
    let listeners_missing = link_side(modules, me, Side::Listeners, &mut below, &above, &mut out);
    let unknown = experts_missing || listeners_missing;
    if unknown {
        out.push_str("  unknown [shape=plaintext, fontcolor=red, label=\"unknown\"];\n");
    }
    for (rank, group) in [("min", &above), ("max", &below)] {
        if !group.is_empty() {
            let members: Vec<String> = group.iter().map(|n| quote(n)).collect();
            let _ = writeln!(out, "  {{ rank={rank}; {}; }}", members.join("; "));
        }
    }
    out.push_str("}\n");
    Ok(out)
}

/// The two sides of the module at the centre of its diagram.
#[derive(Clone, Copy)]
enum Side {
    /// The experts answering what it waits on: green arrows into it, from above.
    Experts,
    /// The modules hearing what it posts: black arrows out of it, below.
    Listeners,
}

/// The modules on one side of `me`, linked to it by what each link is about (a label nobody
/// answers, or a posting nobody hears, linked to `unknown` in red), gathered into `placed`
/// unless already in `elsewhere`; whether any was missing.
fn link_side(
    modules: &[Module],
    me: &Module,
    side: Side,
    placed: &mut Vec<String>,
    elsewhere: &[String],
    out: &mut String,
) -> bool {
    let centre = me.decl.name.as_str();
    let quoted_centre = quote(centre);
    let running = proclaim_runner::running_type(centre);
    let topics: Vec<&String> = match side {
        Side::Experts => me.decl.waits_on.iter().collect(),
        Side::Listeners => me.decl.posts.iter().filter(|t| **t != running).collect(),
    };
    let kind = match side {
        Side::Experts => Arrow::Proclaims,
        Side::Listeners => Arrow::Heard,
    };
    let mut unknown = false;
    for topic in topics {
        let partners: Vec<&str> = modules
            .iter()
            .filter(|m| m.decl.name != centre)
            .filter(|m| match side {
                Side::Experts => m.decl.answers.contains(topic),
                Side::Listeners => m.decl.reads.contains(topic) || m.decl.waits_on.contains(topic),
            })
            .map(|m| m.decl.name.as_str())
            .collect();
        if partners.is_empty() {
            unknown = true;
            let (from, to) = ends(side, &quoted_centre, "unknown");
            arrow(out, from, to, topic, Arrow::Unknown);
        }
        let kind = match side {
            Side::Listeners => subsumption(modules, me, topic).unwrap_or(kind),
            Side::Experts => kind,
        };
        for partner in partners {
            if !placed.iter().chain(elsewhere).any(|p| p == partner) {
                placed.push(partner.to_string());
            }
            let quoted = quote(partner);
            let (from, to) = ends(side, &quoted_centre, &quoted);
            arrow(out, from, to, topic, kind);
        }
    }
    unknown
}

/// An arrow's tail and head: experts point at the centre, the centre at its listeners.
fn ends<'a>(side: Side, centre: &'a str, partner: &'a str) -> (&'a str, &'a str) {
    match side {
        Side::Experts => (partner, centre),
        Side::Listeners => (centre, partner),
    }
}

/// What an arrow of a dependency diagram says.
#[derive(Clone, Copy)]
enum Arrow {
    /// An expert proclaims a label its head waits on (green).
    Proclaims,
    /// Its head hears a posting of its tail (black).
    Heard,
    /// Nobody answers or hears it (red, to or from `unknown`).
    Unknown,
    /// Heard, from a layer whose postings of a `[suppress]` type hold it against a lower
    /// layer's for `hold` (Brooks' suppressor: bold blue, marked S).
    Suppresses { priority: u32, hold: Duration },
    /// Heard, from a layer a higher one suppresses on this type (dashed).
    Suppressible { priority: u32 },
}

/// How the posting of `topic` by `poster` is heard when `topic` is under subsumption and
/// another machine posts it at another priority; `None` for an ordinary posting.
fn subsumption(modules: &[Module], poster: &Module, topic: &str) -> Option<Arrow> {
    let ModuleKind::Machine {
        priority, holds, ..
    } = &poster.kind
    else {
        return None;
    };
    let hold = holds.iter().find(|(ty, _)| ty == topic)?.1;
    let others: Vec<u32> = modules
        .iter()
        .filter(|m| m.decl.name != poster.decl.name && m.decl.posts.iter().any(|t| t == topic))
        .filter_map(|m| match &m.kind {
            ModuleKind::Machine { priority, .. } => Some(*priority),
            _ => None,
        })
        .collect();
    if others.iter().any(|p| p < priority) {
        Some(Arrow::Suppresses {
            priority: *priority,
            hold,
        })
    } else if others.iter().any(|p| p > priority) {
        Some(Arrow::Suppressible {
            priority: *priority,
        })
    } else {
        None
    }
}

/// One arrow between two nodes already quoted (or `unknown`), labelled with what it is about.
fn arrow(out: &mut String, from: &str, to: &str, topic: &str, kind: Arrow) {
    let (colour, label) = match kind {
        Arrow::Proclaims => ("color=green4, ".to_string(), topic.to_string()),
        Arrow::Heard => (String::new(), topic.to_string()),
        Arrow::Unknown => ("color=red, fontcolor=red, ".to_string(), topic.to_string()),
        Arrow::Suppresses { priority, hold } => (
            "color=blue4, fontcolor=blue4, penwidth=2, arrowhead=odot, ".to_string(),
            format!("{topic} @{priority} S {}ms", hold.as_millis()),
        ),
        Arrow::Suppressible { priority } => {
            ("style=dashed, ".to_string(), format!("{topic} @{priority}"))
        }
    };
    let _ = writeln!(out, "  {from} -> {to} [{colour}label={}];", quote(&label));
}

/// Every module and every provider → listener link: green where a label is proclaimed, black
/// where a posting is heard, red to **unknown** where nobody answers or hears.
pub fn overall_diagram(modules: &[Module], name: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "digraph {} {{", quote(&format!("modules of {name}")));
    out.push_str("  rankdir=TB;\n  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n  edge [fontname=\"Helvetica\", fontsize=9];\n");
    for m in modules {
        let style = match m.kind {
            ModuleKind::Machine { .. } => "rounded,bold",
            ModuleKind::Outside => "rounded,dashed",
            _ => "rounded",
        };
        let _ = writeln!(out, "  {} [style=\"{style}\"];", quote(&m.decl.name));
    }
    let mut unknown = false;
    for m in modules {
        for atom in &m.decl.waits_on {
            let experts: Vec<&Module> = modules
                .iter()
                .filter(|e| e.decl.name != m.decl.name && e.decl.answers.contains(atom))
                .collect();
            unknown |= experts.is_empty();
            let name = quote(&m.decl.name);
            if experts.is_empty() {
                arrow(&mut out, "unknown", &name, atom, Arrow::Unknown);
            }
            for e in experts {
                arrow(
                    &mut out,
                    &quote(&e.decl.name),
                    &name,
                    atom,
                    Arrow::Proclaims,
                );
            }
        }
        for ty in m.decl.posts.iter().filter(|t| !m.decl.answers.contains(t)) {
            let kind = subsumption(modules, m, ty).unwrap_or(Arrow::Heard);
            for l in modules
                .iter()
                .filter(|l| l.decl.name != m.decl.name && l.decl.reads.contains(ty))
            {
                arrow(
                    &mut out,
                    &quote(&m.decl.name),
                    &quote(&l.decl.name),
                    ty,
                    kind,
                );
            }
        }
    }
    if unknown {
        out.push_str("  unknown [shape=plaintext, fontcolor=red, label=\"unknown\"];\n");
    }
    out.push_str("}\n");
    out
}

/// The manifest of the smallest behaviour that runs machine `centre`: it, the sub-machines it
/// starts (and theirs), the experts and sensor wrappers that answer their labels, and the
/// behaviour's outside modules. Paths stay relative to the behaviour's folder, so the file
/// belongs beside its `behaviour.toml`.
///
/// `place` says how to write a file of the behaviour so that it is found from where the
/// manifest goes (the file as named in the behaviour, when the manifest goes beside it).
pub fn launch_manifest(
    behaviour: &Behaviour,
    modules: &[Module],
    centre: &str,
    place: &dyn Fn(&str) -> String,
) -> Result<String, BehaviourError> {
    if !behaviour.machines.iter().any(|m| m.machine.name == centre) {
        return Err(BehaviourError::NoSuch {
            kind: "machine",
            name: centre.to_string(),
            known: behaviour
                .machines
                .iter()
                .map(|m| m.machine.name.clone())
                .collect(),
        });
    }
    let wanted = started_from(behaviour, modules, centre);
    let needed = serving(modules, &wanted);
    let smallest = smallest_manifest(behaviour, modules, centre, &wanted, &needed, place);
    let mut comment = format!(
        "The smallest behaviour that runs {centre}: written by `proclaim deps --launch {centre}`."
    );
    let params = behaviour
        .machines
        .iter()
        .find(|m| m.machine.name == centre)
        .map_or(&[][..], |m| &m.machine.interface.params[..]);
    if !params.is_empty() {
        let names: Vec<&str> = params.iter().map(|p| p.name.as_str()).collect();
        let globals: Vec<String> = names
            .iter()
            .map(|p| proclaim_fsm::global_of(centre, p))
            .collect();
        let starters: Vec<&str> = behaviour
            .machines
            .iter()
            .filter(|m| m.machine.name != centre)
            .filter(|m| {
                m.machine.statements().iter().any(|s| {
                    matches!(s, proclaim_fsm::Statement::Assign { name, .. } if globals.contains(name))
                })
            })
            .map(|m| m.machine.name.as_str())
            .collect();
        let _ = write!(
            comment,
            "\n{centre}'s parameters ({}) are given below as placeholders (0): choose them.",
            names.join(", ")
        );
        if !starters.is_empty() {
            let _ = write!(
                comment,
                "\nIn the whole behaviour, {} gives them as it starts {centre}.",
                starters.join(" and ")
            );
        }
    }
    Ok(smallest.to_toml(&comment))
}

/// The parameters of the machine launched on its own (`centre`), each the zero of its type: in
/// the whole behaviour, whoever starts it gives them (the manifest's comment says who).
fn placeholders(
    machine: &proclaim_fsm::Machine,
    centre: &str,
) -> std::collections::BTreeMap<String, toml::Value> {
    if machine.name != centre {
        return Default::default();
    }
    machine
        .interface
        .params
        .iter()
        .map(|p| {
            let zero = match p.ty {
                proclaim_fsm::VarType::Bool => toml::Value::Boolean(false),
                proclaim_fsm::VarType::Float | proclaim_fsm::VarType::Double => {
                    toml::Value::Float(0.0)
                }
                _ => toml::Value::Integer(0),
            };
            (p.name.clone(), zero)
        })
        .collect()
}

/// The behaviour's manifest cut down to the `wanted` machines (only `centre` starting) and the
/// `needed` modules, with every file written as `place` says.
fn smallest_manifest(
    behaviour: &Behaviour,
    modules: &[Module],
    centre: &str,
    wanted: &[String],
    needed: &[&str],
    place: &dyn Fn(&str) -> String,
) -> Manifest {
    let is_needed = |m: &Module| needed.contains(&m.decl.name.as_str());
    let manifest = &behaviour.manifest;
    let needs = |kind: ModuleKind| modules.iter().any(|m| m.kind == kind && is_needed(m));
    let needs_named = |name: &str| modules.iter().any(|m| m.decl.name == name && is_needed(m));
    let mut smallest = Manifest {
        dictionary: manifest.dictionary.as_deref().map(place),
        machines: behaviour
            .machines
            .iter()
            .filter(|m| wanted.contains(&m.machine.name))
            .map(|m| MachineEntry {
                file: place(&m.file),
                start: m.machine.name == centre,
                name: None,
                priority: m.priority,
                params: placeholders(&m.machine, centre),
            })
            .collect(),
        theories: manifest
            .theories
            .iter()
            .zip(&behaviour.theories)
            .filter(|(_, t)| needs_named(&t.name))
            .map(|(entry, _)| TheoryEntry {
                file: place(&entry.file),
                mapping: entry.mapping.as_deref().map(place),
                ..entry.clone()
            })
            .collect(),
        sensors: manifest
            .sensors
            .iter()
            .filter(|s| needs(ModuleKind::Sensor(s.kind)))
            .map(|s| {
                let mut s = s.clone();
                if let Some(Simulator::Script(file)) = &mut s.simulator {
                    *file = place(file);
                }
                s
            })
            .collect(),
        impersonator: manifest
            .impersonator
            .as_ref()
            .filter(|_| needs(ModuleKind::Impersonator))
            .map(|i| ImpersonatorEntry {
                script: place(&i.script),
            }),
        modules: manifest.modules.clone(),
        // The suppressed types some machine it keeps posts (any other would be unknown there).
        suppress: manifest
            .suppress
            .iter()
            .filter(|(ty, _)| {
                modules
                    .iter()
                    .any(|m| wanted.contains(&m.decl.name) && m.decl.posts.contains(ty.get_ref()))
            })
            .map(|(ty, entry)| (ty.clone(), entry.clone()))
            .collect(),
        // The ranges of the types the machines it keeps read or bind (the others warn).
        ranges: manifest
            .ranges
            .iter()
            .filter(|(ty, _)| {
                let ty = ty.get_ref();
                modules.iter().any(|m| {
                    let d = &m.decl;
                    wanted.contains(&d.name)
                        && (d.reads.contains(ty) || d.waits_on.contains(ty) || d.posts.contains(ty))
                })
            })
            .map(|(ty, range)| (ty.clone(), range.clone()))
            .collect(),
        ..Manifest::default()
    };
    (smallest.prolog, smallest.programs) =
        crate::programs::needed_entries(manifest, &behaviour.programs, &needs_named, place);
    smallest
}

/// The machine and every machine it starts, transitively.
fn started_from(behaviour: &Behaviour, modules: &[Module], centre: &str) -> Vec<String> {
    let mut wanted: Vec<String> = vec![centre.to_string()];
    let mut next = 0;
    while next < wanted.len() {
        let name = wanted[next].clone();
        next += 1;
        if let Some(m) = modules.iter().find(|m| m.decl.name == name) {
            for ty in &m.decl.posts {
                if behaviour.machines.iter().any(|x| x.machine.name == *ty) && !wanted.contains(ty)
                {
                    wanted.push(ty.clone());
                }
            }
        }
    }
    wanted
}

/// The modules `wanted` needs: every expert, sensor wrapper or impersonator that answers a
/// label of what is needed, or posts what it reads (a theory's inputs), to a fixpoint.
fn serving<'m>(modules: &'m [Module], wanted: &'m [String]) -> Vec<&'m str> {
    let mut needed: Vec<&str> = wanted.iter().map(String::as_str).collect();
    loop {
        let before = needed.len();
        for m in modules {
            if matches!(m.kind, ModuleKind::Machine { .. } | ModuleKind::Outside)
                || needed.contains(&m.decl.name.as_str())
            {
                continue;
            }
            let serves = modules
                .iter()
                .filter(|n| needed.contains(&n.decl.name.as_str()))
                .any(|n| {
                    m.decl.answers.iter().any(|a| n.decl.waits_on.contains(a))
                        || m.decl
                            .posts
                            .iter()
                            .any(|p| p != proclaim_board::QUERY_TYPE && n.decl.reads.contains(p))
                });
            if serves {
                needed.push(&m.decl.name);
            }
        }
        if needed.len() == before {
            break;
        }
    }
    needed
}

fn quote(text: &str) -> String {
    let escaped = text.replace('\\', "\\\\").replace('"', "\\\"");
    format!("\"{escaped}\"")
}
