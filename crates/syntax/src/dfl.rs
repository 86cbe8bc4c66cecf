//! SPINdle's `.dfl` theory format, read into the same syntax tree as `.dl`, so that theories
//! written for other reasoners run unchanged.
//!
//! One statement a line: `>> a` (fact), `r1: a, -b => c` (rule; `->` strict, `~>` defeater),
//! `r1 > r2` (superiority); `-` negates; `#` starts a comment.

use crate::ast::{Arrow, Item, RuleItem, SourceLiteral};
use crate::diagnostic::{Diagnostic, Sink};
use crate::parse::ParsedTheory;
use crate::span::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum T {
    Word,
    Comma,
    Colon,
    Facts,
    Gt,
    Not,
    Arrow(Arrow),
    Bad,
}

/// Parses a whole `.dfl` text. Never fails.
pub fn parse_dfl(source: &str) -> ParsedTheory {
    let mut items = Vec::new();
    let mut parsed = parse_dfl_each(source, |item| items.push(item));
    parsed.items = items;
    parsed
}

/// Parses a whole `.dfl` text, handing each statement to `on_item` as soon as it is parsed (so
/// a later stage can work at the same time); the result holds the diagnostics and no items.
pub fn parse_dfl_each(source: &str, mut on_item: impl FnMut(Item)) -> ParsedTheory {
    let mut sink = Sink::default();
    if source.len() > u32::MAX as usize {
        sink.push(Diagnostic::error(
            Span::new(0, 0),
            "file is larger than 4 GiB",
        ));
        return ParsedTheory {
            items: Vec::new(),
            diagnostics: sink.finish(0),
            broken_labels: Vec::new(),
        };
    }
    let mut tokens = Vec::new();
    let mut broken_labels = Vec::new();
    let mut line = 0;
    while line < source.len() {
        tokens.clear();
        line = tokenize_line(source, line, &mut tokens);
        if tokens.is_empty() {
            continue;
        }
        match statement(&tokens, source) {
            Ok(item) => on_item(item),
            Err(d) => {
                if let [(T::Word, label), (T::Colon, _), ..] = tokens[..] {
                    broken_labels.push(label);
                }
                sink.push(d)
            }
        }
    }
    ParsedTheory {
        items: Vec::new(),
        diagnostics: sink.finish(source.len()),
        broken_labels,
    }
}

/// The tokens of the line beginning at `start`, up to its `#` comment if it has one; returns
/// where the next line begins. One pass over the bytes: lines and comments are found as the
/// tokens are.
fn tokenize_line(source: &str, start: usize, out: &mut Vec<(T, Span)>) -> usize {
    let bytes = source.as_bytes();
    let line_end = |from: usize| {
        bytes[from..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |p| from + p + 1)
    };
    let mut i = start;
    while i < bytes.len() {
        let from = i;
        // By the first byte, atoms' bytes (nearly all of a file) first; a second `>` makes
        // the two-byte tokens.
        let then_gt = bytes.get(i + 1) == Some(&b'>');
        let (t, width) = match bytes[i] {
            b if b.is_ascii_alphanumeric() || b == b'_' => (T::Word, 0),
            b'\n' => return i + 1,
            b'#' => return line_end(i),
            b if b.is_ascii_whitespace() => {
                i += 1;
                continue;
            }
            b'>' if then_gt => (T::Facts, 2),
            b'-' if then_gt => (T::Arrow(Arrow::Strict), 2),
            b'=' if then_gt => (T::Arrow(Arrow::Defeasible), 2),
            b'~' if then_gt => (T::Arrow(Arrow::Warning), 2),
            b',' => (T::Comma, 1),
            b':' => (T::Colon, 1),
            b'>' => (T::Gt, 1),
            b'-' | b'~' | b'!' => (T::Not, 1),
            _ => (T::Bad, 1),
        };
        i += width;
        let t = match t {
            T::Word => {
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                // SPINdle allows predicate-style atoms `p(x, y)`: the parenthesised part is kept
                // in the atom's name. Unclosed before the comment or the line ends, the rest of
                // the line (its newline too) is one bad token.
                if bytes.get(i) == Some(&b'(') {
                    let stop = bytes[i..]
                        .iter()
                        .position(|&b| matches!(b, b')' | b'#' | b'\n'))
                        .map(|p| (i + p, bytes[i + p]));
                    match stop {
                        Some((close, b')')) => i = close + 1,
                        Some((newline, b'\n')) => {
                            out.push((T::Bad, Span::new(from, newline + 1)));
                            return newline + 1;
                        }
                        Some((comment, _)) => {
                            out.push((T::Bad, Span::new(from, comment)));
                            return line_end(comment);
                        }
                        None => {
                            out.push((T::Bad, Span::new(from, bytes.len())));
                            return bytes.len();
                        }
                    }
                }
                T::Word
            }
            T::Bad => {
                while i < bytes.len() && !source.is_char_boundary(i) {
                    i += 1;
                }
                T::Bad
            }
            t => t,
        };
        out.push((t, Span::new(from, i)));
    }
    bytes.len()
}

