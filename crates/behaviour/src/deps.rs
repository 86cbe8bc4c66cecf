//! The module-dependency diagram of the seed paper (Section III, Figure 4), and the smallest
//! behaviour that runs one machine with exactly the modules it needs (the seed's generated test
//! script).

use crate::load::Behaviour;
use crate::manifest::{ImpersonatorEntry, MachineEntry, Manifest, Simulator, TheoryEntry};
use crate::modules::{Module, ModuleKind};
use std::fmt::Write;

/// One module at the centre: the experts it queries above it (green arrows, blocking: they
/// proclaim its labels), the modules that listen to its postings below it (black arrows,
/// non-blocking), and a red **unknown** for a label nobody answers or a posting nobody hears.
pub fn module_diagram(modules: &[Module], centre: &str) -> Result<String, String> {
    let Some(me) = modules.iter().find(|m| m.decl.name == centre) else {
        return Err(format!(
            "no module `{centre}`; the behaviour has {}",
            names(modules)
        ));
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
    let experts_missing = experts_above(modules, me, &mut above, &mut out);
    let listeners_missing = listeners_below(modules, me, &above, &mut below, &mut out);
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

/// The experts answering what `me` waits on, linked green above it (a label nobody answers
/// from `unknown`, red); whether any was missing.
fn experts_above(
    modules: &[Module],
    me: &Module,
    above: &mut Vec<String>,
    out: &mut String,
) -> bool {
    let centre = me.decl.name.as_str();
    let mut unknown = false;
    for atom in &me.decl.waits_on {
        let experts: Vec<&Module> = modules
            .iter()
            .filter(|m| m.decl.name != centre && m.decl.answers.contains(atom))
            .collect();
        if experts.is_empty() {
            unknown = true;
            let _ = writeln!(
                out,
                "  unknown -> {} [color=red, fontcolor=red, label={}];",
                quote(centre),
                quote(atom)
            );
        }
        for e in experts {
            if !above.contains(&e.decl.name) {
                above.push(e.decl.name.clone());
            }
            let _ = writeln!(
                out,
                "  {} -> {} [color=green4, label={}];",
                quote(&e.decl.name),
                quote(centre),
                quote(atom)
            );
        }
    }
    unknown
}

/// The modules hearing what `me` posts, linked below it (a posting nobody hears to `unknown`,
/// red); whether any was missing.
fn listeners_below(
    modules: &[Module],
    me: &Module,
    above: &[String],
    below: &mut Vec<String>,
    out: &mut String,
) -> bool {
    let centre = me.decl.name.as_str();
    let mut unknown = false;
    for ty in me
        .decl
        .posts
        .iter()
        .filter(|t| **t != proclaim_runner::running_type(centre))
    {
        let listeners: Vec<&Module> = modules
            .iter()
            .filter(|m| {
                m.decl.name != centre && (m.decl.reads.contains(ty) || m.decl.waits_on.contains(ty))
            })
            .collect();
        if listeners.is_empty() {
            unknown = true;
            let _ = writeln!(
                out,
                "  {} -> unknown [color=red, fontcolor=red, label={}];",
                quote(centre),
                quote(ty)
            );
        }
        for l in listeners {
            if !below.contains(&l.decl.name) && !above.contains(&l.decl.name) {
                below.push(l.decl.name.clone());
            }
            let _ = writeln!(
                out,
                "  {} -> {} [label={}];",
                quote(centre),
                quote(&l.decl.name),
                quote(ty)
            );
        }
    }
    unknown
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
            if experts.is_empty() {
                let _ = writeln!(
                    out,
                    "  unknown -> {} [color=red, fontcolor=red, label={}];",
                    quote(&m.decl.name),
                    quote(atom)
                );
            }
            for e in experts {
                let _ = writeln!(
                    out,
                    "  {} -> {} [color=green4, label={}];",
                    quote(&e.decl.name),
                    quote(&m.decl.name),
                    quote(atom)
                );
            }
        }
        for ty in m.decl.posts.iter().filter(|t| !m.decl.answers.contains(t)) {
            for l in modules
                .iter()
                .filter(|l| l.decl.name != m.decl.name && l.decl.reads.contains(ty))
            {
                let _ = writeln!(
                    out,
                    "  {} -> {} [label={}];",
                    quote(&m.decl.name),
                    quote(&l.decl.name),
                    quote(ty)
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
) -> Result<String, String> {
    if !behaviour.machines.iter().any(|m| m.machine.name == centre) {
        return Err(format!(
            "no machine `{centre}`; the behaviour's machines are {}",
            behaviour
                .machines
                .iter()
                .map(|m| m.machine.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let wanted = started_from(behaviour, modules, centre);
    let needed = serving(modules, &wanted);
    let smallest = smallest_manifest(behaviour, modules, centre, &wanted, &needed, place);
    Ok(smallest.to_toml(&format!(
        "The smallest behaviour that runs {centre}: written by `proclaim deps --launch {centre}`."
    )))
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
    let smallest = Manifest {
        dictionary: manifest.dictionary.as_deref().map(place),
        machines: behaviour
            .machines
            .iter()
            .filter(|m| wanted.contains(&m.machine.name))
            .map(|m| MachineEntry {
                file: place(&m.file),
                start: m.machine.name == centre,
                name: None,
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
        ..Manifest::default()
    };
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

fn names(modules: &[Module]) -> String {
    modules
        .iter()
        .map(|m| m.decl.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

fn quote(text: &str) -> String {
    let escaped = text.replace('\\', "\\\\").replace('"', "\\\"");
    format!("\"{escaped}\"")
}
