//! Transition labels: `TRUE`, atoms, `~atom`, and what the team's real machines use: `!a`, `&&`,
//! `||`, parentheses, `1`/`0`, `timeout(µs)` since entering the state, and numeric comparisons
//! of whiteboard values (`x==0`, `x<180`, `x>-1`, `a==fwdAngle`).

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Label {
    True,
    False,
    /// A proposition an expert proclaims.
    Atom(String),
    Not(Box<Label>),
    And(Vec<Label>),
    Or(Vec<Label>),
    /// True once the machine has been in the state this long (µs; a name is a whiteboard value).
    Timeout(Operand),
    Compare {
        left: Operand,
        op: CmpOp,
        right: Operand,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub enum Operand {
    Number(f64),
    /// A whiteboard value by its message type.
    Value(String),
    /// A function of a value, such as `abs(x)` (the interpreter knows which functions exist).
    Call {
        function: String,
        argument: Box<Operand>,
    },
    /// Arithmetic: `delay * 1000`; `op` is one of `+ - * /`.
    Arith {
        left: Box<Operand>,
        op: char,
        right: Box<Operand>,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CmpOp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

impl CmpOp {
    fn symbol(self) -> &'static str {
        match self {
            CmpOp::Eq => "==",
            CmpOp::Ne => "!=",
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }
}

/// Where and why a label did not parse (`offset` in bytes into the label).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LabelError {
    pub offset: usize,
    pub message: String,
}

impl fmt::Display for LabelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at column {})", self.message, self.offset + 1)
    }
}

impl Label {
    /// The atoms an expert must answer for this label, in order, once each.
    pub fn atoms(&self) -> Vec<&str> {
        let mut out = Vec::new();
        self.collect_atoms(&mut out);
        out
    }

    fn collect_atoms<'a>(&'a self, out: &mut Vec<&'a str>) {
        match self {
            Label::Atom(a) if !out.contains(&a.as_str()) => out.push(a),
            Label::Not(l) => l.collect_atoms(out),
            Label::And(ls) | Label::Or(ls) => ls.iter().for_each(|l| l.collect_atoms(out)),
            _ => {}
        }
    }

    fn precedence(&self) -> u8 {
        match self {
            Label::Or(_) => 1,
            Label::And(_) => 2,
            _ => 3,
        }
    }

    fn write_operand(f: &mut fmt::Formatter<'_>, label: &Label, min: u8) -> fmt::Result {
        if label.precedence() < min {
            write!(f, "({label})")
        } else {
            write!(f, "{label}")
        }
    }
}

impl fmt::Display for Operand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Operand::Number(n) => write!(f, "{n}"),
            Operand::Value(v) => f.write_str(v),
            Operand::Call { function, argument } => write!(f, "{function}({argument})"),
            Operand::Arith { left, op, right } => {
                let side = |f: &mut fmt::Formatter<'_>, o: &Operand, tight: bool| match o {
                    Operand::Arith { op: inner, .. }
                        if tight
                            || (*op == '*' || *op == '/') && (*inner == '+' || *inner == '-') =>
                    {
                        write!(f, "({o})")
                    }
                    _ => write!(f, "{o}"),
                };
                side(f, left, false)?;
                write!(f, " {op} ")?;
                side(f, right, true)
            }
        }
    }
}

/// The canonical form: `~` for not, `&&`, `||`, parentheses only where needed. Parsing it gives
/// the same label back.
impl fmt::Display for Label {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Label::True => f.write_str("TRUE"),
            Label::False => f.write_str("FALSE"),
            Label::Atom(a) => f.write_str(a),
            Label::Not(inner) => {
                f.write_str("~")?;
                Label::write_operand(f, inner, 3)
            }
            Label::And(ls) | Label::Or(ls) => {
                let (op, min) = if matches!(self, Label::And(_)) {
                    (" && ", 3)
                } else {
                    (" || ", 2)
                };
                for (i, l) in ls.iter().enumerate() {
                    if i > 0 {
                        f.write_str(op)?;
                    }
                    Label::write_operand(f, l, min)?;
                }
                Ok(())
            }
            Label::Timeout(t) => write!(f, "timeout({t})"),
            Label::Compare { left, op, right } => write!(f, "{left} {} {right}", op.symbol()),
        }
    }
}

/// Parses a label. An empty label is `TRUE` (Qfsm writes no inputs for an unconditional
/// transition).
pub fn parse_label(text: &str) -> Result<Label, LabelError> {
    let mut p = Parser { text, at: 0 };
    p.skip_space();
    if p.at == text.len() {
        return Ok(Label::True);
    }
    let label = p.or()?;
    p.skip_space();
    if p.at < text.len() {
        return Err(p.error(format!(
            "unexpected `{}`",
            &text[p.at..].chars().next().unwrap_or(' ')
        )));
    }
    Ok(label)
}

struct Parser<'t> {
    text: &'t str,
    at: usize,
}

