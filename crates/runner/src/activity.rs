//! Running activities: postings, host calls and statements of the activity language, with the
//! built-in functions gufsm gave its machines (`post`, `postv`, `suspend`, `say`, `print`,
//! `msleep`, …).

use crate::eval::{Clocks, Env};
use crate::event::{Event, Reporter};
use crate::host::Hosts;
use crate::seen::Seen;
use crate::variables::{Locals, Shared};
use proclaim_board::{Suppressor, Value, Visibility, Whiteboard};
use proclaim_fsm::{Action, Argument, Expr};
use proclaim_lower::arith::text;
use proclaim_lower::builtin::{builtin, Builtin, Content};
use proclaim_lower::Evaluate;
use proclaim_lower::{Effects, Walk, LOOP_LIMIT};
use rustc_hash::FxHashSet;
use std::sync::Arc;
use std::time::Duration;
use tokio::time::Instant;

/// A behaviour's [`Suppressor`], shared by its machines and its schedule.
pub type SharedSuppressor = Arc<parking_lot::Mutex<Suppressor<Value>>>;

/// What an activity runs with.
pub(crate) struct ActivityContext<'a> {
    pub board: &'a Whiteboard,
    pub seen: &'a mut Seen,
    /// The machine's name: who posts.
    pub machine: &'a str,
    pub state: &'a str,
    pub entered_at: Instant,
    /// Now, as the machine reads time (the round's moment under the round schedule).
    pub now: Instant,
    pub hosts: &'a Hosts,
    pub shared: &'a Shared,
    pub locals: &'a mut Locals,
    /// Host functions already reported missing (each is reported once).
    pub unknown: &'a mut FxHashSet<String>,
    pub reporter: &'a Reporter,
    /// The machine's subsumption priority, carried by every posting it makes.
    pub priority: u32,
    pub suppressor: Option<&'a SharedSuppressor>,
}

impl ActivityContext<'_> {
    pub async fn run(&mut self, actions: &[Action]) {
        for action in actions {
            match action {
                Action::Post { ty, content } => {
                    self.post(ty, Value::parse(content));
                }
                Action::Call { function, argument } => self.host_call(function, argument).await,
                Action::Statement(s) => {
                    let mut walk = Walk::new(s);
                    while let Some(ms) = walk.resume(self) {
                        sleep_ms(ms).await;
                    }
                }
                // Reported when the machine was read; it does nothing.
                Action::Code(_) => {}
            }
        }
    }

    fn env(&self) -> Env<'_> {
        Env {
            board: self.board,
            seen: self.seen,
            locals: self.locals,
            shared: self.shared,
            // An activity's time test (one the checker never makes due) reads its state's.
            clocks: Clocks {
                now: self.now,
                entered_at: self.entered_at,
                composites: &[],
            },
        }
    }

    fn value(&self, e: &Expr) -> Value {
        self.env().value(e).unwrap_or(Value::Int(0))
    }

    fn text(&self, e: &Expr) -> String {
        text(&self.value(e))
    }

    fn post(&mut self, ty: &str, value: Value) {
        if let Some(suppressor) = self.suppressor {
            // The schedule's moment, so a replay judges as the run did.
            let now = self.now.saturating_duration_since(self.reporter.epoch);
            let verdict = suppressor
                .lock()
                .offer(self.machine, ty, &value, self.priority, now);
            if let Visibility::Suppressed {
                by,
                priority,
                until,
            } = verdict
            {
                // Never on the board, so no reader (the machine itself included) sees it.
                self.reporter.emit(|at, round| Event::Suppressed {
                    machine: self.machine.to_string(),
                    ty: ty.to_string(),
                    content: text(&value),
                    priority: self.priority,
                    by: by.to_string(),
                    by_priority: priority,
                    until,
                    at,
                    round,
                });
                return;
            }
        }
        let message = self
            .board
            .post_ranked(self.machine, ty, value, self.priority);
        self.seen.posted(&message);
        self.reporter.emit(|at, round| Event::Posted {
            machine: self.machine.to_string(),
            ty: ty.to_string(),
            content: text(&message.value),
            priority: self.priority,
            at,
            round,
        });
    }

    fn warn(&self, message: String) {
        // The event reaches whoever runs the machine; a warning here would say it twice.
        tracing::debug!(machine = %self.machine, "{message}");
        self.reporter.emit(|at, round| Event::Warned {
            machine: self.machine.to_string(),
            message,
            at,
            round,
        });
    }

    /// Assigns as gufsm did: the machine's own variable, else an extern (posted), else a global.
    /// A change of a variable's value is reported (an extern's as its posting), so a trace
    /// says what every variable held when.
    fn store(&mut self, name: &str, value: Value) {
        if self.locals.contains(name) {
            let before = self.locals.get(name).cloned();
            self.locals.set(name, value);
            let after = self.locals.get(name).cloned();
            if after != before {
                self.report_assigned(name, after);
            }
        } else if self.shared.is_extern(name) {
            self.post(name, value);
        } else if self.shared.global(name).as_ref() != Some(&value) {
            self.shared.set_global(name, value.clone());
            self.report_assigned(name, Some(value));
        }
    }

    fn report_assigned(&self, variable: &str, value: Option<Value>) {
        self.reporter.emit(|at, round| Event::Assigned {
            machine: self.machine.to_string(),
            variable: variable.to_string(),
            value: value.as_ref().map(text).unwrap_or_default(),
            round,
            at,
        });
    }

    async fn host_call(&mut self, function: &str, argument: &Option<Argument>) {
        match (function, argument) {
            ("msleep", Some(Argument::Int(ms))) => sleep_ms(*ms as f64).await,
            ("sleep", Some(Argument::Int(s))) => sleep_ms(*s as f64 * 1000.0).await,
            _ => self.host(function, argument.as_ref()),
        }
    }

    fn host(&mut self, function: &str, argument: Option<&Argument>) {
        match self.hosts.get(function) {
            Some(f) => f(argument),
            None => {
                if self.unknown.insert(function.to_string()) {
                    tracing::debug!(machine = %self.machine, function = %function, "host function not registered; skipped");
                    self.reporter.emit(|_, _| Event::UnknownFunction {
                        machine: self.machine.to_string(),
                        function: function.to_string(),
                    });
                }
            }
        }
    }

    fn print(&self, text: String) {
        tracing::info!(machine = %self.machine, "{text}");
        self.reporter.emit(|at, round| Event::Printed {
            machine: self.machine.to_string(),
            text,
            at,
            round,
        });
    }
}

