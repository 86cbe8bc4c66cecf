//! Tokens of the activity language, cut on demand with their byte offsets.

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum CodeToken {
    Name(String),
    Int(i64),
    Float(f64),
    Str(String),
    /// A duration with its unit (`500ms`, `2s`, `1.5s`, `250us`), in microseconds.
    Duration(u64),
    /// Punctuation and operators, longest first: `== != <= >= && || ( ) { } , ; = + - * / % < > ! ~`.
    Punct(&'static str),
}

impl fmt::Display for CodeToken {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CodeToken::Name(n) => write!(f, "`{n}`"),
            CodeToken::Int(i) => write!(f, "the number `{i}`"),
            CodeToken::Float(x) => write!(f, "the number `{x:?}`"),
            CodeToken::Str(s) => write!(f, "the string {s:?}"),
            CodeToken::Duration(us) => write!(f, "the duration `{us}us`"),
            CodeToken::Punct(p) => write!(f, "`{p}`"),
        }
    }
}

const PUNCTUATION: [&str; 24] = [
    "==", "!=", "<=", ">=", "&&", "||", "(", ")", "{", "}", ",", ";", "=", "+", "-", "*", "/", "%",
    "<", ">", "!", "~", "[", "]",
];

/// Where and why the text is not a token (`at` in bytes): the activity language's and the
/// machine files' lexers both say it this way.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LexError {
    pub at: usize,
    pub message: String,
}

/// Every token of `text` with its start and end offsets.
pub fn tokenize(text: &str) -> Result<Vec<(usize, CodeToken, usize)>, LexError> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut at = 0;
    while at < text.len() {
        let rest = &text[at..];
        let c = rest.chars().next().unwrap_or(' ');
        if c.is_whitespace() {
            at += c.len_utf8();
            continue;
        }
        if rest.starts_with("//") {
            at += rest.find('\n').unwrap_or(rest.len());
            continue;
        }
        if rest.starts_with("/*") {
            at += rest.find("*/").map_or(rest.len(), |end| end + 2);
            continue;
        }
        let start = at;
        if c.is_ascii_digit() || (c == '.' && bytes.get(at + 1).is_some_and(u8::is_ascii_digit)) {
            let (token, len) = number(rest).map_err(|message| LexError { at, message })?;
            at += len;
            out.push((start, token, at));
        } else if c.is_alphabetic() || c == '_' {
            let len = name_length(rest);
            at += len;
            out.push((start, CodeToken::Name(rest[..len].to_string()), at));
        } else if c == '"' || c == '\'' {
            let (s, len) = string(rest, c).ok_or_else(|| LexError {
                at,
                message: format!("this string has no closing `{c}`"),
            })?;
            at += len;
            out.push((start, CodeToken::Str(s), at));
        } else if let Some(p) = PUNCTUATION.iter().find(|p| rest.starts_with(**p)) {
            at += p.len();
            out.push((start, CodeToken::Punct(p), at));
        } else {
            return Err(LexError {
                at,
                message: format!("`{c}` has no meaning here"),
            });
        }
    }
    Ok(out)
}

/// The length of the name `text` starts with: letters, digits and `_`, and dotted parts
/// (`robot2.ballDistance`, `team.min`: a teammate's value, a team aggregate) whose every part
/// starts with a letter or `_`, so `a.5` is no name.
fn name_length(text: &str) -> usize {
    let part = |from: usize| {
        text[from..]
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .map_or(text.len(), |end| end + from)
    };
    let mut len = part(0);
    while text[len..].starts_with('.')
        && text[len + 1..].starts_with(|c: char| c.is_alphabetic() || c == '_')
    {
        len = part(len + 1);
    }
    len
}

