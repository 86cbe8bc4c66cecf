//! A behaviour as one Graphviz diagram: each machine in its own box, drawn as `proclaim_fsm`
//! draws a machine, and the sub-machines a state starts linked to their boxes.

use proclaim_fsm::dot::{body, header, quote};
use proclaim_fsm::Machine;
use std::fmt::Write;

/// A machine's name with what a start gives it and how it can end: `Dive(side: int) → landed`.
fn signature(machine: &Machine) -> String {
    let interface = &machine.interface;
    let mut out = machine.name.clone();
    if !interface.params.is_empty() {
        let params: Vec<String> = interface
            .params
            .iter()
            .map(|p| format!("{}: {}", p.name, p.ty.name()))
            .collect();
        out += &format!("({})", params.join(", "));
    }
    if !interface.outcomes.is_empty() {
        out += &format!(" → {}", interface.outcome_names().join(" | "));
    }
    out
}

/// DOT text for the machines of a behaviour, each in its own box (sub-machines, those not
/// started at first, dashed), a state that starts a sub-machine linked to that machine's box.
/// A machine started that the behaviour does not have is drawn red.
pub fn behaviour_to_dot(name: &str, machines: &[(&Machine, bool)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "digraph {} {{", quote(name));
    out.push_str("  compound=true;\n");
    header(&mut out);
    let mut links = Vec::new();
    for (i, (machine, start)) in machines.iter().enumerate() {
        let _ = writeln!(out, "  subgraph cluster_{i} {{");
        let _ = writeln!(
            out,
            "    label={}; fontname=\"Helvetica\"; style={};",
            quote(&signature(machine)),
            if *start { "solid" } else { "dashed" }
        );
        let started = body(&mut out, machine, &format!("m{i}_"), "    ");
        out.push_str("  }\n");
        links.extend(started);
    }
    let mut missing: Vec<&str> = Vec::new();
    for (from, target) in &links {
        match machines.iter().position(|(m, _)| m.name == *target) {
            Some(k) => {
                let params: Vec<&str> = machines[k]
                    .0
                    .interface
                    .params
                    .iter()
                    .map(|p| p.name.as_str())
                    .collect();
                let label = match params.as_slice() {
                    [] => "starts".to_string(),
                    given => format!("starts ({})", given.join(", ")),
                };
                let _ = writeln!(
                    out,
                    "  {from} -> m{k}_start [lhead=cluster_{k}, style=dashed, arrowhead=odot, label={}];",
                    quote(&label)
                );
            }
            None => {
                if !missing.contains(&target.as_str()) {
                    let _ = writeln!(
                        out,
                        "  {} [shape=component, style=dashed, color=red, fontcolor=red];",
                        quote(target)
                    );
                    missing.push(target);
                }
                let _ = writeln!(
                    out,
                    "  {from} -> {} [style=dashed, arrowhead=odot, color=red, label=\"starts (unknown)\"];",
                    quote(target)
                );
            }
        }
    }
    out.push_str("}\n");
    out
}
