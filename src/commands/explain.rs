//! `proclaim explain`: why a literal is proved or not, as an indented tree (or JSON).

use super::{algorithms, inputs};
use crate::cli::AlgArg;
use crate::cli::ExplainArgs;
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::{About, Engine, Explanation, Formula, Session};
use std::process::ExitCode;

/// `proclaim explain`.
pub fn command(args: ExplainArgs) -> Result<ExitCode, Failure> {
    run(
        &args.theory,
        &args.query,
        args.alg,
        &args.set,
        args.depth,
        args.json,
    )
}

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

/// A node: its text, what it is about (`goal` with algorithm, literal and whether proved; or
/// `rule` with its role), and the nodes that explain it.
fn to_json(e: &Explanation) -> serde_json::Value {
    let mut node = serde_json::json!({
        "text": e.text,
        "because": e.children.iter().map(to_json).collect::<Vec<_>>(),
    });
    match &e.about {
        About::Note => {}
        About::Goal {
            algorithm,
            literal,
            proved,
        } => {
            node["goal"] = serde_json::json!({
                "algorithm": algorithm.to_string(), "literal": literal, "proved": proved,
            });
        }
        About::Rule { rule, role, by } => {
            node["rule"] = serde_json::json!(rule);
            node["role"] = serde_json::json!(role);
            if let Some(by) = by {
                node["beaten_by"] = serde_json::json!(by);
            }
        }
    }
    node
}
