//! The parser: C's precedence for expressions, gufsm's statements.

use super::expr::{BinOp, Expr, UnOp};
use super::stmt::{Statement, VarType};
use super::token::{tokenize, CodeToken};
use std::fmt;

/// Where and why code did not parse (`offset` in bytes into the text given).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CodeError {
    pub offset: usize,
    pub message: String,
}

impl fmt::Display for CodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at column {})", self.message, self.offset + 1)
    }
}

/// One expression, the whole text.
pub fn parse_expression(text: &str) -> Result<Expr, CodeError> {
    let mut p = Parser::new(text)?;
    let e = p.expression()?;
    p.end_of_expression()?;
    Ok(e)
}

/// Statements up to the end of the text. The last one may leave out its `;`, as people do in a
/// Qfsm description (`{ sound=0 }`).
pub fn parse_statements(text: &str) -> Result<Vec<Statement>, CodeError> {
    let mut p = Parser::new(text)?;
    let mut out = Vec::new();
    while p.peek().is_some() {
        if let Some(s) = p.statement()? {
            out.push(s);
        }
    }
    Ok(out)
}

/// How deeply code may nest: brackets, operators applied to operators, a chain of one
/// operator (`a || b || …` is a tree as deep as it is long), blocks in blocks. Every pass
/// after parsing (printing, evaluating, checking, generating C) walks the tree recursively, on
/// threads with small stacks; C compilers guarantee 63 levels, people write a handful, and a
/// mutated or generated file can write 20,000.
pub const MAX_NESTING: usize = 256;

struct Parser {
    tokens: Vec<(usize, CodeToken, usize)>,
    at: usize,
    end: usize,
    /// How deep the tree being built is at this point (see [`MAX_NESTING`]).
    depth: usize,
}

type Parsed<T> = Result<T, CodeError>;

impl Parser {
    fn new(text: &str) -> Parsed<Parser> {
        let tokens = tokenize(text).map_err(|e| CodeError {
            offset: e.at,
            message: e.message,
        })?;
        Ok(Parser {
            tokens,
            at: 0,
            end: text.len(),
            depth: 0,
        })
    }

    fn peek(&self) -> Option<&CodeToken> {
        self.tokens.get(self.at).map(|(_, t, _)| t)
    }

    fn peek_at(&self, ahead: usize) -> Option<&CodeToken> {
        self.tokens.get(self.at + ahead).map(|(_, t, _)| t)
    }

    fn offset(&self) -> usize {
        self.tokens.get(self.at).map_or(self.end, |(s, _, _)| *s)
    }

    fn is(&self, punct: &str) -> bool {
        matches!(self.peek(), Some(CodeToken::Punct(p)) if *p == punct)
    }

    fn eat(&mut self, punct: &str) -> bool {
        let found = self.is(punct);
        if found {
            self.at += 1;
        }
        found
    }

    fn found(&self) -> String {
        match self.peek() {
            Some(t) => t.to_string(),
            None => "the end".to_string(),
        }
    }

    fn expected(&self, what: &str) -> CodeError {
        let hint = if self.is("=") && what.contains("operator") {
            "; `=` assigns: compare with `==`"
        } else {
            ""
        };
        CodeError {
            offset: self.offset(),
            message: format!("expected {what}, found {}{hint}", self.found()),
        }
    }

    fn expect(&mut self, punct: &str) -> Parsed<()> {
        if self.eat(punct) {
            Ok(())
        } else {
            Err(self.expected(&format!("`{punct}`")))
        }
    }

    fn end_of_expression(&self) -> Parsed<()> {
        match self.peek() {
            None => Ok(()),
            Some(_) => Err(self.expected("an operator or the end of the expression")),
        }
    }

    /// Runs `part` one level deeper, refusing to go past [`MAX_NESTING`].
    fn nested<T>(&mut self, part: impl FnOnce(&mut Self) -> Parsed<T>) -> Parsed<T> {
        self.too_deep(1)?;
        self.depth += 1;
        let parsed = part(self);
        self.depth -= 1;
        parsed
    }

    /// An error if `more` levels below this one would nest past [`MAX_NESTING`].
    fn too_deep(&self, more: usize) -> Parsed<()> {
        if self.depth + more <= MAX_NESTING {
            return Ok(());
        }
        Err(CodeError {
            offset: self.offset(),
            message: format!(
                "nested more than {MAX_NESTING} levels deep (brackets, operators, a chain of one operator, or blocks): split it into smaller parts"
            ),
        })
    }