fn statement(tokens: &[(T, Span)], source: &str) -> Result<Item, Diagnostic> {
    if let Some(&(_, span)) = tokens.iter().find(|(t, _)| *t == T::Bad) {
        return Err(Diagnostic::error(span, "unexpected characters")
            .with_label("not part of a SPINdle statement")
            .with_hint("atoms are letters, digits and `_`; `-` negates; `#` starts a comment"));
    }
    let whole = tokens[0].1.cover(tokens[tokens.len() - 1].1);
    let (label, rest) = match tokens {
        [(T::Word, l), (T::Colon, _), rest @ ..] => (Some(*l), rest),
        _ => (None, tokens),
    };
    match rest {
        [(T::Facts, _), lits @ ..] => {
            let lits = literals(lits, whole, source)?;
            if lits.is_empty() {
                return Err(
                    Diagnostic::error(whole, "`>>` names no fact").with_hint("write `>> a`")
                );
            }
            Ok(Item::Fact {
                clause: lits,
                span: whole,
            })
        }
        [(T::Word, first), (T::Gt, _), more @ ..] if label.is_none() => {
            priority(*first, more, whole)
        }
        _ => rule(label, rest, whole, source),
    }
}

/// A superiority relation `r1 > r2 > …`, `first` and its `>` already read.
fn priority(first: Span, more: &[(T, Span)], whole: Span) -> Result<Item, Diagnostic> {
    let mut labels = vec![first];
    let mut rest = more;
    loop {
        match rest {
            [(T::Word, l)] => {
                labels.push(*l);
                break;
            }
            [(T::Word, l), (T::Gt, _), tail @ ..] => {
                labels.push(*l);
                rest = tail;
            }
            _ => {
                return Err(Diagnostic::error(whole, "malformed superiority relation")
                    .with_hint("write `r1 > r2`"))
            }
        }
    }
    Ok(Item::Priority {
        labels,
        span: whole,
    })
}

/// A rule `[label:] body ARROW head`, the label already read.
fn rule(
    label: Option<Span>,
    rest: &[(T, Span)],
    whole: Span,
    source: &str,
) -> Result<Item, Diagnostic> {
    let Some(arrow_at) = rest.iter().position(|(t, _)| matches!(t, T::Arrow(_))) else {
        return Err(Diagnostic::error(whole, "not a SPINdle statement")
            .with_label("no `=>`, `->`, `~>`, `>>` or `>` here")
            .with_hint("rules are `r1: a, b => c`, facts `>> a`, superiority `r1 > r2`"));
    };
    let T::Arrow(arrow) = rest[arrow_at].0 else {
        unreachable!("position matched an arrow")
    };
    let body = literals(&rest[..arrow_at], whole, source)?;
    // The consequent is one literal: read without a vector to hold it.
    let (mut head, mut second) = (None, None);
    each_literal(&rest[arrow_at + 1..], whole, |lit| match head {
        None => head = Some(lit),
        Some(_) => {
            second.get_or_insert(lit);
        }
    })?;
    match (head, second) {
        (Some(head), None) => Ok(Item::Rule(RuleItem {
            label,
            body,
            arrow,
            head,
            span: whole,
        })),
        (None, _) => Err(
            Diagnostic::error(rest[arrow_at].1, "rule has no consequent")
                .with_label("a literal must follow the arrow"),
        ),
        (Some(_), Some(second)) => Err(Diagnostic::error(
            second.span,
            "rule has more than one consequent",
        )
        .with_hint("write one rule for each consequent")),
    }
}

fn literals(
    tokens: &[(T, Span)],
    whole: Span,
    _source: &str,
) -> Result<Vec<SourceLiteral>, Diagnostic> {
    // A literal is at least one token and a comma parts two: room for all of them at once.
    let mut lits = Vec::with_capacity(tokens.len().div_ceil(2));
    each_literal(tokens, whole, |lit| lits.push(lit))?;
    Ok(lits)
}

/// Hands each literal of a comma-separated list to `on_lit`, in order, or says what is wrong.
fn each_literal(
    tokens: &[(T, Span)],
    whole: Span,
    mut on_lit: impl FnMut(SourceLiteral),
) -> Result<(), Diagnostic> {
    let mut i = 0;
    while i < tokens.len() {
        let (negated, at) = match tokens[i] {
            (T::Not, _) => (true, i + 1),
            _ => (false, i),
        };
        match tokens.get(at) {
            Some(&(T::Word, atom)) => on_lit(SourceLiteral {
                negated,
                atom,
                span: tokens[i].1.cover(atom),
            }),
            Some(&(_, span)) => {
                return Err(Diagnostic::error(span, "expected a literal").with_label("here"))
            }
            None => {
                return Err(
                    Diagnostic::error(tokens[i].1, "expected an atom after the negation")
                        .with_related(whole, "in this statement"),
                )
            }
        }
        i = at + 1;
        match tokens.get(i) {
            None => {}
            Some((T::Comma, _)) => i += 1,
            Some(&(_, span)) => {
                return Err(
                    Diagnostic::error(span, "expected `,` between literals").with_label("here")
                )
            }
        }
    }
    Ok(())
}
