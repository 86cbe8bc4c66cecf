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
    let formulas = queries
        .iter()
        .map(|q| inputs::formula(q, &theory, &source))
        .collect::<Result<Vec<_>, _>>()?;
    let mut session = Session::new(Engine::new(theory));
    let engine = session.engine().clone();
    inputs::apply(&mut session, engine.theory(), sets)?;
    let mut answers = Vec::new();
    for formula in &formulas {
        for alg in algorithms(alg) {
            let proved = session.prove_formula(alg, formula);
            answers.push((alg, formula.show(engine.theory()), proved));
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