    fn name(&mut self) -> Parsed<String> {
        match self.peek() {
            Some(CodeToken::Name(n)) => {
                let n = n.clone();
                self.at += 1;
                Ok(n)
            }
            _ => Err(self.expected("a name")),
        }
    }

    fn expression(&mut self) -> Parsed<Expr> {
        self.binary(1)
    }

    /// Operators binding at least as tight as `min`, left to right.
    fn binary(&mut self, min: u8) -> Parsed<Expr> {
        self.nested(|p| p.binary_chain(min))
    }

    fn binary_chain(&mut self, min: u8) -> Parsed<Expr> {
        let mut left = self.unary()?;
        let mut links = 0;
        loop {
            let Some(op) = (match self.peek() {
                Some(CodeToken::Punct(p)) => BinOp::from_symbol(p),
                _ => None,
            }) else {
                return Ok(left);
            };
            if op.precedence() < min {
                return Ok(left);
            }
            // Each link of the chain puts the tree built so far one level further down.
            links += 1;
            self.too_deep(links)?;
            self.at += 1;
            let right = self.binary(op.precedence() + 1)?;
            left = Expr::binary(op, left, right);
        }
    }

    fn unary(&mut self) -> Parsed<Expr> {
        self.nested(Self::unary_operand)
    }

    fn unary_operand(&mut self) -> Parsed<Expr> {
        if self.eat("!") || self.eat("~") {
            return Ok(Expr::negation(self.unary()?));
        }
        if self.eat("+") {
            return self.unary();
        }
        if self.eat("-") {
            // A sign before a number is part of it: `-1` is the number minus one.
            match self.peek() {
                Some(CodeToken::Int(i)) => {
                    let i = -*i;
                    self.at += 1;
                    return Ok(Expr::Int(i));
                }
                Some(CodeToken::Float(x)) => {
                    let x = -*x;
                    self.at += 1;
                    return Ok(Expr::Float(x));
                }
                _ => {}
            }
            // So is a sign before a signed or bracketed number (`-+6`, `-(6)`): the tree is the
            // one its printed form reads back as.
            return Ok(match self.unary()? {
                Expr::Int(i) if i.checked_neg().is_some() => Expr::Int(-i),
                Expr::Float(x) => Expr::Float(-x),
                operand => Expr::Unary {
                    op: UnOp::Neg,
                    operand: Box::new(operand),
                },
            });
        }
        self.primary()
    }

    fn primary(&mut self) -> Parsed<Expr> {
        let token = self.peek().cloned();
        match token {
            Some(CodeToken::Int(i)) => {
                self.at += 1;
                Ok(Expr::Int(i))
            }
            Some(CodeToken::Float(x)) => {
                self.at += 1;
                Ok(Expr::Float(x))
            }
            Some(CodeToken::Str(s)) => {
                self.at += 1;
                Ok(Expr::Str(s))
            }
            Some(CodeToken::Duration(us)) => {
                self.at += 1;
                Ok(Expr::Duration(us))
            }
            Some(CodeToken::Name(n)) => {
                self.at += 1;
                if self.eat("(") {
                    let mut arguments = Vec::new();
                    if !self.eat(")") {
                        loop {
                            arguments.push(self.expression()?);
                            if self.eat(")") {
                                break;
                            }
                            if !self.eat(",") {
                                return Err(self
                                    .expected(&format!("`,` or `)` in the arguments of `{n}(`")));
                            }
                        }
                    }
                    return Ok(Expr::Call {
                        function: n,
                        arguments,
                        clock: None,
                    });
                }
                Ok(match n.as_str() {
                    "TRUE" | "true" => Expr::Bool(true),
                    "FALSE" | "false" => Expr::Bool(false),
                    _ => Expr::Name(n),
                })
            }
            Some(CodeToken::Punct("(")) => {
                self.at += 1;
                let inner = self.expression()?;
                if !self.eat(")") {
                    return Err(self.expected("`)` or an operator"));
                }
                Ok(inner)
            }
            _ => Err(self.expected("a name, a number, a string, `(`, `!` or `-`")),
        }
    }

    /// One statement; `None` for an empty one (`;`).
    fn statement(&mut self) -> Parsed<Option<Statement>> {
        self.nested(Self::one_statement)
    }

