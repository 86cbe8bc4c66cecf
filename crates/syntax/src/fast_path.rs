//! The statements nearly every theory is made of (`a.`, `\/{~a, b}.`, `R1: a, ~b => c.`,
//! `R1 > R2.`) read straight off their tokens, without the LR parser: at a million statements
//! its stacks and symbols cost more than the reading. Anything else, and anything malformed, is
//! left to the grammar of record (`grammar.lalrpop`), which says what is wrong; a property test
//! holds the two to the same trees.

use crate::ast::{Arrow, Item, RuleItem, SourceLiteral};
use crate::lexer::{Tok, Token};
use crate::span::Span;

/// The statement (its tokens, the final `.` included) when it has one of the common shapes,
/// exactly as the grammar would build it; `None` for the grammar to parse.
pub(crate) fn common_statement(statement: &[Token<'_>]) -> Option<Item> {
    let (last, rest) = statement.split_last()?;
    if last.tok != Tok::Dot {
        return None;
    }
    let span = Span::new(statement[0].span.start as usize, last.span.end as usize);
    // `a.` / `~a.`
    if let Some((lit, [])) = lit(rest) {
        return Some(Item::Fact {
            clause: vec![lit],
            span,
        });
    }
    match rest {
        [Token {
            tok: Tok::Ident(_),
            span: first,
        }, Token { tok: Tok::Gt, .. }, ..] => priority(*first, &rest[2..], span),
        // `\/{a, ~b}.`
        [Token { tok: Tok::Or, .. }, Token {
            tok: Tok::LBrace, ..
        }, inside @ .., Token {
            tok: Tok::RBrace, ..
        }] => {
            let (clause, after) = lits(inside, |_| false)?;
            after.is_empty().then_some(Item::Fact { clause, span })
        }
        _ => rule(rest, span),
    }
}

/// Literals separated by commas, a trailing comma allowed (the grammar's `Comma<SourceLiteral>`), up to
/// the first token `ends` accepts or the end; `None` when two literals have no comma between.
fn lits<'t, 'a>(
    mut tokens: &'t [Token<'a>],
    ends: impl Fn(&Token<'_>) -> bool,
) -> Option<(Vec<SourceLiteral>, &'t [Token<'a>])> {
    let mut found = Vec::new();
    while let Some(first) = tokens.first() {
        if ends(first) {
            break;
        }
        let (l, after) = lit(tokens)?;
        found.push(l);
        tokens = match after.first() {
            Some(Token {
                tok: Tok::Comma, ..
            }) => &after[1..],
            Some(next) if ends(next) => after,
            None => after,
            Some(_) => return None,
        };
    }
    Some((found, tokens))
}

/// `~`? name, and what follows it.
fn lit<'t, 'a>(tokens: &'t [Token<'a>]) -> Option<(SourceLiteral, &'t [Token<'a>])> {
    match tokens {
        [Token {
            tok: Tok::Tilde,
            span: tilde,
        }, Token {
            tok: Tok::Ident(_),
            span: atom,
        }, after @ ..] => Some((
            SourceLiteral {
                negated: true,
                atom: *atom,
                span: Span::new(tilde.start as usize, atom.end as usize),
            },
            after,
        )),
        [Token {
            tok: Tok::Ident(_),
            span: atom,
        }, after @ ..] => Some((
            SourceLiteral {
                negated: false,
                atom: *atom,
                span: *atom,
            },
            after,
        )),
        _ => None,
    }
}

/// `first > b > c` once `first >` is read: the rest of the chain.
fn priority(first: Span, mut tokens: &[Token<'_>], span: Span) -> Option<Item> {
    let mut labels = vec![first];
    loop {
        match tokens {
            [Token {
                tok: Tok::Ident(_),
                span: label,
            }] => {
                labels.push(*label);
                return Some(Item::Priority { labels, span });
            }
            [Token {
                tok: Tok::Ident(_),
                span: label,
            }, Token { tok: Tok::Gt, .. }, after @ ..] => {
                labels.push(*label);
                tokens = after;
            }
            _ => return None,
        }
    }
}

/// `label:`? lits arrow lit.
fn rule(tokens: &[Token<'_>], span: Span) -> Option<Item> {
    let (label, tokens) = match tokens {
        [Token {
            tok: Tok::Ident(_),
            span: label,
        }, Token {
            tok: Tok::Colon, ..
        }, after @ ..] => (Some(*label), after),
        _ => (None, tokens),
    };
    let (body, tokens) = lits(tokens, |t| arrow(t).is_some())?;
    let arrow = arrow(tokens.first()?)?;
    let (head, after) = lit(&tokens[1..])?;
    after.is_empty().then_some(Item::Rule(RuleItem {
        label,
        body,
        arrow,
        head,
        span,
    }))
}

fn arrow(token: &Token<'_>) -> Option<Arrow> {
    match token.tok {
        Tok::Defeasible => Some(Arrow::Defeasible),
        Tok::Strict => Some(Arrow::Strict),
        Tok::Warning => Some(Arrow::Warning),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grammar::StatementParser;
    use crate::lexer::lex;
    use proptest::prelude::*;

    /// Statements of the common shapes and near misses, as token soup.
    fn statement() -> impl Strategy<Value = String> {
        let word = prop_oneof![
            Just("a"),
            Just("b2"),
            Just("r1"),
            Just("~"),
            Just(":"),
            Just(","),
            Just("=>"),
            Just("->"),
            Just("~>"),
            Just(">"),
            Just("{"),
            Just("}"),
            Just("\\/"),
            Just("input"),
            Just("."),
        ];
        prop::collection::vec(word, 0..9).prop_map(|words| words.join(" ") + ".")
    }

    /// The fast path, where it reads `text`'s first statement, reads it as the grammar does.
    fn read_as_the_grammar_reads_it(text: &str) -> Result<(), TestCaseError> {
        let tokens = lex(text);
        let Some(end) = tokens.iter().position(|t| t.tok == Tok::Dot) else {
            return Ok(());
        };
        let statement = &tokens[..=end];
        if let Some(fast) = common_statement(statement) {
            let triples = statement.iter().map(|t| {
                Ok::<_, crate::parse::UserError>((
                    t.span.start as usize,
                    t.tok,
                    t.span.end as usize,
                ))
            });
            let slow = StatementParser::new().parse(triples);
            prop_assert_eq!(Ok(fast), slow.map_err(|e| format!("{e:?}")), "{}", text);
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn common_statements_read_as_the_grammar_reads_them(text in statement()) {
            read_as_the_grammar_reads_it(&text)?;
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20000))]

        /// Before a release: `cargo nextest run -p proclaim-syntax --run-ignored all`.
        #[test]
        #[ignore = "before a release: the full twenty thousand cases (`--run-ignored all`)"]
        fn common_statements_read_as_the_grammar_reads_them_in_twenty_thousand_cases(text in statement()) {
            read_as_the_grammar_reads_it(&text)?;
        }
    }

    #[test]
    fn the_common_shapes_are_read_without_the_grammar() {
        for text in [
            "a.",
            "~a.",
            "r1: a, ~b => c.",
            "=> a.",
            "a, -> ~b.",
            "r1 > r2 > r3.",
            "\\/{~a, b}.",
            "\\/{a,}.",
        ] {
            assert!(common_statement(&lex(text)).is_some(), "{text}");
        }
        for text in [
            "a b => c.",
            "{a} => b.",
            "input{a}.",
            "r1 >.",
            "a => b c.",
            "\\/{a b}.",
            "\\/{a}, b.",
        ] {
            assert!(common_statement(&lex(text)).is_none(), "{text}");
        }
    }
}
