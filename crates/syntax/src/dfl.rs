//! SPINdle's `.dfl` theory format, read into the same syntax tree as `.dl`, so that theories
//! written for other reasoners run unchanged.
//!
//! One statement a line: `>> a` (fact), `r1: a, -b => c` (rule; `->` strict, `~>` defeater),
//! `r1 > r2` (superiority); `-` negates; `#` starts a comment.

use crate::ast::{Arrow, Item, Lit, RuleItem};
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
    let mut offset = 0;
    let mut tokens = Vec::new();
    let mut broken_labels = Vec::new();
    for line in source.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let code = line.split('#').next().unwrap_or("");
        tokens.clear();
        tokenize(code, start, &mut tokens);
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

fn tokenize(code: &str, base: usize, out: &mut Vec<(T, Span)>) {
    let bytes = code.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        let start = i;
        let two = bytes.get(i..i + 2);
        let t = match bytes[i] {
            b if b.is_ascii_whitespace() => {
                i += 1;
                continue;
            }
            _ if two == Some(b">>") => {
                i += 2;
                T::Facts
            }
            _ if two == Some(b"->") => {
                i += 2;
                T::Arrow(Arrow::Strict)
            }
            _ if two == Some(b"=>") => {
                i += 2;
                T::Arrow(Arrow::Defeasible)
            }
            _ if two == Some(b"~>") => {
                i += 2;
                T::Arrow(Arrow::Warning)
            }
            b',' => {
                i += 1;
                T::Comma
            }
            b':' => {
                i += 1;
                T::Colon
            }
            b'>' => {
                i += 1;
                T::Gt
            }
            b'-' | b'~' | b'!' => {
                i += 1;
                T::Not
            }
            b if b.is_ascii_alphanumeric() || b == b'_' => {
                // SPINdle allows predicate-style atoms `p(x, y)`: the parenthesised part is kept
                // in the atom's name.
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                if bytes.get(i) == Some(&b'(') {
                    match bytes[i..].iter().position(|&b| b == b')') {
                        Some(p) => i += p + 1,
                        None => {
                            i = bytes.len();
                            out.push((T::Bad, Span::new(base + start, base + i)));
                            continue;
                        }
                    }
                }
                T::Word
            }
            _ => {
                i += 1;
                while i < bytes.len() && !code.is_char_boundary(i) {
                    i += 1;
                }
                T::Bad
            }
        };
        out.push((t, Span::new(base + start, base + i)));
    }
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
            let mut labels = vec![*first];
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
        _ => {
            let Some(arrow_at) = rest.iter().position(|(t, _)| matches!(t, T::Arrow(_))) else {
                return Err(Diagnostic::error(whole, "not a SPINdle statement")
                    .with_label("no `=>`, `->`, `~>`, `>>` or `>` here")
                    .with_hint("rules are `r1: a, b => c`, facts `>> a`, superiority `r1 > r2`"));
            };
            let T::Arrow(arrow) = rest[arrow_at].0 else {
                unreachable!("position matched an arrow")
            };
            let body = literals(&rest[..arrow_at], whole, source)?;
            let head = literals(&rest[arrow_at + 1..], whole, source)?;
            match head.as_slice() {
                [head] => Ok(Item::Rule(RuleItem {
                    label,
                    body,
                    arrow,
                    head: *head,
                    span: whole,
                })),
                [] => Err(
                    Diagnostic::error(rest[arrow_at].1, "rule has no consequent")
                        .with_label("a literal must follow the arrow"),
                ),
                [_, second, ..] => Err(Diagnostic::error(
                    second.span,
                    "rule has more than one consequent",
                )
                .with_hint("write one rule for each consequent")),
            }
        }
    }
}

fn literals(tokens: &[(T, Span)], whole: Span, _source: &str) -> Result<Vec<Lit>, Diagnostic> {
    let mut lits = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let (negated, at) = match tokens[i] {
            (T::Not, _) => (true, i + 1),
            _ => (false, i),
        };
        match tokens.get(at) {
            Some(&(T::Word, atom)) => lits.push(Lit {
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
    Ok(lits)
}