    fn one_statement(&mut self) -> Parsed<Option<Statement>> {
        if self.eat(";") {
            return Ok(None);
        }
        if self.eat("{") {
            let mut body = Vec::new();
            while !self.eat("}") {
                if self.peek().is_none() {
                    return Err(self.expected("`}` to close the block"));
                }
                if let Some(s) = self.statement()? {
                    body.push(s);
                }
            }
            return Ok(Some(Statement::Block(body)));
        }
        let statement = match (self.peek(), self.peek_at(1)) {
            (Some(CodeToken::Name(k)), Some(CodeToken::Punct("("))) if k == "for" => {
                return self.for_loop().map(Some)
            }
            (Some(CodeToken::Name(k)), Some(CodeToken::Name(_))) if k == "extern" => {
                self.at += 1;
                let ty = match (self.peek(), self.peek_at(1)) {
                    (Some(CodeToken::Name(t)), Some(CodeToken::Name(_))) => {
                        let ty = type_of(t);
                        self.at += 1;
                        Some(ty)
                    }
                    _ => None,
                };
                Statement::Extern {
                    ty,
                    name: self.name()?,
                }
            }
            _ => self.simple()?,
        };
        self.terminator()?;
        Ok(Some(statement))
    }

    /// A declaration, an assignment or an expression, without its `;`.
    fn simple(&mut self) -> Parsed<Statement> {
        match (self.peek(), self.peek_at(1)) {
            (Some(CodeToken::Name(t)), Some(CodeToken::Name(_))) => {
                let ty = type_of(t);
                self.at += 1;
                let name = self.name()?;
                let value = if self.eat("=") {
                    Some(self.expression()?)
                } else {
                    None
                };
                Ok(Statement::Declare { ty, name, value })
            }
            (Some(CodeToken::Name(n)), Some(CodeToken::Punct("="))) => {
                let name = n.clone();
                self.at += 2;
                Ok(Statement::Assign {
                    name,
                    value: self.expression()?,
                })
            }
            _ => Ok(Statement::Expr(self.expression()?)),
        }
    }

    /// `;`, which may be left out before a block's `}` or at the end of the text.
    fn terminator(&mut self) -> Parsed<()> {
        if self.eat(";") || self.is("}") || self.peek().is_none() {
            Ok(())
        } else if matches!(self.peek(), Some(CodeToken::Punct(p)) if BinOp::from_symbol(p).is_some() || *p == "=")
        {
            Err(self.expected("`;` or an operator"))
        } else {
            Err(self.expected("`;`"))
        }
    }

    fn for_loop(&mut self) -> Parsed<Statement> {
        self.at += 1; // `for`
        self.expect("(")?;
        let init = if self.is(";") {
            None
        } else {
            Some(Box::new(self.simple()?))
        };
        self.expect(";")?;
        let condition = if self.is(";") {
            None
        } else {
            Some(self.expression()?)
        };
        self.expect(";")?;
        let step = if self.is(")") {
            None
        } else {
            Some(Box::new(self.simple()?))
        };
        self.expect(")")?;
        let body = match self.statement()? {
            Some(s) => s,
            None => Statement::Block(Vec::new()),
        };
        Ok(Statement::For {
            init,
            condition,
            step,
            body: Box::new(body),
        })
    }
}