impl Parser<'_> {
    fn error(&self, message: impl Into<String>) -> LabelError {
        LabelError {
            offset: self.at,
            message: message.into(),
        }
    }

    fn skip_space(&mut self) {
        while self.text[self.at..].starts_with(char::is_whitespace) {
            self.at += self.text[self.at..]
                .chars()
                .next()
                .map_or(1, char::len_utf8);
        }
    }

    fn eat(&mut self, token: &str) -> bool {
        self.skip_space();
        if self.text[self.at..].starts_with(token) {
            self.at += token.len();
            true
        } else {
            false
        }
    }

    fn or(&mut self) -> Result<Label, LabelError> {
        let mut parts = vec![self.and()?];
        while self.eat("||") {
            parts.push(self.and()?);
        }
        Ok(if parts.len() == 1 {
            parts.pop().expect("one part")
        } else {
            Label::Or(parts)
        })
    }

    fn and(&mut self) -> Result<Label, LabelError> {
        let mut parts = vec![self.unary()?];
        while self.eat("&&") {
            parts.push(self.unary()?);
        }
        Ok(if parts.len() == 1 {
            parts.pop().expect("one part")
        } else {
            Label::And(parts)
        })
    }

    fn unary(&mut self) -> Result<Label, LabelError> {
        self.skip_space();
        let rest = &self.text[self.at..];
        if (rest.starts_with('!') && !rest.starts_with("!=")) || rest.starts_with('~') {
            self.at += 1;
            return Ok(Label::Not(Box::new(self.unary()?)));
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<Label, LabelError> {
        if self.eat("(") {
            let inner = self.or()?;
            if !self.eat(")") {
                return Err(self.error("missing `)`"));
            }
            return Ok(inner);
        }
        let start = self.at;
        let left = self.operand()?;
        self.skip_space();
        let rest = &self.text[self.at..];
        let op = [
            ("==", CmpOp::Eq),
            ("!=", CmpOp::Ne),
            ("<=", CmpOp::Le),
            (">=", CmpOp::Ge),
            ("<", CmpOp::Lt),
            (">", CmpOp::Gt),
        ]
        .into_iter()
        .find(|(s, _)| rest.starts_with(s));
        if let Some((symbol, op)) = op {
            self.at += symbol.len();
            let right = self.operand()?;
            return Ok(Label::Compare { left, op, right });
        }
        Ok(match left {
            Operand::Call { function, argument } if function == "timeout" => Label::Timeout(*argument),
            Operand::Call { function, .. } => {
                return Err(LabelError {
                    offset: start,
                    message: format!("`{function}(…)` is a number, not a label; compare it, as in `{function}(x) > 4`"),
                })
            }
            Operand::Arith { .. } => {
                return Err(LabelError { offset: start, message: "arithmetic is a number, not a label; compare it, as in `x - y > 0`".into() })
            }
            Operand::Value(name) if name == "TRUE" || name == "true" => Label::True,
            Operand::Value(name) if name == "FALSE" || name == "false" => Label::False,
            Operand::Value(name) => Label::Atom(name),
            Operand::Number(0.0) => Label::False,
            Operand::Number(_) => Label::True,
        })
    }

    /// `a + b * c`, left-associative, `*` and `/` binding tighter.
    fn operand(&mut self) -> Result<Operand, LabelError> {
        self.arithmetic(['+', '-'], |p| {
            p.arithmetic(['*', '/'], Parser::atom_operand)
        })
    }

    /// One precedence level: `next (op next)*` for the two operators of the level.
    fn arithmetic(
        &mut self,
        ops: [char; 2],
        next: impl Fn(&mut Self) -> Result<Operand, LabelError>,
    ) -> Result<Operand, LabelError> {
        let mut left = next(self)?;
        loop {
            self.skip_space();
            let Some(op) = self.text[self.at..]
                .chars()
                .next()
                .filter(|c| ops.contains(c))
            else {
                return Ok(left);
            };
            self.at += 1;
            let right = next(self)?;
            left = Operand::Arith {
                left: Box::new(left),
                op,
                right: Box::new(right),
            };
        }
    }

    fn atom_operand(&mut self) -> Result<Operand, LabelError> {
        self.skip_space();
        let rest = &self.text[self.at..];
        let number_len = rest
            .char_indices()
            .take_while(|&(i, c)| c.is_ascii_digit() || c == '.' || (i == 0 && c == '-'))
            .count();
        if number_len > 0 && rest[..number_len] != *"-" {
            return match rest[..number_len].parse() {
                Ok(n) => {
                    self.at += number_len;
                    Ok(Operand::Number(n))
                }
                Err(_) => Err(self.error(format!("`{}` is not a number", &rest[..number_len]))),
            };
        }
        let name_len = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .map(char::len_utf8)
            .sum::<usize>();
        if name_len == 0 || rest.starts_with(|c: char| c.is_ascii_digit()) {
            return Err(self.error(match rest.chars().next() {
                Some(c) => format!("expected an atom, a number or `(`, found `{c}`"),
                None => "the label ends too early".to_string(),
            }));
        }
        self.at += name_len;
        let name = rest[..name_len].to_string();
        if self.eat("(") {
            let argument = self.operand()?;
            if !self.eat(")") {
                return Err(self.error(format!("missing `)` after `{name}(`")));
            }
            return Ok(Operand::Call {
                function: name,
                argument: Box::new(argument),
            });
        }
        Ok(Operand::Value(name))
    }
}
