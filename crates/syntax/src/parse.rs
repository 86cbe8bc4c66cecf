//! The .dl parser driver: splits the token stream into statements and parses each one, so that
//! every problem in a file is reported at once and parsing never fails.

use crate::ast::{Item, Query};
use crate::diagnostic::{Diagnostic, Sink};
use crate::fast_path::common_statement;
use crate::grammar::{QueryParser, StatementParser};
use crate::lexer::{lex, Lexer, Tok, Token};
use crate::span::Span;
use lalrpop_util::ParseError;

/// A theory file as written, with every problem found in it. Never fails: whatever parsed is in
/// `items`, whatever did not is in `diagnostics`.
#[derive(Debug, Default)]
pub struct ParsedTheory {
    pub items: Vec<Item>,
    pub diagnostics: Vec<Diagnostic>,
    /// Labels of rules whose statement did not parse (`R1: a b => c.`), so that later stages do
    /// not report them again as undefined.
    pub broken_labels: Vec<Span>,
}

impl ParsedTheory {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// An error raised from inside a grammar action.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UserError {
    pub span: Span,
    pub message: String,
    pub hint: Option<String>,
}

impl UserError {
    pub fn new(span: Span, message: String, hint: Option<String>) -> UserError {
        UserError {
            span,
            message,
            hint,
        }
    }
}

/// An identifier with its place, as the grammar hands it around.
#[derive(Clone, Copy, Debug)]
pub struct NameTok<'a> {
    pub text: &'a str,
    pub span: Span,
}

/// Parses a whole `.dl` text.
pub fn parse_dl(source: &str) -> ParsedTheory {
    // About 25 bytes a statement in generated theories; a guess that saves regrowing.
    let mut items = Vec::with_capacity(source.len() / 32);
    let mut parsed = parse_dl_each(source, |item| items.push(item));
    parsed.items = items;
    parsed
}

/// Parses a whole `.dl` text, handing each statement to `on_item` as soon as it is parsed (so a
/// later stage can work at the same time); the result holds the diagnostics and no items.
pub fn parse_dl_each(source: &str, mut on_item: impl FnMut(Item)) -> ParsedTheory {
    if source.len() > u32::MAX as usize {
        return too_large();
    }
    let mut lexer = Lexer::new(source);
    let parser = StatementParser::new();
    let mut sink = Sink::default();
    // Labels written in statements that did not parse (a missing `.` runs two statements
    // together, `R1: a => b  Doubt: c => d.`, so every label inside counts), so that
    // priorities naming them stay quiet.
    let mut broken_labels = Vec::new();
    let mut statement: Vec<Token<'_>> = Vec::new();
    loop {
        let terminated = next_statement(&mut lexer, &mut statement);
        if statement.is_empty() {
            break;
        }
        if report_bad_tokens(&statement, &mut sink) {
            broken_labels.extend(labels_written_in(&statement));
            continue;
        }
        if !terminated {
            broken_labels.extend(labels_written_in(&statement));
            sink.push(missing_dot(&statement));
            continue;
        }
        let parsed = match common_statement(&statement) {
            Some(item) => Ok(item),
            None => parser.parse(triples(&statement)),
        };
        match parsed {
            Ok(item) => on_item(item),
            Err(error) => {
                broken_labels.extend(labels_written_in(&statement));
                sink.push(to_diagnostic(error, source, &statement))
            }
        }
    }
    ParsedTheory {
        items: Vec::new(),
        diagnostics: sink.finish(source.len()),
        broken_labels,
    }
}

/// Reads the tokens up to and including the next `.` into `statement` (emptied first); false
/// when the text ended before a `.`.
fn next_statement<'a>(lexer: &mut Lexer<'a>, statement: &mut Vec<Token<'a>>) -> bool {
    statement.clear();
    for token in lexer.by_ref() {
        statement.push(token);
        if token.tok == Tok::Dot {
            return true;
        }
    }
    false
}