impl Effects for ActivityContext<'_> {
    /// Milliseconds to sleep.
    type Pause = f64;

    fn assign(&mut self, name: &str, value: &Expr) {
        let value = self.value(value);
        self.store(name, value);
    }

    /// A call standing as a statement: a built-in ([`builtin`]), or a function of the
    /// environment, or a host function.
    fn perform(&mut self, function: &str, arguments: &[Expr]) -> Option<f64> {
        let call = builtin(function, arguments);
        let state = match call {
            Builtin::Post {
                content: Content::StateName,
                ..
            }
            | Builtin::Print(Content::StateName) => self.state.to_string(),
            _ => String::new(),
        };
        match call {
            Builtin::Post { to, content } => {
                let ty = to.name(|e| self.text(e));
                let value = content.value(|e| self.value(e), &state);
                self.post(&ty, value);
            }
            Builtin::Print(content) => {
                let printed = text(&content.value(|e| self.value(e), &state));
                self.print(printed);
            }
            Builtin::Sleep {
                amount,
                ms_per_unit,
            } => return Some(self.value(amount).as_f64().unwrap_or(0.0) * ms_per_unit),
            Builtin::Other if self.env().call(function, arguments, None).is_some() => {}
            Builtin::Other => {
                let argument = arguments.first().map(|a| match self.value(a) {
                    Value::Int(i) => Argument::Int(i),
                    Value::Str(s) => Argument::Str(s),
                    other => Argument::Word(other.to_string()),
                });
                self.host(function, argument.as_ref());
            }
        }
        None
    }

    fn evaluate(&mut self, expr: &Expr) {
        self.value(expr);
    }

    fn holds(&mut self, condition: &Expr) -> bool {
        self.env().truth(condition)
    }

    fn loop_stopped(&mut self) {
        self.warn(format!(
            "a `for` loop in state {} stopped after {LOOP_LIMIT} rounds",
            self.state
        ));
    }
}

async fn sleep_ms(ms: f64) {
    if ms > 0.0 {
        // A sleep too long for a `Duration` sleeps for ever rather than panicking.
        let duration = Duration::try_from_secs_f64(ms / 1e3).unwrap_or(Duration::MAX);
        tokio::time::sleep(duration).await;
    }
}