fn type_of(word: &str) -> VarType {
    VarType::keyword(word).unwrap_or_else(|| VarType::Named(word.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parses, prints, and checks the printed form parses to the same tree.
    fn expr(text: &str) -> String {
        let e = parse_expression(text).unwrap_or_else(|err| panic!("{text}: {err}"));
        let printed = e.to_string();
        assert_eq!(parse_expression(&printed).as_ref(), Ok(&e), "{printed}");
        printed
    }

    fn error(text: &str) -> String {
        parse_expression(text).unwrap_err().to_string()
    }

    fn stmts(text: &str) -> String {
        let s = parse_statements(text).unwrap_or_else(|err| panic!("{text}: {err}"));
        let printed: Vec<String> = s.iter().map(ToString::to_string).collect();
        let printed = printed.join(" ");
        assert_eq!(parse_statements(&printed).as_ref(), Ok(&s), "{printed}");
        printed
    }

    #[test]
    fn labels_the_team_wrote() {
        for (input, expect) in [
            ("HeadYaw<-boundaryLeftRight", "HeadYaw < -boundaryLeftRight"),
            (
                "loopCounter==2*(loopCounter/2)",
                "loopCounter == 2 * (loopCounter / 2)",
            ),
            ("!(x<(-y))", "~(x < -y)"),
            ("timeout((a*b)/2)", "timeout(a * b / 2)"),
            ("a - (b - c)", "a - (b - c)"),
            ("a && (b || c) && !d", "a && (b || c) && ~d"),
            ("1", "1"),
            ("TRUE", "TRUE"),
            ("- -x", "--x"),
            ("-(-1)", "1"),
            // Found by the fuzzer: `-+6` printed as `-6`, which read back as another tree.
            ("-+6", "-6"),
            ("-(2.5)", "-2.5"),
            (
                "timeout(500ms) || after(2s) || after_ms(1.5s)",
                "timeout(500ms) || after(2s) || after_ms(1500ms)",
            ),
            ("timeout(250us)", "timeout(250us)"),
            ("x > -1 && abs(a - b) >= 0.5", "x > -1 && abs(a - b) >= 0.5"),
            ("f(1, \"two\", g())", "f(1, \"two\", g())"),
        ] {
            assert_eq!(expr(input), expect, "{input}");
        }
    }

    #[test]
    fn errors_say_what_was_expected_and_what_was_found() {
        assert!(
            error("2E999 != 1").contains("`2E999` is too large for a number"),
            "{}",
            error("2E999 != 1")
        );
        assert_eq!(
            error("a && "),
            "expected a name, a number, a string, `(`, `!` or `-`, found the end (at column 6)"
        );
        assert_eq!(
            error("(a || b"),
            "expected `)` or an operator, found the end (at column 8)"
        );
        assert_eq!(
            error("x = 1"),
            "expected an operator or the end of the expression, found `=`; `=` assigns: compare with `==` (at column 3)"
        );
        assert_eq!(
            error("f(a b)"),
            "expected `,` or `)` in the arguments of `f(`, found `b` (at column 5)"
        );
    }

    #[test]
    fn nesting_past_the_bound_is_an_error_at_its_place_not_a_stack_overflow() {
        let deep = |open: &str, inner: &str, close: &str, n: usize| {
            format!("{}{inner}{}", open.repeat(n), close.repeat(n))
        };
        let chain = |n: usize| vec!["a"; n].join(" || ");
        // What people write, and well beyond it, reads.
        for text in [deep("(", "a", ")", 60), deep("!", "a", "", 100), chain(200)] {
            assert!(parse_expression(&text).is_ok(), "{text}");
        }
        for text in [
            deep("(", "a", ")", 20_000),
            deep("!", "a", "", 20_000),
            deep("-(", "a", ")", 20_000),
            chain(6_000),
            deep("f(", "a", ")", 20_000),
        ] {
            let err = parse_expression(&text).unwrap_err();
            assert!(
                err.message.starts_with("nested more than 256 levels deep"),
                "{err}"
            );
            assert!(err.offset < text.len() / 2, "{err}");
        }
        let blocks = deep("{ ", "x = 1;", " }", 20_000);
        let err = parse_statements(&blocks).unwrap_err();
        assert!(err.message.starts_with("nested more than"), "{err}");
        let body = deep("for (;;) ", "x = 1;", "", 20_000);
        assert!(parse_statements(&body).is_err());
    }

    #[test]
    fn statements_the_team_wrote() {
        for (input, expect) in [
            (
                "int currentTime; extern  buttonPushed; currentTime=0;",
                "int currentTime; extern buttonPushed; currentTime = 0;",
            ),
            ("kickOffTeam=!kickOffTeam", "kickOffTeam = !kickOffTeam;"),
            (
                "postv(\"gunaowalk_walk\", 100, corrYaw, corrYaw, 100);",
                "postv(\"gunaowalk_walk\", 100, corrYaw, corrYaw, 100);",
            ),
            (
                "for (i = 0; i < 3; i = i + 1) { post(\"Beep\", i); }",
                "for (i = 0; i < 3; i = i + 1) { post(\"Beep\", i); }",
            ),
            (
                "float speed = .5; ;; { a = 1 }",
                "float speed = 0.5; { a = 1; }",
            ),
            ("extern int x;", "extern int x;"),
            ("timeLeft = 0 < currentTime;", "timeLeft = 0 < currentTime;"),
        ] {
            assert_eq!(stmts(input), expect, "{input}");
        }
    }

    #[test]
    fn statement_errors_have_their_place() {
        let e = parse_statements("a = 1 b = 2;").unwrap_err();
        assert_eq!(e.to_string(), "expected `;`, found `b` (at column 7)");
        let e = parse_statements("for (i = 0; i < 3) {}").unwrap_err();
        assert_eq!(e.to_string(), "expected `;`, found `)` (at column 18)");
        let e = parse_statements("{ a = 1;").unwrap_err();
        assert!(e.message.contains("`}` to close the block"));
    }
}
