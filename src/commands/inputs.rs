//! `--set atom=value` options, and formulas given on the command line, checked against a theory.

use crate::failure::Failure;
use crate::load::{color, Source};
use proclaim_cdl::{Formula, Session, Theory};
use proclaim_syntax::render;

/// Applies every `--set`; an unknown atom, a bad value or a contradiction with the axioms is an
/// error that names it.
pub fn apply(session: &mut Session, theory: &Theory, sets: &[String]) -> Result<(), Failure> {
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
