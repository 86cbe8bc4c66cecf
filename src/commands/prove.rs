//! `proclaim prove`: answers queries, one line each.

use super::{algorithms, inputs};
use crate::cli::AlgArg;
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::{Engine, Session};
use std::process::ExitCode;

pub fn run(
    theory_name: &str,
    queries: &[String],
    alg: AlgArg,
    sets: &[String],
    json: bool,
) -> Result<ExitCode, Failure> {
    let (source, theory) = load::theory(theory_name)?;
    // A literal whose atom the theory lacks is not provable: answered `-`, with a warning, as
    // SPINdle and Deimos answer it. Any other bad query is an error.
    let mut formulas = Vec::new();
    for q in queries {
        match inputs::formula(q, &theory, &source) {
            Ok(f) => formulas.push(Some(f)),
            Err(Failure::Invalid { rendered, .. }) if unknown_literal(q, &theory) => {
                // The same words and caret, as a warning: the answer is `-`, not a failure.
                eprint!("{}", rendered.replacen("error", "warning", 1));
                eprintln!(
                    "warning: `{}` is not provable: the theory never mentions it",
                    q.trim()
                );
                formulas.push(None);
            }
            Err(failure) => return Err(failure),
        }
    }
    let mut session = Session::new(Engine::new(theory));
    let engine = session.engine().clone();
    inputs::apply(&mut session, engine.theory(), sets)?;
    let mut answers = Vec::new();
    for (formula, query) in formulas.iter().zip(queries) {
        for alg in algorithms(alg) {
            match formula {
                Some(f) => {
                    let proved = session.prove_formula(alg, f);
                    answers.push((alg, f.show(engine.theory()), proved));
                }
                None => answers.push((alg, query.trim().to_string(), false)),
            }
        }
    }
    // No query: every conclusion of each algorithm asked for.
    if queries.is_empty() {
        for alg in algorithms(alg) {
            for lit in session.conclusions(alg) {
                answers.push((alg, engine.theory().show(lit).to_string(), true));
            }
        }
    }
    if json {
        let list: Vec<_> = answers
            .iter()
            .map(|(alg, query, proved)| {
                serde_json::json!({"algorithm": alg.name(), "query": query, "proved": proved})
            })
            .collect();
        println!("{}", serde_json::Value::Array(list));
    } else {
        for (alg, query, proved) in answers {
            println!("{}{alg} {query}", if proved { '+' } else { '-' });
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Whether `query` is a plain literal (`a`, `~a`) naming an atom the theory does not have.
fn unknown_literal(query: &str, theory: &proclaim_cdl::Theory) -> bool {
    match proclaim_syntax::parse_query(query) {
        Ok(proclaim_syntax::Query::Lit(l)) => theory.atom(l.atom.text(query)).is_none(),
        _ => false,
    }
}

/// SPINdle's form of the conclusions: `+D`/`-D` for μ (definitely), `+d`/`-d` for β
/// (defeasibly, ambiguity blocking, SPINdle's default), for every literal of the theory in
/// atom order (or each literal queried), negation written `-a` as in `.dfl`.
pub fn spindle(
    theory_name: &str,
    queries: &[String],
    sets: &[String],
) -> Result<ExitCode, Failure> {
    let (source, theory) = load::theory(theory_name)?;
    let mut lits = Vec::new();
    for q in queries {
        match inputs::formula(q, &theory, &source)? {
            proclaim_cdl::Formula::Lit(l) => lits.push(l),
            _ => {
                return Err(Failure::Argument(format!(
                    "{q}: --format spindle answers literals only"
                )))
            }
        }
    }
    if queries.is_empty() {
        let mut atoms: Vec<u32> = (0..theory.atom_count() as u32).collect();
        atoms.sort_by_key(|&a| theory.atom_name(proclaim_cdl::Atom(a)).to_string());
        for a in atoms {
            let atom = proclaim_cdl::Atom(a);
            lits.push(proclaim_cdl::Lit::new(atom, false));
            lits.push(proclaim_cdl::Lit::new(atom, true));
        }
    }
    let mut session = Session::new(Engine::new(theory));
    let engine = session.engine().clone();
    inputs::apply(&mut session, engine.theory(), sets)?;
    let theory = engine.theory();
    for lit in lits {
        let name = theory.atom_name(lit.atom());
        let shown = if lit.is_negated() {
            format!("-{name}")
        } else {
            name.to_string()
        };
        for (tag, alg) in [
            ('D', proclaim_cdl::Algorithm::Mu),
            ('d', proclaim_cdl::Algorithm::Beta),
        ] {
            let sign = if session.prove(alg, lit) { '+' } else { '-' };
            println!("{sign}{tag} {shown}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
