//! `proclaim explain`: why a literal is proved or not, as an indented tree (or JSON).

use super::{algorithms, inputs};
use crate::cli::AlgArg;
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::{Engine, Explanation, Formula, Session};
use std::process::ExitCode;

pub fn run(
    theory_name: &str,
    query: &str,
    alg: AlgArg,
    sets: &[String],
    depth: usize,
    json: bool,
) -> Result<ExitCode, Failure> {
    let (source, theory) = load::theory(theory_name)?;
    let Formula::Lit(lit) = inputs::formula(query, &theory, &source)? else {
        return Err(Failure::Argument(format!(
            "explain takes one literal (`a` or `~a`), not `{query}`"
        )));
    };
    let mut session = Session::new(Engine::new(theory));
    let engine = session.engine().clone();
    inputs::apply(&mut session, engine.theory(), sets)?;
    let explanations: Vec<Explanation> = algorithms(alg)
        .into_iter()
        .map(|alg| session.explain(alg, lit, depth))
        .collect();
    if json {
        let list: Vec<_> = explanations.iter().map(to_json).collect();
        println!("{}", serde_json::Value::Array(list));
    } else {
        for explanation in explanations {
            print!("{explanation}");
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn to_json(e: &Explanation) -> serde_json::Value {
    serde_json::json!({
        "text": e.text,
        "because": e.children.iter().map(to_json).collect::<Vec<_>>(),
    })
}
