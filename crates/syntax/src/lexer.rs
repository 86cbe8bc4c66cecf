//! Turns .dl text into tokens with byte positions; never fails, bad characters become error tokens.

use crate::span::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tok<'a> {
    Ident(&'a str),
    /// A double-quoted string; the payload is the text between the quotes, escapes untouched.
    Str(&'a str),
    Num(u32),
    Dot,
    Comma,
    Colon,
    LBrace,
    RBrace,
    Tilde,
    /// `\/`, the clause (disjunction) constructor.
    Or,
    /// `/\`, the conjunction constructor (queries only).
    And,
    /// `=>`
    Defeasible,
    /// `->`
    Strict,
    /// `~>`
    Warning,
    Gt,
    // Directive keywords: only when the word is directly followed by `{` (or, for `ignore`, by a
    // number), so that `input`, `output`, `name` … stay usable as atoms.
    KwName,
    KwInput,
    KwIgnore,
    KwAssert,
    KwOutput,
    /// Characters that start no token; one error token per run of them.
    Error,
    /// A string with no closing quote before the end of the line.
    UnclosedStr,
    /// A `/*` comment with no closing `*/`.
    UnclosedComment,
}

impl Tok<'_> {
    /// How the token is named in "expected …" messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("`{s}`"),
            Tok::Str(_) => "a string".into(),
            Tok::Num(n) => format!("`{n}`"),
            Tok::Error | Tok::UnclosedStr | Tok::UnclosedComment => "bad text".into(),
            other => format!("`{}`", other.symbol()),
        }
    }

    fn symbol(&self) -> &'static str {
        match self {
            Tok::Dot => ".",
            Tok::Comma => ",",
            Tok::Colon => ":",
            Tok::LBrace => "{",
            Tok::RBrace => "}",
            Tok::Tilde => "~",
            Tok::Or => "\\/",
            Tok::And => "/\\",
            Tok::Defeasible => "=>",
            Tok::Strict => "->",
            Tok::Warning => "~>",
            Tok::Gt => ">",
            Tok::KwName => "name",
            Tok::KwInput => "input",
            Tok::KwIgnore => "ignore",
            Tok::KwAssert => "assert",
            Tok::KwOutput => "output",
            _ => "?",
        }
    }
}

/// A token and where it stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token<'a> {
    pub tok: Tok<'a>,
    pub span: Span,
}

/// Lexes the whole text. Comments (`%` or `//` to end of line, `/* … */`) and white space are
/// dropped.
pub fn lex(source: &str) -> Vec<Token<'_>> {
    Lexer::new(source).collect()
}

/// Tokens on demand, so a file of millions of statements never holds all its tokens at once.
pub struct Lexer<'a> {
    source: &'a str,
    at: usize,
}

impl<'a> Lexer<'a> {
    pub fn new(source: &'a str) -> Lexer<'a> {
        Lexer { source, at: 0 }
    }
}

impl<'a> Iterator for Lexer<'a> {
    type Item = Token<'a>;

    fn next(&mut self) -> Option<Token<'a>> {
        let source = self.source;
        let bytes = source.as_bytes();
        let mut i = self.at;
        let token = scan(source, bytes, &mut i);
        self.at = i;
        token
    }
}

