//! Evaluating expressions of the activity language over variables and whiteboard values, with
//! C's arithmetic: whole numbers stay whole (`7 / 2` is 3), a fraction anywhere makes the
//! result a fraction, and (as gufsm had it) dividing by zero gives the largest whole number
//! instead of stopping the robot.

use crate::seen::Seen;
use crate::variables::{Locals, Scope, Shared};
use proclaim_board::{Value, Whiteboard};
use proclaim_fsm::{Expr, TIME_TESTS};
use proclaim_lower::{arith, Evaluate};
use std::time::Duration;
use tokio::time::Instant;

/// What names mean where an expression runs.
pub(crate) struct Env<'a> {
    pub board: &'a Whiteboard,
    /// How the board reads in this part of the ringlet (live, or its snapshot).
    pub seen: &'a Seen,
    pub locals: &'a Locals,
    pub shared: &'a Shared,
    /// What the time tests (`timeout`, `after`, `after_ms`) count from.
    pub clocks: Clocks<'a>,
}

/// How long the machine has been in its state and in each composite around it: a time test
/// reads the clock lowering gave it ([`Expr::Call`]'s `clock`).
#[derive(Clone, Copy)]
pub(crate) struct Clocks<'a> {
    pub now: Instant,
    /// The arrival in its current state.
    pub entered_at: Instant,
    /// Each composite's entry (`None` until the move into it arrives: then its state's).
    pub composites: &'a [Option<Instant>],
}

impl Clocks<'_> {
    /// How long since `clock` started.
    pub fn elapsed(&self, clock: Option<usize>) -> Duration {
        let entered = clock
            .and_then(|c| self.composites.get(c).copied().flatten())
            .unwrap_or(self.entered_at);
        self.now.saturating_duration_since(entered)
    }
}

impl Env<'_> {
    pub fn scope(&self) -> Scope<'_> {
        Scope {
            locals: self.locals,
            shared: self.shared,
        }
    }

    /// A name's value: a variable's, else the latest whiteboard message of that type (`None`
    /// when none was ever posted). An extern never posted reads 0, as gufsm's cache did.
    pub fn read(&self, name: &str) -> Option<Value> {
        if let Some(v) = self.locals.get(name) {
            return Some(v.clone());
        }
        if self.shared.is_extern(name) {
            return Some(self.seen.value(self.board, name).unwrap_or(Value::Int(0)));
        }
        if let Some(v) = self.shared.global(name) {
            return Some(v);
        }
        self.seen.value(self.board, name)
    }

    /// The newest message of a type, as the ringlet sees the board.
    pub fn latest(&self, ty: &str) -> Option<proclaim_board::Message> {
        self.seen.latest(self.board, ty)
    }

    /// The functions an expression may use; `None` for one that gives no value (a host
    /// function or an activity built-in such as `post`, which only statements run).
    fn function(
        &mut self,
        function: &str,
        arguments: &[Expr],
        clock: Option<usize>,
    ) -> Option<Value> {
        if let Some(limit) = self.time_limit(function, arguments) {
            let elapsed = self.clocks.elapsed(clock);
            return Some(Value::Bool(limit.is_some_and(|l| elapsed >= l)));
        }
        if let Some(aggregate) = proclaim_fsm::Aggregate::of_function(function) {
            let team =
                crate::team::aggregated_type(function, arguments).and_then(|ty| self.latest(&ty));
            let me = self.latest(proclaim_board::team::ME);
            let size = self.latest(proclaim_board::team::SIZE);
            let asker = crate::team::Asker {
                me: me.as_ref().map(|m| &m.value),
                size: size.as_ref().map(|m| &m.value),
            };
            return crate::team::aggregate(aggregate, team.as_ref().map(|m| &m.value), asker);
        }
        let values: Vec<Option<Value>> = arguments.iter().map(|a| self.value(a)).collect();
        arith::function(function, &values)
    }

    /// For `timeout(µs)`, `after(s)` and `after_ms(ms)`: how long the state must have been
    /// active (`Some(None)` when the argument has no value); `None` for other functions.
    pub fn time_limit(&mut self, function: &str, arguments: &[Expr]) -> Option<Option<Duration>> {
        let (_, micros_per_unit) = TIME_TESTS.iter().find(|(f, _)| *f == function)?;
        let [argument] = arguments else {
            return Some(None);
        };
        // A duration says its own unit: `after(2s)` and `timeout(2s)` are the same test.
        if let Expr::Duration(us) = argument {
            return Some(Some(Duration::from_micros(*us)));
        }
        Some(
            self.value(argument)
                .and_then(|v| v.as_f64())
                // Too long for a `Duration` is never.
                .map(|n| {
                    Duration::try_from_secs_f64((n * micros_per_unit).max(0.0) / 1e6)
                        .unwrap_or(Duration::MAX)
                }),
        )
    }
}

