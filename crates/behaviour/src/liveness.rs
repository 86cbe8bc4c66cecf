//! Liveness formulas (the Kouretes paper, Section 3; Gaia's operators) read into formulas that
//! `skeleton.rs` draws as a behaviour: one machine for the first formula, one for each branch of
//! a `||`.
//!
//! ```text
//! TestBehavior = (Play | NoPlay)+
//! Play = SitDownAndStare | StandUpAndScan
//! ```
//!
//! Operators, loosest first: `A || B` (concurrently), `A | B` (one of them), `A . B` (A then B),
//! then `A*` (zero or more times), `A+` (one or more), `A~` (for ever), `[A]` (optional), and
//! parentheses. An activity defined by a formula of its own is a state holding that formula's
//! states; the others are basic activities. Every bad line is reported, with its line.

use proclaim_fsm::FileDiagnostic;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GaiaFormula {
    Activity(String),
    Sequence(Vec<GaiaFormula>),
    Choice(Vec<GaiaFormula>),
    Parallel(Vec<GaiaFormula>),
    /// `A*`
    Many(Box<GaiaFormula>),
    /// `A+`
    OneOrMore(Box<GaiaFormula>),
    /// `A~`
    Forever(Box<GaiaFormula>),
    /// `[A]`
    Optional(Box<GaiaFormula>),
}

/// One `Name = formula` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Definition {
    pub name: String,
    pub formula: GaiaFormula,
    pub line: usize,
}

/// Reads formulas, one a line (`#` and `//` comments). Every bad line is reported.
pub fn parse_liveness(file: &str, text: &str) -> (Vec<Definition>, Vec<FileDiagnostic>) {
    let mut defs = Vec::new();
    let mut diagnostics = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let code = raw.split('#').next().unwrap_or("");
        let code = code.split("//").next().unwrap_or("").trim();
        if code.is_empty() {
            continue;
        }
        let Some((name, formula)) = code.split_once('=') else {
            diagnostics.push(FileDiagnostic::error(
                file,
                line,
                "a formula is `Name = activities` (no `=` here)",
            ));
            continue;
        };
        let name = name.trim();
        if !is_name(name) {
            diagnostics.push(FileDiagnostic::error(
                file,
                line,
                format!("`{name}` is not an activity name (letters, digits, `_` and `-`)"),
            ));
            continue;
        }
        let mut p = Parser {
            tokens: tokenize(formula),
            at: 0,
        };
        match p.parallel().and_then(|f| match p.peek() {
            None => Ok(f),
            Some(t) => Err(format!("unexpected `{t}`")),
        }) {
            Ok(_) if defs.iter().any(|d: &Definition| d.name == name) => {
                diagnostics.push(FileDiagnostic::error(
                    file,
                    line,
                    format!("`{name}` is defined twice"),
                ));
            }
            Ok(formula) => defs.push(Definition {
                name: name.to_string(),
                formula,
                line,
            }),
            Err(message) => diagnostics.push(FileDiagnostic::error(
                file,
                line,
                format!("in the formula of `{name}`: {message}"),
            )),
        }
    }
    (defs, diagnostics)
}

fn is_name(text: &str) -> bool {
    text.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && text
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
}

fn tokenize(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '|' && chars.get(i + 1) == Some(&'|') {
            out.push("||".into());
            i += 2;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len()
                && (chars[i].is_alphanumeric() || chars[i] == '_' || chars[i] == '-')
            {
                i += 1;
            }
            out.push(chars[start..i].iter().collect());
        } else {
            // `∼` (the paper's tilde) reads as `~`.
            out.push(if c == '∼' {
                "~".into()
            } else {
                c.to_string()
            });
            i += 1;
        }
    }
    out
}

struct Parser {
    tokens: Vec<String>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&str> {
        self.tokens.get(self.at).map(String::as_str)
    }

    fn list(
        &mut self,
        op: &str,
        part: fn(&mut Parser) -> Result<GaiaFormula, String>,
        make: fn(Vec<GaiaFormula>) -> GaiaFormula,
    ) -> Result<GaiaFormula, String> {
        let mut parts = vec![part(self)?];
        while self.peek() == Some(op) {
            self.at += 1;
            parts.push(part(self)?);
        }
        Ok(if parts.len() == 1 {
            parts.remove(0)
        } else {
            make(parts)
        })
    }

    fn parallel(&mut self) -> Result<GaiaFormula, String> {
        self.list("||", Parser::choice, GaiaFormula::Parallel)
    }

    fn choice(&mut self) -> Result<GaiaFormula, String> {
        self.list("|", Parser::sequence, GaiaFormula::Choice)
    }

    fn sequence(&mut self) -> Result<GaiaFormula, String> {
        self.list(".", Parser::postfix, GaiaFormula::Sequence)
    }

    fn postfix(&mut self) -> Result<GaiaFormula, String> {
        let mut f = self.atom()?;
        loop {
            f = match self.peek() {
                Some("*") => GaiaFormula::Many(Box::new(f)),
                Some("+") => GaiaFormula::OneOrMore(Box::new(f)),
                Some("~") => GaiaFormula::Forever(Box::new(f)),
                _ => return Ok(f),
            };
            self.at += 1;
        }
    }

    fn atom(&mut self) -> Result<GaiaFormula, String> {
        let Some(token) = self.peek().map(str::to_string) else {
            return Err("the formula ends too early".into());
        };
        self.at += 1;
        match token.as_str() {
            "(" => {
                let f = self.parallel()?;
                self.expect(")")?;
                Ok(f)
            }
            "[" => {
                let f = self.parallel()?;
                self.expect("]")?;
                Ok(GaiaFormula::Optional(Box::new(f)))
            }
            name if is_name(name) => Ok(GaiaFormula::Activity(name.to_string())),
            other => Err(format!("expected an activity, `(` or `[`, found `{other}`")),
        }
    }

    fn expect(&mut self, token: &str) -> Result<(), String> {
        match self.peek() {
            Some(t) if t == token => {
                self.at += 1;
                Ok(())
            }
            Some(t) => Err(format!("expected `{token}`, found `{t}`")),
            None => Err(format!("missing `{token}`")),
        }
    }
}