/// The next token at `cursor`: one arm per token shape, the lexer's whole table in one match
/// (the order of the arms decides), the longer shapes read by a function each.
fn scan<'a>(source: &'a str, bytes: &[u8], cursor: &mut usize) -> Option<Token<'a>> {
    let mut i = *cursor;
    while i < bytes.len() {
        let start = i;
        let b = bytes[i];
        let tok = match b {
            b' ' | b'\t' | b'\r' | b'\n' => {
                i += 1;
                continue;
            }
            // `//` as in the `.machine` files and the activity language beside the theories.
            b'%' | b'/' if b == b'%' || bytes.get(i + 1) == Some(&b'/') => {
                i = memchr_newline(bytes, i);
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => match find(bytes, i + 2, b"*/") {
                Some(end) => {
                    i = end + 2;
                    continue;
                }
                None => {
                    i = bytes.len();
                    Tok::UnclosedComment
                }
            },
            b'/' if bytes.get(i + 1) == Some(&b'\\') => {
                i += 2;
                Tok::And
            }
            b'\\' if bytes.get(i + 1) == Some(&b'/') => {
                i += 2;
                Tok::Or
            }
            b'=' if bytes.get(i + 1) == Some(&b'>') => {
                i += 2;
                Tok::Defeasible
            }
            b'-' if bytes.get(i + 1) == Some(&b'>') => {
                i += 2;
                Tok::Strict
            }
            b'~' if bytes.get(i + 1) == Some(&b'>') => {
                i += 2;
                Tok::Warning
            }
            b'~' => single(&mut i, Tok::Tilde),
            b'.' => single(&mut i, Tok::Dot),
            b',' => single(&mut i, Tok::Comma),
            b':' => single(&mut i, Tok::Colon),
            b'{' => single(&mut i, Tok::LBrace),
            b'}' => single(&mut i, Tok::RBrace),
            b'>' => single(&mut i, Tok::Gt),
            b'"' => string(source, bytes, &mut i),
            b'0'..=b'9' => number(source, bytes, &mut i),
            b if b.is_ascii_alphabetic() => {
                while i < bytes.len() && is_ident_byte(bytes[i]) {
                    i += 1;
                }
                keyword_or_ident(&source[start..i], next_significant(bytes, i))
            }
            _ => unusable_run(source, bytes, &mut i),
        };
        *cursor = i;
        return Some(Token {
            tok,
            span: Span::new(start, i),
        });
    }
    *cursor = i;
    None
}

/// A string from the `"` at `i`, closed on its line (a `\"` inside does not close it).
fn string<'a>(source: &'a str, bytes: &[u8], i: &mut usize) -> Tok<'a> {
    let start = *i;
    let mut j = start + 1;
    while j < bytes.len() && bytes[j] != b'"' && bytes[j] != b'\n' {
        j += if bytes[j] == b'\\' && j + 1 < bytes.len() && bytes[j + 1] != b'\n' {
            2
        } else {
            1
        };
    }
    if j < bytes.len() && bytes[j] == b'"' {
        *i = j + 1;
        Tok::Str(&source[start + 1..j])
    } else {
        *i = j;
        Tok::UnclosedStr
    }
}

/// A number from the digit at `i`.
fn number<'a>(source: &'a str, bytes: &[u8], i: &mut usize) -> Tok<'a> {
    let start = *i;
    while *i < bytes.len() && bytes[*i].is_ascii_digit() {
        *i += 1;
    }
    // A digit run glued to letters (`2ab`) is not an atom: atoms start with a letter.
    if *i < bytes.len() && is_ident_byte(bytes[*i]) {
        while *i < bytes.len() && is_ident_byte(bytes[*i]) {
            *i += 1;
        }
        Tok::Error
    } else {
        source[start..*i].parse().map_or(Tok::Error, Tok::Num)
    }
}

/// One error token for a whole run of unusable characters from `i`, ending on a char boundary.
fn unusable_run<'a>(source: &'a str, bytes: &[u8], i: &mut usize) -> Tok<'a> {
    *i += 1;
    while *i < bytes.len() && !starts_token(bytes[*i]) {
        *i += 1;
    }
    while *i < bytes.len() && !source.is_char_boundary(*i) {
        *i += 1;
    }
    Tok::Error
}

fn single<'a>(i: &mut usize, tok: Tok<'a>) -> Tok<'a> {
    *i += 1;
    tok
}

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

fn starts_token(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b"~.,:{}>\"%/\\=- \t\r\n".contains(&b)
}

fn memchr_newline(bytes: &[u8], from: usize) -> usize {
    bytes[from..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |p| from + p)
}

fn find(bytes: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|p| from + p)
}

fn next_significant(bytes: &[u8], mut i: usize) -> Option<u8> {
    while i < bytes.len() && bytes[i].is_ascii_whitespace() {
        i += 1;
    }
    bytes.get(i).copied()
}

fn keyword_or_ident(word: &str, next: Option<u8>) -> Tok<'_> {
    match (word, next) {
        ("name", Some(b'{')) => Tok::KwName,
        ("input", Some(b'{')) => Tok::KwInput,
        ("ignore", Some(b'{' | b'0'..=b'9')) => Tok::KwIgnore,
        ("assert", Some(b'{')) => Tok::KwAssert,
        ("output", Some(b'{')) => Tok::KwOutput,
        _ => Tok::Ident(word),
    }
}
