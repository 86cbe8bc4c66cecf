//! `--set atom=value` options, and formulas given on the command line, checked against a theory.

use crate::failure::Failure;
use crate::load::{color, Source};
use proclaim_cdl::{Formula, Session, Theory};
use proclaim_syntax::render;

/// Applies every `--set`; an unknown atom, an atom that is not a declared input (when the theory
/// declares its inputs), a bad value, two atoms of one input group set true, or a contradiction
/// with the axioms is an error that names it. One of a group set true makes the others false.
pub fn apply(session: &mut Session, theory: &Theory, sets: &[String]) -> Result<(), Failure> {
    let mut set_true = Vec::new();
    for set in sets {
        let Some((name, value)) = set.split_once('=') else {
            return Err(Failure::Argument(format!(
                "--set {set}: expected ATOM=VALUE, such as --set doorOpen=true"
            )));
        };
        let name = name.trim();
        let atom = theory.atom(name).ok_or_else(|| {
            let inputs: Vec<&str> = theory.input_atoms().map(|a| theory.atom_name(a)).collect();
            Failure::Argument(format!(
                "--set {set}: the theory has no atom `{name}`{}",
                if inputs.is_empty() {
                    String::new()
                } else {
                    format!(" (its inputs are {})", inputs.join(", "))
                }
            ))
        })?;
        let declared: Vec<_> = theory.input_atoms().collect();
        if !declared.is_empty() && !declared.contains(&atom) {
            let names: Vec<&str> = declared.iter().map(|&a| theory.atom_name(a)).collect();
            return Err(Failure::Argument(format!(
                "--set {set}: `{name}` is not an input of the theory, so it is concluded, not set (its inputs are {})",
                names.join(", ")
            )));
        }
        let value = match value.trim() {
            "true" | "1" | "yes" => Some(true),
            "false" | "0" | "no" => Some(false),
            "unknown" | "?" => None,
            other => {
                return Err(Failure::Argument(format!(
                    "--set {set}: `{other}` is not a value; use true, false or unknown"
                )))
            }
        };
        if value == Some(true) {
            // Exactly one of a group is true: two set true is a contradiction, not a choice.
            let group = theory
                .inputs()
                .iter()
                .find(|g| g.atoms.len() > 1 && g.atoms.contains(&atom));
            if let Some(other) = group.and_then(|g| {
                g.atoms
                    .iter()
                    .find(|&&o| o != atom && set_true.contains(&o))
            }) {
                return Err(Failure::Argument(format!(
                    "--set {set}: `{name}` and `{}` are one input group, of which exactly one is true",
                    theory.atom_name(*other)
                )));
            }
            set_true.push(atom);
        }
        session
            .set_input(atom, value)
            .map_err(|conflict| Failure::Argument(format!("--set {set}: {conflict}")))?;
    }
    Ok(())
}

/// Parses a query against the theory, rendering any error against the query text.
pub fn formula(query: &str, theory: &Theory, source: &Source) -> Result<Formula, Failure> {
    Formula::parse(query, theory).map_err(|diagnostics| Failure::Invalid {
        what: "the query",
        rendered: render(
            &diagnostics,
            &format!("query (for {})", source.name),
            query,
            color(),
        ),
        errors: diagnostics.len(),
    })
}