impl Evaluate for Env<'_> {
    fn read(&mut self, name: &str) -> Option<Value> {
        Env::read(self, name)
    }

    fn call(&mut self, function: &str, arguments: &[Expr], clock: Option<usize>) -> Option<Value> {
        self.function(function, arguments, clock)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::parse_label;

    fn eval(text: &str) -> Option<Value> {
        let board = Whiteboard::local();
        board.post("test", "posted", Value::Int(12));
        board.post("test", "word", Value::Str("ball".into()));
        // What a robot of a team keeps of it (`proclaim_board::team`).
        let (near, far) = (Value::Float(0.8), Value::Float(2.5));
        let team = proclaim_board::team::team_value([("robot1", &far), ("robot2", &near)]);
        board.post("team", "team.ballDistance", team);
        board.post("team", "robot1.ballDistance", far.clone());
        board.post("team", "me", "robot2");
        let shared = Shared::for_machines([]);
        shared.set_global("g", Value::Int(7));
        let entered_at = Instant::now();
        let mut env = Env {
            board: &board,
            seen: &Seen::default(),
            locals: &Locals::default(),
            shared: &shared,
            clocks: Clocks {
                now: entered_at + Duration::from_millis(1500),
                entered_at,
                composites: &[],
            },
        };
        env.value(&parse_label(text).expect("parses"))
    }

    #[tokio::test]
    async fn c_arithmetic_over_variables_and_whiteboard_values() {
        for (text, expect) in [
            ("7 / 2", Some(Value::Int(3))),
            ("7 / 2.0", Some(Value::Float(3.5))),
            ("-7 % 3", Some(Value::Int(-1))),
            ("1 / 0", Some(Value::Int(i64::MAX))),
            ("g * 2 + posted", Some(Value::Int(26))),
            ("g == 2 * (g / 2)", Some(Value::Bool(false))),
            ("posted - never", None),
            ("never < 3", Some(Value::Bool(false))),
            ("!(never < 3)", Some(Value::Bool(true))),
            ("word + \" at \" + g", Some(Value::Str("ball at 7".into()))),
            ("abs(-3)", Some(Value::Int(3))),
            ("max(g, 2.5)", Some(Value::Int(7))),
            (
                "timeout(1500000) && after(1) && !after_ms(1501)",
                Some(Value::Bool(true)),
            ),
            ("timeout(g * 1000000)", Some(Value::Bool(false))),
            (
                "timeout(1500ms) && after(1s) && !after_ms(2s)",
                Some(Value::Bool(true)),
            ),
            ("timeout(2s) + 500ms", Some(Value::Int(500_000))),
            ("team.argmin(ballDistance) == me", Some(Value::Bool(true))),
            ("team.argmax(ballDistance)", Some(Value::from("robot1"))),
            (
                "team.min(ballDistance) < robot1.ballDistance",
                Some(Value::Bool(true)),
            ),
            ("team.count(ballDistance)", Some(Value::Int(2))),
            ("team.count(role)", Some(Value::Int(0))),
            ("team.argmin(role) == me", Some(Value::Bool(false))),
        ] {
            assert_eq!(eval(text), expect, "{text}");
        }
    }
}