/// Every `label:` written in the statement.
fn labels_written_in<'s>(statement: &'s [Token<'_>]) -> impl Iterator<Item = Span> + 's {
    statement.windows(2).filter_map(|pair| match pair {
        [Token {
            tok: Tok::Ident(_),
            span,
        }, Token {
            tok: Tok::Colon, ..
        }] => Some(*span),
        _ => None,
    })
}

fn missing_dot(statement: &[Token<'_>]) -> Diagnostic {
    let last = statement[statement.len() - 1].span;
    Diagnostic::error(
        Span::new(last.end as usize, last.end as usize),
        "missing `.` at the end of the statement",
    )
    .with_label("the statement ends here")
    .with_hint("every statement (fact, rule, priority, directive) ends with `.`")
}

/// Parses a query given on the command line or through the library: `a`, `~a`, `\/{a, b}` or
/// `/\{a, \/{b, c}}`.
pub fn parse_query(text: &str) -> Result<Query, Vec<Diagnostic>> {
    let tokens = lex(text);
    let mut sink = Sink::default();
    if report_bad_tokens(&tokens, &mut sink) {
        return Err(sink.finish(text.len()));
    }
    if tokens.is_empty() {
        return Err(vec![Diagnostic::error(Span::new(0, 0), "empty query")
            .with_hint(
                "a query is a literal such as `offside` or `~offside`, or a clause `\\/{a, b}`",
            )]);
    }
    QueryParser::new()
        .parse(triples(&tokens))
        .map_err(|e| vec![to_diagnostic(e, text, &tokens)])
}

fn triples<'a, 's>(
    tokens: &'s [Token<'a>],
) -> impl Iterator<Item = Result<(usize, Tok<'a>, usize), UserError>> + 's {
    tokens
        .iter()
        .map(|t| Ok((t.span.start as usize, t.tok, t.span.end as usize)))
}

fn too_large() -> ParsedTheory {
    ParsedTheory {
        diagnostics: vec![
            Diagnostic::error(Span::new(0, 0), "file is larger than 4 GiB")
                .with_hint("split the theory into several files"),
        ],
        ..ParsedTheory::default()
    }
}

/// Reports lexer error tokens; true when the statement had any (it is then not parsed).
fn report_bad_tokens(statement: &[Token<'_>], sink: &mut Sink) -> bool {
    let mut bad = false;
    for token in statement {
        let diagnostic = match token.tok {
            Tok::Error => Diagnostic::error(token.span, "unexpected characters")
                .with_label("not part of any token")
                .with_hint("atoms are letters, digits and `_`, starting with a letter; comments start with `%` or `//`, or are written `/* … */`"),
            Tok::UnclosedStr => Diagnostic::error(token.span, "string has no closing `\"`")
                .with_label("starts here")
                .with_hint("close the string on the same line"),
            Tok::UnclosedComment => Diagnostic::error(Span::new(token.span.start as usize, token.span.start as usize + 2), "comment has no closing `*/`")
                .with_label("opened here")
                .with_hint("close the comment with `*/`"),
            _ => continue,
        };
        bad = true;
        sink.push(diagnostic);
    }
    bad
}

fn to_diagnostic(
    error: ParseError<usize, Tok<'_>, UserError>,
    source: &str,
    statement: &[Token<'_>],
) -> Diagnostic {
    match error {
        ParseError::User { error } => {
            let d = Diagnostic::error(error.span, error.message).with_label("here");
            match error.hint {
                Some(hint) => d.with_hint(hint),
                None => d,
            }
        }
        ParseError::UnrecognizedToken {
            token: (l, tok, r),
            expected,
        } => {
            let span = Span::new(l, r);
            let mut d = Diagnostic::error(span, format!("unexpected {}", tok.describe()))
                .with_label(expected_list(&expected));
            d.hint = hint_for(tok, &expected, source, statement, l);
            d
        }
        ParseError::ExtraToken { token: (l, tok, r) } => {
            Diagnostic::error(Span::new(l, r), format!("unexpected {}", tok.describe()))
                .with_label("nothing more was expected")
        }
        ParseError::UnrecognizedEof { location, expected } => {
            Diagnostic::error(Span::new(location, location), "the text ends too early")
                .with_label(expected_list(&expected))
        }
        ParseError::InvalidToken { location } => {
            Diagnostic::error(Span::new(location, location + 1), "unexpected characters")
        }
    }
}

fn expected_list(expected: &[String]) -> String {
    let mut names: Vec<String> = expected.iter().map(|e| terminal_name(e)).collect();
    names.sort();
    names.dedup();
    match names.len() {
        0 => "not expected here".to_string(),
        1 => format!("expected {}", names[0]),
        n if n <= 6 => format!("expected {} or {}", names[..n - 1].join(", "), names[n - 1]),
        _ => format!("expected {}, …", names[..5].join(", ")),
    }
}

fn terminal_name(terminal: &str) -> String {
    match terminal {
        "Ident" => "an atom".to_string(),
        "Str" => "a string".to_string(),
        "Num" => "a number".to_string(),
        quoted => {
            let inner = quoted.trim_matches('"').replace("\\\\", "\\");
            format!("`{inner}`")
        }
    }
}

fn hint_for(
    tok: Tok<'_>,
    expected: &[String],
    source: &str,
    statement: &[Token<'_>],
    at: usize,
) -> Option<String> {
    let expects = |t: &str| expected.iter().any(|e| e == t);
    let index = statement.iter().position(|t| t.span.start as usize == at)?;
    let previous = index.checked_sub(1).map(|i| statement[i]);
    if let Some(previous) = previous {
        let new_line = source[previous.span.end as usize..at].contains('\n');
        if new_line && expects("\".\"") {
            return Some("did you forget the `.` that ends the previous line's statement?".into());
        }
        if matches!(previous.tok, Tok::Ident(_)) && matches!(tok, Tok::Ident(_)) && expects("\",\"")
        {
            return Some("separate the literals of a rule's antecedent with `,`".into());
        }
    }
    if tok == Tok::Dot && (expects("\"=>\"") || expects("\"->\"")) {
        return Some("a rule needs an arrow: `->` strict, `=>` defeasible, `~>` warning".into());
    }
    None
}
