//! `proclaim prove`: answers queries, one line each.

use super::{algorithms, conclusions, inputs};
use crate::cli::AlgArg;
use crate::cli::{ProveArgs, ProveFormat};
use crate::failure::Failure;
use crate::load;
use proclaim_cdl::{Algorithm, Engine, Formula, SearchLimits, Session, Undecided};
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

/// The exit status when some answer was undecided within the search budget (the guide's tour of the commands).
const UNDECIDED_EXIT: u8 = 3;

/// A session with the `--budget` given (search steps per attack cycle), or the default.
fn session(theory: impl Into<Arc<proclaim_cdl::Theory>>, budget: Option<u64>) -> Session {
    let defaults = SearchLimits::default();
    let limits = SearchLimits {
        steps: budget.unwrap_or(defaults.steps),
        ..defaults
    };
    Session::with_limits(Engine::new(theory), limits)
}

fn exit(any_undecided: bool) -> ExitCode {
    if any_undecided {
        ExitCode::from(UNDECIDED_EXIT)
    } else {
        ExitCode::SUCCESS
    }
}

/// One answer: the algorithm, the query as shown, proved or not (or undecided).
type Answer = (Algorithm, String, Result<bool, Undecided>);

pub fn run(
    theory_name: &str,
    queries: &[String],
    alg: AlgArg,
    sets: &[String],
    json: bool,
    budget: Option<u64>,
) -> Result<ExitCode, Failure> {
    let (source, theory) = load::theory(theory_name)?;
    let formulas = read_queries(queries, &theory, &source)?;
    let mut session = session(theory, budget);
    let engine = session.engine().clone();
    inputs::apply(&mut session, engine.theory(), sets)?;
    if queries.is_empty() {
        let any_undecided =
            write_out(|out| conclusions::write_every(out, &mut session, &algorithms(alg), json))?;
        return Ok(exit(any_undecided));
    }
    let answers = answer(&mut session, &formulas, queries, alg);
    write_out(|out| write_answers(out, &answers, json))?;
    Ok(exit(answers.iter().any(|(_, _, a)| a.is_err())))
}

/// The answers to the queries, a line each or one JSON array.
fn write_answers(out: &mut Out, answers: &[Answer], json: bool) -> std::io::Result<()> {
    if json {
        out.write_all(b"[")?;
    }
    for (i, (alg, query, answer)) in answers.iter().enumerate() {
        if json {
            if i > 0 {
                out.write_all(b",")?;
            }
            let query = |out: &mut Out| conclusions::write_json_string(out, query);
            conclusions::write_json_item(out, *alg, query, answer)?;
        } else {
            let query = |out: &mut Out| out.write_all(query.as_bytes());
            conclusions::write_line(out, *alg, query, answer)?;
        }
    }
    if json {
        out.write_all(b"]\n")?;
    }
    Ok(())
}

/// Each query as a formula, or `None` for a literal whose atom the theory lacks: that is not
/// provable, so it is answered `-` with a warning, as SPINdle and Deimos answer it. Any other
/// bad query is an error.
fn read_queries(
    queries: &[String],
    theory: &proclaim_cdl::Theory,
    source: &load::Source,
) -> Result<Vec<Option<Formula>>, Failure> {
    let mut formulas = Vec::new();
    for q in queries {
        match inputs::formula(q, theory, source) {
            Ok(f) => formulas.push(Some(f)),
            Err(Failure::Invalid { rendered, .. }) if unknown_literal(q, theory) => {
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
    Ok(formulas)
}

/// Each query under each algorithm asked for, in the order written.
fn answer(
    session: &mut Session,
    formulas: &[Option<Formula>],
    queries: &[String],
    alg: AlgArg,
) -> Vec<Answer> {
    let engine = session.engine().clone();
    let mut answers = Vec::new();
    for (formula, query) in formulas.iter().zip(queries) {
        for alg in algorithms(alg) {
            match formula {
                Some(f) => {
                    let answer = session.decide_formula(alg, f);
                    answers.push((alg, f.show(engine.theory()), answer));
                }
                None => answers.push((alg, query.trim().to_string(), Ok(false))),
            }
        }
    }
    answers
}

/// Standard output through one buffer.
type Out = BufWriter<std::io::StdoutLock<'static>>;

/// Writes to standard output through one buffer: a line a conclusion is a million lines for a
/// large theory, and unbuffered each would be a system call. A closed pipe (`| head`) is the
/// reader's choice, not an error.
fn write_out<T: Default>(write: impl FnOnce(&mut Out) -> std::io::Result<T>) -> Result<T, Failure> {
    let mut out = BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
    match write(&mut out).and_then(|t| out.flush().map(|()| t)) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(T::default()),
        other => other.map_err(|error| Failure::Write {
            path: PathBuf::from("<stdout>"),
            error,
        }),
    }
}

/// Whether `query` is a plain literal (`a`, `~a`) naming an atom the theory does not have.
fn unknown_literal(query: &str, theory: &proclaim_cdl::Theory) -> bool {
    match proclaim_syntax::parse_query(query) {
        Ok(proclaim_syntax::Query::Lit(l)) => theory.atom(l.atom.text(query)).is_none(),
        _ => false,
    }
}

/// `proclaim prove`: SPINdle's output with `--format spindle`, else one line an answer.
pub fn command(args: ProveArgs) -> Result<ExitCode, Failure> {
    match args.format {
        ProveFormat::Spindle => spindle(&args.theory, &args.queries, &args.set, args.budget),
        ProveFormat::Text => run(
            &args.theory,
            &args.queries,
            args.alg,
            &args.set,
            args.json,
            args.budget,
        ),
    }
}

/// SPINdle's form of the conclusions: `+D`/`-D` for μ (definitely), `+d`/`-d` for β
/// (defeasibly, ambiguity blocking, SPINdle's default), for every literal of the theory in
/// atom order (or each literal queried), negation written `-a` as in `.dfl`.
pub fn spindle(
    theory_name: &str,
    queries: &[String],
    sets: &[String],
    budget: Option<u64>,
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
    let theory = Arc::new(theory);
    std::thread::scope(|scope| {
        // SPINdle's order needs only the theory: sorted on a second thread while this one
        // compiles and proves.
        let every_atom = queries.is_empty().then(|| {
            let theory = theory.clone();
            scope.spawn(move || conclusions::spindle_order(&theory))
        });
        let mut session = session(theory, budget);
        let engine = session.engine().clone();
        inputs::apply(&mut session, engine.theory(), sets)?;
        let any_undecided = match every_atom {
            Some(order) => {
                let order = || {
                    order
                        .join()
                        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
                };
                write_out(|out| conclusions::write_spindle_every(out, &mut session, order))?
            }
            None => write_out(|out| conclusions::write_spindle(out, &mut session, lits))?,
        };
        Ok(exit(any_undecided))
    })
}