/// `12`, `0.3`, `.5`, `1e-3`, `2.5E4`: an integer unless it has a point or an exponent.
fn number(text: &str) -> Result<(CodeToken, usize), String> {
    let b = text.as_bytes();
    let mut len = 0;
    while len < b.len() && b[len].is_ascii_digit() {
        len += 1;
    }
    let mut float = false;
    if len < b.len() && b[len] == b'.' {
        float = true;
        len += 1;
        while len < b.len() && b[len].is_ascii_digit() {
            len += 1;
        }
    }
    if len < b.len() && (b[len] == b'e' || b[len] == b'E') {
        let mut exp = len + 1;
        if exp < b.len() && (b[exp] == b'+' || b[exp] == b'-') {
            exp += 1;
        }
        if exp < b.len() && b[exp].is_ascii_digit() {
            float = true;
            len = exp;
            while len < b.len() && b[len].is_ascii_digit() {
                len += 1;
            }
        }
    }
    let digits = &text[..len];
    // A unit right after the number makes it a duration: `500ms`, `2s`, `250us`.
    for (unit, micros) in [("us", 1.0), ("ms", 1e3), ("s", 1e6)] {
        let rest = &text[len..];
        let ends = rest
            .get(unit.len()..)
            .is_none_or(|after| !after.starts_with(|c: char| c.is_alphanumeric() || c == '_'));
        if rest.starts_with(unit) && ends {
            let amount: f64 = digits
                .parse()
                .map_err(|_| format!("`{digits}` is not a number"))?;
            return Ok((
                CodeToken::Duration((amount * micros).round() as u64),
                len + unit.len(),
            ));
        }
    }
    if b.get(len)
        .is_some_and(|c| c.is_ascii_alphabetic() || *c == b'_')
    {
        let word_end = text[len..]
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .map_or(text.len(), |e| e + len);
        return Err(format!(
            "`{}` is neither a number nor a name",
            &text[..word_end]
        ));
    }
    if float {
        match digits.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok((CodeToken::Float(x), len)),
            // Found by the fuzzer: `2E999` would be infinity, which prints as a name.
            Ok(_) => Err(format!("`{digits}` is too large for a number")),
            Err(_) => Err(format!("`{digits}` is not a number")),
        }
    } else {
        digits
            .parse()
            .map(|i| (CodeToken::Int(i), len))
            .map_err(|_| format!("`{digits}` is too large for a whole number"))
    }
}

/// A quoted string with gufsm's escapes (`\n \t \b \f \r \; \" \' \\`); its text and length.
fn string(text: &str, quote: char) -> Option<(String, usize)> {
    let mut out = String::new();
    let mut chars = text.char_indices().skip(1);
    while let Some((i, c)) = chars.next() {
        match c {
            c if c == quote => return Some((out, i + 1)),
            '\\' => {
                let (_, e) = chars.next()?;
                out.push(match e {
                    'n' => '\n',
                    't' => '\t',
                    'r' => '\r',
                    'b' => '\u{8}',
                    'f' => '\u{c}',
                    other => other,
                });
            }
            c => out.push(c),
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<CodeToken> {
        tokenize(text)
            .expect("tokens")
            .into_iter()
            .map(|(_, t, _)| t)
            .collect()
    }

    #[test]
    fn operators_are_cut_longest_first_and_a_minus_after_less_stays_apart() {
        assert_eq!(
            kinds("HeadYaw<-b"),
            vec![
                CodeToken::Name("HeadYaw".into()),
                CodeToken::Punct("<"),
                CodeToken::Punct("-"),
                CodeToken::Name("b".into())
            ]
        );
        assert_eq!(kinds("a<=b")[1], CodeToken::Punct("<="));
    }

    #[test]
    fn dotted_names_are_one_name_and_a_dot_before_a_digit_is_not_part_of_one() {
        assert_eq!(
            kinds("robot2.ballDistance team.min(x)"),
            vec![
                CodeToken::Name("robot2.ballDistance".into()),
                CodeToken::Name("team.min".into()),
                CodeToken::Punct("("),
                CodeToken::Name("x".into()),
                CodeToken::Punct(")"),
            ]
        );
        assert_eq!(
            kinds("a.5"),
            vec![CodeToken::Name("a".into()), CodeToken::Float(0.5)]
        );
        assert!(tokenize("a.").is_err());
    }

    #[test]
    fn numbers_strings_and_comments() {
        assert_eq!(
            kinds(r#"12 0.3 .5 1e-3 "a\"b" /* x */ // y"#),
            vec![
                CodeToken::Int(12),
                CodeToken::Float(0.3),
                CodeToken::Float(0.5),
                CodeToken::Float(0.001),
                CodeToken::Str("a\"b".into())
            ]
        );
    }

    #[test]
    fn bad_text_is_an_error_with_its_place() {
        assert_eq!(tokenize("a $ b").unwrap_err().at, 2);
        assert_eq!(tokenize("\"open").unwrap_err().at, 0);
        assert!(tokenize("12abc").unwrap_err().message.contains("12abc"));
    }
}
