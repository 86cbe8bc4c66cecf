//! Walking an activity's statements, one walk for the runner and the checker: what each
//! statement does comes from [`Statement::kind`], what that does to the world from an
//! [`Effects`]. A walk stops where an effect asks it to (the runner sleeps there) and resumes
//! where it stopped, so the runner's sleeps need no second, asynchronous walk.

use proclaim_fsm::{Expr, ForLoop, Statement, StatementKind};
use std::slice;

/// A `for` loop stops after this many rounds in one activity (with a warning): a ringlet must
/// end.
pub const LOOP_LIMIT: u64 = 100_000;

/// What the statements of an activity do to whoever runs them.
pub trait Effects {
    /// What stops a walk before its end (the runner: a sleep to take before going on).
    type Pause;
    fn assign(&mut self, name: &str, value: &Expr);
    /// A call standing as a statement, performed; `Some` stops the walk after it.
    fn perform(&mut self, function: &str, arguments: &[Expr]) -> Option<Self::Pause>;
    /// An expression standing as a statement: evaluated for what evaluating it reads.
    fn evaluate(&mut self, expr: &Expr);
    /// Whether a `for` loop's condition holds now.
    fn holds(&mut self, condition: &Expr) -> bool;
    /// A `for` loop was stopped at [`LOOP_LIMIT`] rounds.
    fn loop_stopped(&mut self) {}
}

/// Where a walk through one statement is: the statement still to start, then what is left of
/// each block and loop it is inside, innermost last.
pub struct Walk<'s> {
    first: Option<&'s Statement>,
    frames: Vec<Frame<'s>>,
}

enum Frame<'s> {
    Statements(slice::Iter<'s, Statement>),
    Loop { parts: ForLoop<'s>, rounds: u64 },
}

impl<'s> Walk<'s> {
    pub fn new(statement: &'s Statement) -> Walk<'s> {
        Walk {
            first: Some(statement),
            frames: Vec::new(),
        }
    }

    /// Walks on from where the walk stopped: `None` at the end, or the pause an effect asked
    /// for.
    pub fn resume<E: Effects + ?Sized>(&mut self, effects: &mut E) -> Option<E::Pause> {
        while let Some(statement) = self.next_statement(effects) {
            match statement.kind() {
                StatementKind::Assign { name, value } => effects.assign(name, value),
                StatementKind::Call {
                    function,
                    arguments,
                } => {
                    if let Some(pause) = effects.perform(function, arguments) {
                        return Some(pause);
                    }
                }
                StatementKind::Evaluate(expr) => effects.evaluate(expr),
                StatementKind::Sequence(body) => self.frames.push(Frame::Statements(body.iter())),
                StatementKind::Loop(parts) => {
                    self.frames.push(Frame::Loop { parts, rounds: 0 });
                    if let Some(init) = parts.init {
                        self.first = Some(init);
                    }
                }
                StatementKind::Nothing => {}
            }
        }
        None
    }

    /// The next statement to run, deciding each loop's next round on the way.
    fn next_statement<E: Effects + ?Sized>(&mut self, effects: &mut E) -> Option<&'s Statement> {
        if let Some(first) = self.first.take() {
            return Some(first);
        }
        loop {
            match self.frames.last_mut()? {
                Frame::Statements(rest) => match rest.next() {
                    Some(statement) => return Some(statement),
                    None => {
                        self.frames.pop();
                    }
                },
                Frame::Loop { parts, rounds } => {
                    let parts = *parts;
                    if !parts.condition.is_none_or(|c| effects.holds(c)) {
                        self.frames.pop();
                        continue;
                    }
                    if *rounds == LOOP_LIMIT {
                        effects.loop_stopped();
                        self.frames.pop();
                        continue;
                    }
                    *rounds += 1;
                    // The step runs once the body is done.
                    let step = parts.step.map(slice::from_ref).unwrap_or_default();
                    self.frames.push(Frame::Statements(step.iter()));
                    return Some(parts.body);
                }
            }
        }
    }
}

/// Walks a statement to its end, for effects that never pause.
pub fn walk_to_end<E: Effects<Pause = std::convert::Infallible> + ?Sized>(
    statement: &Statement,
    effects: &mut E,
) {
    let _ = Walk::new(statement).resume(effects);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::code::parse_statements;

    /// Records what a walk did, pausing at every call named `pause`; every loop condition
    /// holds for the first three asks.
    #[derive(Default)]
    struct Log {
        done: Vec<String>,
        conditions_asked: u32,
    }

    impl Effects for Log {
        type Pause = ();
        fn assign(&mut self, name: &str, value: &Expr) {
            self.done.push(format!("{name} = {value}"));
        }
        fn perform(&mut self, function: &str, _: &[Expr]) -> Option<()> {
            self.done.push(format!("{function}()"));
            (function == "pause").then_some(())
        }
        fn evaluate(&mut self, expr: &Expr) {
            self.done.push(format!("evaluate {expr}"));
        }
        fn holds(&mut self, _: &Expr) -> bool {
            self.conditions_asked += 1;
            self.conditions_asked <= 3
        }
        fn loop_stopped(&mut self) {
            self.done.push("stopped".into());
        }
    }

    fn check(code: &str, expect: &[&str]) {
        let statements = parse_statements(code).expect("the test's code reads");
        let mut log = Log::default();
        for statement in &statements {
            let mut walk = Walk::new(statement);
            while walk.resume(&mut log).is_some() {
                log.done.push("-- paused".into());
            }
        }
        assert_eq!(log.done, expect, "walking {code}");
    }

    #[test]
    fn statements_run_in_order_and_declarations_without_values_do_nothing() {
        check("int x; x = 1; f(); x;", &["x = 1", "f()", "evaluate x"]);
    }

    #[test]
    fn a_loop_runs_init_then_condition_body_and_step_each_round() {
        check(
            "for (i = 0; i < 3; i = i + 1) { g(); }",
            &[
                "i = 0",
                "g()",
                "i = i + 1",
                "g()",
                "i = i + 1",
                "g()",
                "i = i + 1",
            ],
        );
    }

    #[test]
    fn a_pause_stops_the_walk_and_resuming_goes_on_inside_the_loop() {
        check(
            "for (i = 0; i < 3; i = i + 1) { pause(); } done();",
            &[
                "i = 0",
                "pause()",
                "-- paused",
                "i = i + 1",
                "pause()",
                "-- paused",
                "i = i + 1",
                "pause()",
                "-- paused",
                "i = i + 1",
                "done()",
            ],
        );
    }

    #[test]
    fn a_loop_that_never_ends_is_stopped_at_the_limit() {
        check("for (;;) { } after();", &["stopped", "after()"]);
    }
}
