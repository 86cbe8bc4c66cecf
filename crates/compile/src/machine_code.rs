//! A machine of the plan as the functions a compiled behaviour runs (its ringlet, what its
//! labels read, its final states, its dues): the one walk of states, labels and steps that both
//! target languages print, so C and Rust cannot drift apart in what a ringlet does.

use crate::code::{print, Expr, Function, Op, Spelling, Stmt, Type};
use crate::plan::{Condition, Conversion, MachinePlan, Piece, Plan, StatePlan, Step, Value};
use proclaim_fsm::control::Command;
use proclaim_lower::LOOP_LIMIT;

/// Every machine's functions, and those that hand a machine's number to its own, as
/// `spelling` writes them.
pub(crate) fn printed(plan: &Plan, spelling: &dyn Spelling) -> String {
    let mut code = String::new();
    for (m, machine) in plan.machines.iter().enumerate() {
        for f in functions(m, machine) {
            code.push_str(&print(&f, spelling));
        }
    }
    for f in dispatch(plan.machines.len()) {
        code.push_str(&print(&f, spelling));
    }
    code
}

/// `answer` and `apply_input` (`answer_code.rs`), as `spelling` writes them.
pub(crate) fn answers(plan: &Plan, spelling: &dyn Spelling) -> String {
    let functions = crate::answer_code::functions(plan);
    functions.iter().map(|f| print(f, spelling)).collect()
}

/// Machine `m`'s functions.
fn functions(m: usize, machine: &MachinePlan) -> Vec<Function> {
    let walk = Walk { m, machine };
    vec![
        walk.ring(),
        walk.reads(),
        walk.reads_externs(),
        walk.test("reads_globals", |s| s.reads_globals),
        walk.test("final", |s| s.is_final),
        walk.dues(),
    ]
}

/// The ringlets of every machine in a round, and the functions that hand a machine's number to
/// its own (`reads(w, m, k)` to `reads_M(w, k)`, …), so that the runtime's news and dues are one
/// loop over the machines.
fn dispatch(machines: usize) -> Vec<Function> {
    let m = ("m", Type::Index);
    let to = |name: &str, own: &str, params: Vec<(&'static str, Type)>, returns: Type| {
        dispatcher(machines, (name, own), params, returns)
    };
    vec![
        ring_machines(machines),
        to("reads", "reads", vec![m, ("k", Type::Index)], Type::Truth),
        to(
            "reads_extern",
            "reads_extern",
            vec![m, ("e", Type::Index)],
            Type::Truth,
        ),
        to("reads_globals", "reads_globals", vec![m], Type::Truth),
        to("final_state", "final", vec![m], Type::Truth),
        to("due_of", "due", vec![m, ("due", Type::Ms)], Type::Ms),
    ]
}

/// A ringlet of every machine due to ring, in manifest order, each followed by the commands it
/// posted; whether one fired. Written out machine by machine, not a loop over a switch: each
/// machine's test and ringlet are then direct calls a compiler can inline.
fn ring_machines(machines: usize) -> Function {
    let fired = || Expr::Name("fired".into());
    let mut body = vec![Stmt::Let("fired", Type::Truth, Expr::Truth(false))];
    for m in 0..machines {
        let ring = Expr::call(&format!("ring_{m}"), vec![]);
        body.push(Stmt::If(
            Expr::call("ringlet_due", vec![Expr::count(m)]),
            vec![
                Stmt::If(ring, vec![Stmt::Set(fired(), Expr::Truth(true))]),
                Stmt::Do(Expr::call("obey", vec![])),
            ],
        ));
    }
    body.push(Stmt::Return(fired()));
    Function {
        name: "ring_machines".into(),
        writes: true,
        params: vec![],
        returns: Type::Truth,
        body,
    }
}

/// `name(w, m, …)` as machine `m`'s `own_M(w, …)`: false for no machine, or `due` unchanged.
fn dispatcher(
    machines: usize,
    (name, own): (&str, &str),
    params: Vec<(&'static str, Type)>,
    returns: Type,
) -> Function {
    let args: Vec<Expr> = params[1..]
        .iter()
        .map(|(name, _)| Expr::Name(name.to_string()))
        .collect();
    let arms = (0..machines)
        .map(|m| {
            let call = Expr::call(&format!("{own}_{m}"), args.clone());
            (vec![m as i64], vec![Stmt::Return(call)])
        })
        .collect();
    let otherwise = match returns {
        Type::Ms => due(),
        Type::Truth | Type::Index | Type::Text => Expr::Truth(false),
    };
    Function {
        name: name.to_string(),
        writes: false,
        params,
        returns,
        body: vec![Stmt::Switch {
            on: Expr::Name("m".into()),
            arms,
            otherwise: vec![Stmt::Return(otherwise)],
        }],
    }
}

struct Walk<'a> {
    m: usize,
    machine: &'a MachinePlan,
}

