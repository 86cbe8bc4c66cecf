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
    if let Some(round) = args.round {
        return from_run(&args, round);
    }
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

/// `explain BEHAVIOUR LABEL --recording FILE --round N` (or `--trace FILE`): the answer the
/// run gave, explained from the inputs its theory held when the label was asked. A replay that
/// answers otherwise than the run is a failure (the run is of another behaviour, or of a
/// changed one, or a trace's text lost a value).
fn from_run(args: &ExplainArgs, round: u64) -> Result<ExitCode, Failure> {
    let behaviour = crate::behaviours::load_behaviour(&args.theory)?;
    let (path, recording) = read_run(args, &behaviour)?;
    let path = path.as_path();
    if behaviour
        .machines
        .iter()
        .any(|m| m.machine.name == args.query)
    {
        let tried = proclaim_behaviour::tried(&behaviour, &recording, &args.query, round)
            .map_err(|e| Failure::Argument(format!("{}: {e}", path.display())))?;
        if args.json {
            println!("{}", serde_json::to_string(&tried).unwrap_or_default());
        } else {
            print!("{tried}");
        }
        return Ok(ExitCode::SUCCESS);
    }
    let mut held = proclaim_behaviour::held_at(
        &behaviour,
        &recording,
        &args.query,
        round,
        args.machine.as_deref(),
    )
    .map_err(|e| Failure::Argument(format!("{}: {e}", path.display())))?;
    let explanation = held.explain(args.depth);
    let asked = &held.asked;
    if asked.recorded.is_some_and(|r| r != asked.replayed) {
        return Err(Failure::Argument(format!(
            "{}: `{}` was answered {} in round {}, but the theory `{}` answers {} from the recorded inputs: the {} is not of this behaviour as it is now{}",
            path.display(),
            asked.label,
            asked.recorded.unwrap_or_default(),
            round,
            asked.theory,
            asked.replayed,
            if args.trace.is_some() { "trace" } else { "recording" },
            if args.trace.is_some() {
                ", or a posting's value was lost as text (a recording, `run --record`, keeps it)"
            } else {
                ""
            },
        )));
    }
    print_held(&held, &explanation, args.json);
    Ok(ExitCode::SUCCESS)
}

/// The run `--recording` or `--trace` names, as a recording, and its path.
fn read_run(
    args: &ExplainArgs,
    behaviour: &proclaim_behaviour::Behaviour,
) -> Result<(std::path::PathBuf, proclaim_behaviour::Recording), Failure> {
    let path = args.recording.as_ref().or(args.trace.as_ref());
    let Some(path) = path else {
        return Err(Failure::Argument(
            "--round explains a run: give --recording FILE or --trace FILE".into(),
        ));
    };
    let text = crate::bounded::read_text(path, "a recording or a trace")?;
    let recording = if args.trace.is_some() {
        let events = proclaim_behaviour::read_trace(&text)
            .map_err(|e| Failure::Argument(format!("{}: not a trace: {e}", path.display())))?;
        let machines: Vec<&str> = behaviour
            .machines
            .iter()
            .map(|m| m.machine.name.as_str())
            .collect();
        proclaim_behaviour::Recording::from_trace(events, &machines)
    } else {
        proclaim_behaviour::read_recording(&text)
            .map_err(|e| Failure::Argument(format!("{}: not a recording: {e}", path.display())))?
    };
    Ok((path.clone(), recording))
}

/// A recorded answer explained: what was asked, the theory's inputs then, and the tree (or
/// all of it as JSON).
fn print_held(held: &proclaim_behaviour::Held, explanation: &Explanation, json: bool) {
    let asked = &held.asked;
    if json {
        let inputs = held.inputs().into_iter();
        let inputs: Vec<_> = inputs
            .map(|(ty, v)| serde_json::json!({"type": ty, "value": v}))
            .collect();
        let json = serde_json::json!({
            "round": asked.round, "machine": asked.machine, "label": asked.label,
            "theory": asked.theory, "answer": asked.replayed, "inputs": inputs,
            "explanation": to_json(explanation),
        });
        println!("{json}");
        return;
    }
    print!("{}", held_text(held, explanation));
}

/// A recorded answer as a person reads it: what was asked, the theory's inputs then, the tree.
fn held_text(held: &proclaim_behaviour::Held, explanation: &Explanation) -> String {
    let asked = &held.asked;
    let inputs: Vec<String> = held
        .inputs()
        .into_iter()
        .map(|(ty, v)| match v {
            Some(v) => format!("{ty} = {v}"),
            None => format!("{ty} unknown"),
        })
        .collect();
    let inputs = if inputs.is_empty() {
        "none".to_string()
    } else {
        inputs.join(", ")
    };
    format!(
        "round {}: {} asked `{}`; the theory `{}` answered {}, its inputs then: {inputs}\n{explanation}",
        asked.round, asked.machine, asked.label, asked.theory, asked.replayed
    )
}

/// Why `asked.machine` read `asked.label` as it did in `asked.round` of a run whose events so
/// far are `events` (the monitor's click on an answer): the text `explain --trace` prints, or
/// why there is none.
pub fn answer_in_events(
    behaviour: &proclaim_behaviour::Behaviour,
    events: &[proclaim_runtime::Event],
    asked: &proclaim_monitor::AnswerAsked,
) -> Result<String, String> {
    let machines: Vec<&str> = behaviour
        .machines
        .iter()
        .map(|m| m.machine.name.as_str())
        .collect();
    let recording = proclaim_behaviour::Recording::from_trace(events.to_vec(), &machines);
    let (label, round) = (asked.label.as_str(), asked.round);
    let machine = Some(asked.machine.as_str());
    let mut held = proclaim_behaviour::held_at(behaviour, &recording, label, round, machine)
        .map_err(|e| e.to_string())?;
    let explanation = held.explain(1);
    let answered = &held.asked;
    if answered.recorded.is_some_and(|r| r != answered.replayed) {
        return Err(format!(
            "`{label}` was answered {} in round {round}, but the theory `{}` answers {} from the inputs the run's postings give (the behaviour changed, or a posting's value was lost as text)",
            !answered.replayed, answered.theory, answered.replayed
        ));
    }
    Ok(held_text(&held, &explanation))
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
