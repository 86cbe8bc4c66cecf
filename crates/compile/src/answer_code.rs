//! What a behaviour's experts answer and how a posting reaches its theories' inputs, as code
//! both target languages print: `answer(w, k)` (output `k` decided by its theory, or an atom
//! from outside as last posted) and `apply_input(w, ty, content)` (a posting's type setting
//! the inputs it names, an input group moving as the reasoner's session moves it).

use crate::code::{Expr, Function, Stmt, Type};
use crate::plan::{Answer, Input, Plan};

/// `answer` and `apply_input`.
pub(crate) fn functions(plan: &Plan) -> Vec<Function> {
    vec![answer(plan), apply_input(plan)]
}

fn input(variable: usize) -> Expr {
    Expr::index(Expr::World("input"), Expr::count(variable))
}

fn answer(plan: &Plan) -> Function {
    let arms = plan
        .outputs
        .iter()
        .enumerate()
        .map(|(k, o)| {
            let answer = match o.answer {
                Answer::Theory {
                    theory,
                    index,
                    offset,
                } => Expr::Decide {
                    theory: plan.theories[theory].prefix.clone(),
                    output: index,
                    offset,
                },
                // The pair's second variable: whether the atom was last posted true.
                Answer::Outside { variable } => input(variable + 1),
            };
            (vec![k as i64], vec![Stmt::Return(answer)])
        })
        .collect();
    Function {
        name: "answer".into(),
        writes: false,
        params: vec![("k", Type::Index)],
        returns: Type::Truth,
        body: vec![Stmt::Switch {
            on: Expr::Name("k".into()),
            arms,
            otherwise: vec![Stmt::Return(Expr::Truth(false))],
        }],
    }
}

/// Whether a posting of type `ty` sets theory inputs (then set from `content`).
fn apply_input(plan: &Plan) -> Function {
    let mut body = Vec::new();
    for (ty, inputs) in plan.input_types() {
        let mut sets: Vec<Stmt> = inputs.iter().flat_map(|i| updates(i)).collect();
        sets.push(Stmt::Return(Expr::Truth(true)));
        let same = Expr::Pure("same", vec![Expr::Name("ty".into()), Expr::Text(ty.into())]);
        body.push(Stmt::If(same, sets));
    }
    body.push(Stmt::Return(Expr::Truth(false)));
    Function {
        name: "apply_input".into(),
        writes: true,
        params: vec![("ty", Type::Text), ("content", Type::Text)],
        returns: Type::Truth,
        body,
    }
}

/// One input set from the content; for an atom of an input group that came true, each other
/// atom of its group made known and false (`docs/spec/cdl.md` §1).
fn updates(i: &Input) -> Vec<Stmt> {
    let args = vec![Expr::count(i.variable), Expr::Name("content".into())];
    let mut out = vec![Stmt::Do(Expr::call("set_input", args))];
    if !i.group.is_empty() {
        let others = i
            .group
            .iter()
            .flat_map(|&o| {
                [
                    Stmt::Set(input(o), Expr::Truth(true)),
                    Stmt::Set(input(o + 1), Expr::Truth(false)),
                ]
            })
            .collect();
        out.push(Stmt::If(input(i.variable + 1), others));
    }
    out
}