impl Walk<'_> {
    fn name(&self, what: &str) -> String {
        format!("{what}_{}", self.m)
    }

    fn machine(&self) -> Expr {
        Expr::count(self.m)
    }

    fn state(&self) -> Expr {
        Expr::index(Expr::World("state"), self.machine())
    }

    /// The ringlet (`docs/spec/behaviour.md` §3.1): OnEntry once after entering, the snapshot,
    /// then the state's transitions in order (OnExit and the move for the first proved), else
    /// its Internal. Whether a transition fired.
    fn ring(&self) -> Function {
        let entries = self
            .machine
            .states
            .iter()
            .map(|s| (vec![s.id], self.entry(s)))
            .collect();
        let cases = self
            .machine
            .states
            .iter()
            .map(|s| (vec![s.id], self.ringlet(s)))
            .collect();
        let body = vec![
            Stmt::If(
                Expr::call("begin_ringlet", vec![self.machine()]),
                vec![Stmt::Switch {
                    on: self.state(),
                    arms: entries,
                    otherwise: vec![],
                }],
            ),
            Stmt::Do(Expr::call("take_snapshot", vec![self.machine()])),
            Stmt::Switch {
                on: self.state(),
                arms: cases,
                otherwise: vec![Stmt::Return(Expr::Truth(false))],
            },
        ];
        Function {
            name: self.name("ring"),
            writes: true,
            params: vec![],
            returns: Type::Truth,
            body,
        }
    }

    /// Entering `state`: the event, its OnEntry, and a final state's end.
    fn entry(&self, state: &StatePlan) -> Vec<Stmt> {
        let mut body = vec![Stmt::Do(Expr::Report(
            "entered",
            vec![
                Expr::Text(self.machine.name.clone()),
                Expr::Text(state.name.clone()),
                Expr::Number(state.id),
            ],
        ))];
        self.steps(&state.entry, &mut body);
        if state.is_final {
            body.push(Stmt::Do(Expr::call(
                "report_finished",
                vec![self.machine(), Expr::Text(state.name.clone())],
            )));
        }
        body
    }

    /// A ringlet in `state`: its transitions tried in order, else its Internal.
    fn ringlet(&self, state: &StatePlan) -> Vec<Stmt> {
        let mut body = Vec::new();
        for t in &state.transitions {
            let mut fire = vec![Stmt::Do(Expr::Report(
                "fired",
                vec![
                    Expr::Text(self.machine.name.clone()),
                    Expr::Number(state.id),
                    Expr::Number(t.target),
                    Expr::Text(t.label.clone()),
                ],
            ))];
            self.steps(&state.leavings[t.leaving], &mut fire);
            // One that stays moves nowhere: its state is not entered again.
            if !t.stays {
                fire.extend(
                    t.enters
                        .iter()
                        .map(|&c| Stmt::Do(Expr::call("enter_composite", vec![Expr::count(c)]))),
                );
                fire.extend([
                    Stmt::Set(self.state(), Expr::Number(t.target)),
                    Stmt::Set(
                        Expr::index(Expr::World("just_entered"), self.machine()),
                        Expr::Truth(true),
                    ),
                ]);
            }
            fire.push(Stmt::Return(Expr::Truth(true)));
            let label = Expr::Label(Box::new(self.condition(&t.condition)));
            let proved = Expr::call("proved", vec![self.machine(), label]);
            body.push(Stmt::If(proved, fire));
        }
        self.steps(&state.staying, &mut body);
        body.push(Stmt::Return(Expr::Truth(false)));
        body
    }

    /// Whether the current state's labels ask output `k`.
    fn reads(&self) -> Function {
        self.reading("reads", "k", |s| &s.reads)
    }

    /// Whether the current state's labels read whiteboard variable `e`.
    fn reads_externs(&self) -> Function {
        self.reading("reads_extern", "e", |s| &s.reads_externs)
    }

    /// Whether parameter `param` is one of the numbers the current state's labels read
    /// (`read`); false in a state whose labels read none.
    fn reading(
        &self,
        what: &str,
        param: &'static str,
        read: fn(&StatePlan) -> &[usize],
    ) -> Function {
        let arms = self
            .machine
            .states
            .iter()
            .filter(|s| !read(s).is_empty())
            .map(|s| {
                let numbers = read(s).iter().map(|&n| (n, param));
                (vec![s.id], vec![Stmt::Return(any(numbers))])
            })
            .collect();
        self.of_state(what, vec![(param, Type::Index)], arms)
    }

    /// Whether the machine is in a state that `keep` holds of.
    fn test(&self, what: &str, keep: fn(&StatePlan) -> bool) -> Function {
        let ids: Vec<i64> = self
            .machine
            .states
            .iter()
            .filter(|s| keep(s))
            .map(|s| s.id)
            .collect();
        let arms = if ids.is_empty() {
            vec![]
        } else {
            vec![(ids, vec![Stmt::Return(Expr::Truth(true))])]
        };
        self.of_state(what, vec![], arms)
    }

    /// A truth of the current state: its arm's, else false.
    fn of_state(
        &self,
        what: &str,
        params: Vec<(&'static str, Type)>,
        arms: Vec<(Vec<i64>, Vec<Stmt>)>,
    ) -> Function {
        Function {
            name: self.name(what),
            writes: false,
            params,
            returns: Type::Truth,
            body: vec![Stmt::Switch {
                on: self.state(),
                arms,
                otherwise: vec![Stmt::Return(Expr::Truth(false))],
            }],
        }
    }

    /// The soonest of `due` and the current state's time tests still to come due.
    fn dues(&self) -> Function {
        let arms = self
            .machine
            .states
            .iter()
            .filter(|s| !s.due_ms.is_empty())
            .map(|s| {
                let body = s
                    .due_ms
                    .iter()
                    .map(|&(ms, composite)| {
                        let after = match composite {
                            None => ("due_after", self.machine()),
                            Some(c) => ("composite_due_after", Expr::count(c)),
                        };
                        let args = vec![after.1, Expr::Count(ms), due()];
                        Stmt::Set(due(), Expr::call(after.0, args))
                    })
                    .collect();
                (vec![s.id], body)
            })
            .collect();
        Function {
            name: self.name("due"),
            writes: false,
            params: vec![("due", Type::Ms)],
            returns: Type::Ms,
            body: vec![
                Stmt::Switch {
                    on: self.state(),
                    arms,
                    otherwise: vec![],
                },
                Stmt::Return(due()),
            ],
        }
    }

    /// A label as the runner proves it.
    fn condition(&self, c: &Condition) -> Expr {
        match c {
            Condition::Constant(b) => Expr::Truth(*b),
            Condition::Ask(k) => Expr::call("ask", vec![self.machine(), Expr::count(*k)]),
            Condition::AskPosted { number, atom } => Expr::call(
                "ask_posted",
                vec![
                    self.machine(),
                    Expr::count(*number),
                    Expr::Text(atom.clone()),
                ],
            ),
            Condition::Not(c) => Expr::Not(Box::new(self.condition(c))),
            Condition::Both { and, left, right } => Expr::binary(
                if *and { Op::And } else { Op::Or },
                self.condition(left),
                self.condition(right),
            ),
            Condition::Elapsed {
                ms,
                composite: None,
            } => Expr::call("elapsed_at_least", vec![self.machine(), Expr::Count(*ms)]),
            Condition::Elapsed {
                ms,
                composite: Some(c),
            } => Expr::call("composite_elapsed", vec![Expr::count(*c), Expr::Count(*ms)]),
            Condition::Truth(v) => truthy(v),
        }
    }

    fn steps(&self, steps: &[Step], out: &mut Vec<Stmt>) {
        for s in steps {
            self.step(s, out);
        }
    }

    /// One step of an activity, as the runner's statement walk does it.
    fn step(&self, s: &Step, out: &mut Vec<Stmt>) {
        match s {
            Step::Post { ty, content } => {
                out.push(call("post", vec![self.machine(), text(ty), text(content)]))
            }
            Step::PostBuilt { ty, pieces } => {
                build_text(pieces, out);
                out.push(call("post_text", vec![self.machine(), text(ty)]));
            }
            Step::Command {
                ty,
                word,
                command,
                target,
            } => {
                out.push(call("post", vec![self.machine(), text(ty), text(word)]));
                let code = Expr::Name(command_code(*command).into());
                out.push(call(
                    "command",
                    vec![Expr::count(*target), code, text(word)],
                ));
            }
            Step::Print(pieces) => {
                build_text(pieces, out);
                out.push(call("print_text", vec![self.machine()]));
            }
            Step::PostExtern { number, value } => out.push(call(
                "post_extern",
                vec![self.machine(), Expr::count(*number), self::value(value)],
            )),
            Step::Assign {
                slot,
                conversion,
                global,
                name,
                value,
            } => out.push(call(
                "assign",
                vec![
                    self.machine(),
                    Expr::count(*slot),
                    Expr::Name(conversion_code(*conversion).into()),
                    Expr::Truth(*global),
                    text(name),
                    self::value(value),
                ],
            )),
            Step::Block(body) => {
                let mut inner = Vec::new();
                self.steps(body, &mut inner);
                out.push(Stmt::Block(inner));
            }
            Step::Loop {
                number,
                state,
                init,
                condition,
                body,
                step,
            } => out.push(self.for_loop(*number, state, (init, condition), (body, step))),
            Step::Nothing => {}
        }
    }

    /// A `for` loop as a `while`, stopped at the runner's loop limit with its warning.
    fn for_loop(
        &self,
        number: usize,
        state: &str,
        (init, condition): (&Option<Box<Step>>, &Option<Value>),
        (body, step): (&Step, &Option<Box<Step>>),
    ) -> Stmt {
        let counter = format!("rounds_{number}");
        let mut block = vec![Stmt::Counter(counter.clone())];
        if let Some(init) = init {
            self.step(init, &mut block);
        }
        let warning = format!("a `for` loop in state {state} stopped after {LOOP_LIMIT} rounds");
        let limit = Expr::binary(
            Op::Equal,
            Expr::Name(counter.clone()),
            Expr::Name("LOOP_LIMIT".into()),
        );
        let warned = Expr::Report(
            "warned",
            vec![
                Expr::index(Expr::Table("machine_name"), self.machine()),
                Expr::Text(warning),
            ],
        );
        let mut round = vec![
            Stmt::If(limit, vec![Stmt::Do(warned), Stmt::Break]),
            Stmt::Increment(counter),
        ];
        self.step(body, &mut round);
        if let Some(step) = step {
            self.step(step, &mut round);
        }
        let test = condition.as_ref().map_or(Expr::Truth(true), truthy);
        block.push(Stmt::While(test, round));
        Stmt::Block(block)
    }
}

