//! Reading an activity's statements without running them, for the back ends that write or
//! analyse an activity whole (the Promela writer, the compile planner, the checker's flow of
//! free values): what each statement is comes from [`Statement::kind`], here, so a new kind of
//! statement is met in one match, and each back end says only what it makes of each kind.

use proclaim_fsm::{Expr, ForLoop, Statement, StatementKind};

/// What a back end makes of each kind of statement (the walk that runs them is
/// [`crate::walk::Effects`]).
pub trait StatementReader {
    /// What reading one statement gives: code written, a planned step, or nothing.
    type Read;
    fn assign(&mut self, name: &str, value: &Expr) -> Self::Read;
    /// A call standing as a statement (a posting, a command, a print, a host function).
    fn call(&mut self, function: &str, arguments: &[Expr]) -> Self::Read;
    /// An expression standing as a statement.
    fn evaluate(&mut self, expr: &Expr) -> Self::Read;
    /// A block: its statements in order.
    fn sequence(&mut self, body: &[Statement]) -> Self::Read;
    fn for_loop(&mut self, parts: ForLoop<'_>) -> Self::Read;
    /// A statement that does nothing (a declaration without a value, an empty one).
    fn nothing(&mut self) -> Self::Read;
}

/// `statement` as `reader` makes it.
pub fn read_statement<R: StatementReader + ?Sized>(
    reader: &mut R,
    statement: &Statement,
) -> R::Read {
    match statement.kind() {
        StatementKind::Assign { name, value } => reader.assign(name, value),
        StatementKind::Call {
            function,
            arguments,
        } => reader.call(function, arguments),
        StatementKind::Evaluate(expr) => reader.evaluate(expr),
        StatementKind::Sequence(body) => reader.sequence(body),
        StatementKind::Loop(parts) => reader.for_loop(parts),
        StatementKind::Nothing => reader.nothing(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::code::parse_statements;

    /// Names each statement as it is read, blocks and loops with what they hold.
    struct Names;

    impl StatementReader for Names {
        type Read = String;
        fn assign(&mut self, name: &str, value: &Expr) -> String {
            format!("{name} = {value}")
        }
        fn call(&mut self, function: &str, arguments: &[Expr]) -> String {
            format!("call {function}/{}", arguments.len())
        }
        fn evaluate(&mut self, expr: &Expr) -> String {
            format!("evaluate {expr}")
        }
        fn sequence(&mut self, body: &[Statement]) -> String {
            let inside: Vec<String> = body.iter().map(|s| read_statement(self, s)).collect();
            format!("{{{}}}", inside.join("; "))
        }
        fn for_loop(&mut self, parts: ForLoop<'_>) -> String {
            let condition = parts.condition.map_or("ever".into(), |c| c.to_string());
            format!("for {condition}: {}", read_statement(self, parts.body))
        }
        fn nothing(&mut self) -> String {
            "nothing".into()
        }
    }

    fn check(text: &str, expect: &str) {
        let statements = parse_statements(text).expect("it parses");
        let read: Vec<String> = statements
            .iter()
            .map(|s| read_statement(&mut Names, s))
            .collect();
        assert_eq!(read.join("; "), expect);
    }

    #[test]
    fn each_kind_of_statement_is_read_as_its_kind() {
        check("x = 1;", "x = 1");
        check("post(\"Say\", \"hi\");", "call post/2");
        check("x + 1;", "evaluate x + 1");
        check("{ x = 1; y = 2; }", "{x = 1; y = 2}");
        check(
            "for (i = 0; i < 3; i = i + 1) { n = n + i; }",
            "for i < 3: {n = n + i}",
        );
        check("int x;", "nothing");
    }
}
