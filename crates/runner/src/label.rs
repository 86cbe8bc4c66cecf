//! Proving a label: names standing as conditions that are no variable are asked of their
//! expert by the query protocol; everything else (variables, whiteboard values, arithmetic,
//! comparisons, the time tests) is computed on the spot, with no round trip.

use crate::eval::Env;
use crate::event::Answerer;
use crate::feed::QueryHook;
use crate::variables::Scope;
use proclaim_board::QueryOutcome;
use proclaim_fsm::{BinOp, Expr, Label, UnOp};
use proclaim_lower::Evaluate;
use std::future::Future;
use std::pin::Pin;
use std::time::Duration;

/// Where a label is proved: the names it reads, who asks, how long to wait for an answer,
/// and the answers gathered for the trace.
pub(crate) struct Context<'a> {
    pub env: Env<'a>,
    pub module: &'a str,
    pub answer_timeout: Duration,
    pub answered: &'a mut Vec<(String, bool, Answerer)>,
    /// Under a feed: told before each query.
    pub hook: Option<&'a QueryHook>,
    /// Queries this ringlet asked so far.
    pub queries: &'a mut usize,
}

/// Proves a label; `&&` and `||` stop at the first answer that decides them, as the original
/// interpreter asked its experts one label at a time.
pub(crate) fn prove<'a>(
    label: &'a Label,
    cx: &'a mut Context<'_>,
) -> Pin<Box<dyn Future<Output = bool> + Send + 'a>> {
    Box::pin(async move {
        match label {
            Expr::Name(atom) if !cx.env.scope().is_variable(atom) => ask(atom, cx).await,
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => !prove(operand, cx).await,
            Expr::Binary {
                op: BinOp::And,
                left,
                right,
            } => prove(left, cx).await && prove(right, cx).await,
            Expr::Binary {
                op: BinOp::Or,
                left,
                right,
            } => prove(left, cx).await || prove(right, cx).await,
            other => cx.env.truth(other),
        }
    })
}

async fn ask(atom: &str, cx: &mut Context<'_>) -> bool {
    let board = cx.env.board;
    if let Some(hook) = cx.hook {
        // Only a query an expert answers is posted (and recorded); a replay counts those.
        if !board.registry().answerers(atom).is_empty() {
            hook.feed
                .lock()
                .before_query(hook.ringlet, *cx.queries, board);
            *cx.queries += 1;
        }
    }
    let outcome = board.query(cx.module, atom, cx.answer_timeout).await;
    if matches!(outcome, QueryOutcome::Answered { .. }) {
        // The expert's answer is a posting: those who hear of postings (the trace's note of
        // the script's, a monitor) hear of it before the ringlet goes on, whichever task the
        // answer woke first.
        tokio::task::yield_now().await;
    }
    let (value, by) = match &outcome {
        QueryOutcome::Answered { value, by, .. } => (*value, Answerer::Expert(by.to_string())),
        QueryOutcome::TimedOut => (false, Answerer::TimedOut),
        // No expert, but a module posts it as a state (`PlacerIsRunning`, a sensor value): its
        // current value is the answer.
        QueryOutcome::NoExpert => match cx.env.latest(atom) {
            Some(m) => (m.value.truthy(), Answerer::Posted(m.module.to_string())),
            None => (false, Answerer::NoExpert),
        },
    };
    // Within a ringlet an atom reads as it read first (`seen.rs`).
    let (value, by) = cx.env.seen.answer(board, atom, value, by);
    cx.answered.push((atom.to_string(), value, by));
    value
}

/// The message types a label reads: a post of any of them may change its answer. Variables
/// of the machine and globals are not messages; externs are.
pub(crate) fn dependencies(label: &Label, scope: Scope<'_>, out: &mut Vec<String>) {
    label.visit_names(&mut |name, _| {
        if scope.is_message(name) && !out.iter().any(|o| o == name) {
            out.push(name.to_string());
        }
    });
    // A team aggregate reads the type holding the whole team's values, not its argument.
    for (function, arguments) in label.calls() {
        if let Some(team) = crate::team::aggregated_type(function, arguments) {
            if !out.contains(&team) {
                out.push(team);
            }
        }
    }
}

/// Whether a label reads a global (so a change of globals may change its answer).
pub(crate) fn reads_globals(label: &Label, scope: Scope<'_>) -> bool {
    let mut found = false;
    label.visit_names(&mut |name, _| {
        found |= !scope.locals.contains(name) && scope.shared.is_global(name);
    });
    found
}

/// How long the label's time tests (`timeout`, `after`, `after_ms`) still need, the soonest
/// first; none when it has none still to come.
pub(crate) fn next_time_test(label: &Label, env: &mut Env<'_>) -> Option<Duration> {
    label
        .time_tests()
        .into_iter()
        .filter_map(|(f, arguments, clock)| {
            let due = env.time_limit(f, arguments).flatten()?;
            let elapsed = env.clocks.elapsed(clock);
            (due > elapsed).then(|| due - elapsed)
        })
        .min()
}