fn call(name: &'static str, args: Vec<Expr>) -> Stmt {
    Stmt::Do(Expr::call(name, args))
}

fn text(s: &str) -> Expr {
    Expr::Text(s.to_string())
}

fn due() -> Expr {
    Expr::Name("due".into())
}

/// Whether parameter `name` is one of `numbers`.
fn any(numbers: impl Iterator<Item = (usize, &'static str)>) -> Expr {
    numbers
        .map(|(n, name)| Expr::binary(Op::Equal, Expr::Name(name.into()), Expr::count(n)))
        .reduce(|a, b| Expr::binary(Op::Or, a, b))
        .unwrap_or(Expr::Truth(false))
}

/// The pieces built into the world's text.
fn build_text(pieces: &[Piece], out: &mut Vec<Stmt>) {
    out.push(Stmt::Do(Expr::Buffer("text_clear", vec![])));
    for piece in pieces {
        let (what, arg) = match piece {
            Piece::Literal(s) if s.is_empty() => continue,
            Piece::Literal(s) => ("text_literal", text(s)),
            Piece::Value(v) => ("text_value", value(v)),
            Piece::Whole(v) => ("text_whole", value(v)),
        };
        out.push(Stmt::Do(Expr::Buffer(what, vec![arg])));
    }
}

fn truthy(v: &Value) -> Expr {
    Expr::Pure("truthy", vec![value(v)])
}

/// A value, as `proclaim-lower`'s `arith` computes it.
fn value(v: &Value) -> Expr {
    match v {
        Value::Bool(b) => Expr::Pure("v_bool", vec![Expr::Truth(*b)]),
        Value::Int(i) => Expr::Pure("v_int", vec![Expr::Whole(*i)]),
        Value::Slot(slot) => Expr::index(Expr::World("var"), Expr::count(*slot)),
        Value::Extern(number) => Expr::call("read_extern", vec![Expr::count(*number)]),
        Value::Not(operand) => Expr::Pure("v_bool", vec![Expr::Not(Box::new(truthy(operand)))]),
        Value::Logic { and, left, right } => {
            let op = if *and { Op::And } else { Op::Or };
            Expr::Pure(
                "v_bool",
                vec![Expr::binary(op, truthy(left), truthy(right))],
            )
        }
        Value::Apply(function, arguments) => {
            Expr::Pure(function.helper(), arguments.iter().map(value).collect())
        }
    }
}

fn conversion_code(conversion: Conversion) -> &'static str {
    match conversion {
        Conversion::Whole => "CONVERT_WHOLE",
        Conversion::Truth => "CONVERT_TRUTH",
        Conversion::Kept => "CONVERT_KEPT",
    }
}

/// A sub-machine control command as both runtimes name it.
fn command_code(command: Option<Command>) -> &'static str {
    match command {
        Some(Command::On) => "COMMAND_ON",
        Some(Command::Off) => "COMMAND_OFF",
        Some(Command::Suspend) => "COMMAND_SUSPEND",
        Some(Command::Resume) => "COMMAND_RESUME",
        Some(Command::Restart) => "COMMAND_RESTART",
        Some(Command::Reload) | Some(Command::Reread) | None => "COMMAND_UNKNOWN",
    }
}
