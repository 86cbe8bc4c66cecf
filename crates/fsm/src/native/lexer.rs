//! Tokens of the native machine format. Line-aware where the format is: the text after a
//! posting's `:`, after `code`, and a label between `when` and `->` are taken raw, so they need
//! no quoting and read like the original tables. Inside an activity (`entry { … }`), anything
//! that is not a posting (`Type: content`), a `call` or `code` is a statement of the activity
//! language, taken raw up to its `;` (or the `}` of its block) and parsed later.

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MachineToken<'a> {
    Machine,
    Description,
    Initial,
    State,
    /// `parallel`, where a state may begin: a state whose states are regions.
    Parallel,
    Entry,
    Exit,
    Internal,
    When,
    Call,
    Code,
    /// `param`, at the top of a file; the rest of its line comes as a [`MachineToken::Text`].
    Param,
    /// `outcome`, at the top of a file or in a state; the rest of its line comes as a
    /// [`MachineToken::Text`].
    Outcome,
    Word(&'a str),
    Str(String),
    Int(i64),
    Hash,
    LBrace,
    RBrace,
    LParen,
    RParen,
    Arrow,
    /// Between the targets of a transition that enters a state in each of several regions.
    Comma,
    /// The rest of a line after `:` or `code`, trimmed.
    Text(&'a str),
    /// A label as written between `when` and `->`.
    LabelText(&'a str),
    /// A statement of the activity language as written, with its `;`.
    Statement(&'a str),
}

impl std::fmt::Display for MachineToken<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MachineToken::Machine => f.write_str("`machine`"),
            MachineToken::Description => f.write_str("`description`"),
            MachineToken::Initial => f.write_str("`initial`"),
            MachineToken::State => f.write_str("`state`"),
            MachineToken::Parallel => f.write_str("`parallel`"),
            MachineToken::Entry => f.write_str("`entry`"),
            MachineToken::Exit => f.write_str("`exit`"),
            MachineToken::Internal => f.write_str("`internal`"),
            MachineToken::When => f.write_str("`when`"),
            MachineToken::Call => f.write_str("`call`"),
            MachineToken::Code => f.write_str("`code`"),
            MachineToken::Param => f.write_str("`param`"),
            MachineToken::Outcome => f.write_str("`outcome`"),
            MachineToken::Word(w) => write!(f, "`{w}`"),
            MachineToken::Str(s) => write!(f, "{s:?}"),
            MachineToken::Int(i) => write!(f, "`{i}`"),
            MachineToken::Hash => f.write_str("`#`"),
            MachineToken::LBrace => f.write_str("`{`"),
            MachineToken::RBrace => f.write_str("`}`"),
            MachineToken::LParen => f.write_str("`(`"),
            MachineToken::RParen => f.write_str("`)`"),
            MachineToken::Arrow => f.write_str("`->`"),
            MachineToken::Comma => f.write_str("`,`"),
            MachineToken::Text(t) => write!(f, "`: {t}`"),
            MachineToken::LabelText(t) => write!(f, "label `{t}`"),
            MachineToken::Statement(t) => write!(f, "statement `{t}`"),
        }
    }
}

/// Where and why the text is not a token: the one lexer error of both languages.
pub(crate) use crate::code::LexError;

pub type Spanned<'a> = Result<(usize, MachineToken<'a>, usize), LexError>;

/// How deep blocks may nest (states in states, with their activities): far past any machine a
/// person writes, and short of what reading and dropping a tree that deep would take of a
/// thread's stack.
const MAX_DEPTH: usize = 256;

pub struct MachineLexer<'a> {
    text: &'a str,
    at: usize,
    /// Tokens already cut that come before anything else (a label's `->`).
    pending: Vec<(usize, MachineToken<'a>, usize)>,
    /// The `{` still open, innermost last: `true` for an activity's (`entry {`), whose items
    /// are cut as postings and statements, `false` for a state's body.
    open: Vec<bool>,
    /// The last word was `entry`, `exit` or `internal`, or a transition's target: the next `{`
    /// opens an activity.
    activity_next: bool,
    /// A `when`'s `->` was cut: the next word or number is its target.
    target_next: bool,
    /// Up to here, tokens are cut as anywhere else (the rest of a `call` line).
    plain_until: usize,
    /// The last word was `machine`, `state`, `parallel` or `initial`: the next word is a name,
    /// never a keyword (so a state may be called `outcome` or `initial`).
    name_next: bool,
}

impl<'a> MachineLexer<'a> {
    pub fn new(text: &'a str) -> MachineLexer<'a> {
        MachineLexer {
            text,
            at: 0,
            pending: Vec::new(),
            open: Vec::new(),
            activity_next: false,
            target_next: false,
            plain_until: 0,
            name_next: false,
        }
    }

    fn rest(&self) -> &'a str {
        &self.text[self.at..]
    }

    fn skip_space_and_comments(&mut self) {
        loop {
            let rest = self.rest();
            let trimmed = rest.trim_start();
            self.at += rest.len() - trimmed.len();
            if trimmed.starts_with("//") {
                let end = trimmed.find('\n').unwrap_or(trimmed.len());
                self.at += end;
            } else {
                return;
            }
        }
    }

    /// The rest of the current line from `self.at`, trimmed, as one token.
    fn line_text(
        &mut self,
        make: fn(&'a str) -> MachineToken<'a>,
    ) -> (usize, MachineToken<'a>, usize) {
        let rest = self.rest();
        let line = &rest[..rest.find('\n').unwrap_or(rest.len())];
        let start = self.at + (line.len() - line.trim_start().len());
        let text = line.trim();
        self.at += line.len();
        (start, make(text), start + text.len())
    }

    /// One arm per token shape and per raw-text mode, the lexer's whole table in one match (the
    /// order of the arms decides); the longer shapes are read by a method each.
    fn next_token(&mut self) -> Option<Spanned<'a>> {
        if let Some(t) = self.pending.pop() {
            return Some(Ok(t));
        }
        self.skip_space_and_comments();
        let start = self.at;
        let rest = self.rest();
        let c = rest.chars().next()?;
        let in_activity = self.open.last() == Some(&true);
        if in_activity && self.at >= self.plain_until {
            if let Some(token) = self.activity_item(c) {
                return Some(Ok(token));
            }
        }
        if c != '{' {
            self.activity_next = false;
        }
        // A name is a word: anything else (a quoted name, an id) ends the wait for one.
        if !(c.is_alphabetic() || c == '_') {
            self.name_next = false;
        }
        let one = |tok| Some(Ok((start, tok, start + 1)));
        match c {
            '{' if self.open.len() >= MAX_DEPTH => {
                self.at += 1;
                Some(Err(LexError {
                    at: start,
                    message: format!("blocks nest deeper than {MAX_DEPTH}"),
                }))
            }
            '{' => {
                self.at += 1;
                self.open.push(std::mem::take(&mut self.activity_next));
                one(MachineToken::LBrace)
            }
            '}' => {
                self.at += 1;
                self.open.pop();
                one(MachineToken::RBrace)
            }
            '(' => {
                self.at += 1;
                one(MachineToken::LParen)
            }
            ')' => {
                self.at += 1;
                one(MachineToken::RParen)
            }
            '#' => {
                self.at += 1;
                one(MachineToken::Hash)
            }
            ':' => {
                self.at += 1;
                Some(Ok(self.line_text(MachineToken::Text)))
            }
            '-' if rest.starts_with("->") => {
                self.at += 2;
                Some(Ok((start, MachineToken::Arrow, start + 2)))
            }
            // `-> A, B`: another target follows, a name as the first was.
            ',' => {
                self.at += 1;
                self.target_next = true;
                one(MachineToken::Comma)
            }
            '"' => Some(self.string()),
            c if c.is_ascii_digit() || c == '-' => Some(self.number()),
            c if c.is_alphabetic() || c == '_' => Some(Ok(self.word())),
            other => {
                self.at += other.len_utf8();
                Some(Err(LexError {
                    at: start,
                    message: format!("`{other}` cannot start anything here"),
                }))
            }
        }
    }

    /// A whole number from the digit or `-` at `self.at`.
    fn number(&mut self) -> Spanned<'a> {
        let start = self.at;
        let rest = self.rest();
        let len = rest[1..]
            .find(|c: char| !c.is_ascii_digit())
            .map_or(rest.len(), |n| n + 1);
        self.at += len;
        self.activity_next = std::mem::take(&mut self.target_next);
        match rest[..len].parse() {
            Ok(n) => Ok((start, MachineToken::Int(n), start + len)),
            Err(_) => Err(LexError {
                at: start,
                message: format!("`{}` is not a whole number", &rest[..len]),
            }),
        }
    }

    /// What follows `param` or `outcome`: the rest of the line up to a comment or a `}` (names
    /// and types hold neither), so `state LANDED { outcome landed }` reads on one line.
    fn declaration_text(&mut self) -> (usize, MachineToken<'a>, usize) {
        let rest = self.rest();
        let line = &rest[..rest.find(['\n', '}']).unwrap_or(rest.len())];
        let line = &line[..line.find("//").unwrap_or(line.len())];
        let start = self.at + (line.len() - line.trim_start().len());
        let text = line.trim();
        self.at += line.len();
        (start, MachineToken::Text(text), start + text.len())
    }

    /// A keyword or a word from the letter at `self.at`; after `code` and `when`, the raw text
    /// that follows them is cut too and waits in `pending`.
    fn word(&mut self) -> (usize, MachineToken<'a>, usize) {
        let start = self.at;
        let rest = self.rest();
        let len = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '.'))
            .unwrap_or(rest.len());
        let word = &rest[..len];
        self.at += len;
        let named = std::mem::take(&mut self.name_next) || self.target_next;
        // Where a state's body or the file's top expects an item, not inside an activity.
        let item = !named && self.open.last() != Some(&true);
        let tok = match word {
            // A name, whatever word it is: a state may be called `initial` or `entry` (SCXML
            // documents have both) and be the target of a move.
            _ if named => {
                self.activity_next = std::mem::take(&mut self.target_next);
                MachineToken::Word(word)
            }
            "machine" | "initial" | "state" => {
                self.name_next = true;
                match word {
                    "machine" => MachineToken::Machine,
                    "initial" => MachineToken::Initial,
                    _ => MachineToken::State,
                }
            }
            "parallel" if item => {
                self.name_next = true;
                MachineToken::Parallel
            }
            "description" if self.open.is_empty() => MachineToken::Description,
            "param" | "outcome" if item && (word == "outcome" || self.open.is_empty()) => {
                let text = self.declaration_text();
                self.pending.push(text);
                if word == "param" {
                    MachineToken::Param
                } else {
                    MachineToken::Outcome
                }
            }
            "entry" | "exit" | "internal" => {
                self.activity_next = true;
                match word {
                    "entry" => MachineToken::Entry,
                    "exit" => MachineToken::Exit,
                    _ => MachineToken::Internal,
                }
            }
            "call" => MachineToken::Call,
            "code" => {
                let text = self.line_text(MachineToken::Text);
                self.pending.push(text);
                MachineToken::Code
            }
            "when" => {
                let label = self.label();
                self.pending.extend(label);
                MachineToken::When
            }
            _ => {
                self.activity_next = std::mem::take(&mut self.target_next);
                MachineToken::Word(word)
            }
        };
        (start, tok, start + len)
    }

    /// Inside an activity: a statement, or `None` where the item starts as anywhere else (a
    /// posting's type, `call`, `code`, the activity's closing `}`).
    fn activity_item(&mut self, first: char) -> Option<(usize, MachineToken<'a>, usize)> {
        let rest = self.rest();
        if matches!(first, '}' | '"' | ':') {
            return None;
        }
        if first.is_alphabetic() || first == '_' {
            let len = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '.'))
                .unwrap_or(rest.len());
            let after = rest[len..].trim_start_matches([' ', '\t']);
            match &rest[..len] {
                "call" => {
                    self.plain_until = self.at + rest.find('\n').unwrap_or(rest.len());
                    return None;
                }
                "code" => return None,
                _ if after.starts_with(':') => return None,
                _ => {}
            }
        }
        let len = statement_length(rest);
        let start = self.at;
        self.at += len;
        let text = rest[..len].trim_end();
        Some((start, MachineToken::Statement(text), start + text.len()))
    }

    /// The label after `when`, up to `->` on the same line, or up to the `{` that opens the
    /// actions of a transition that stays; the tokens come back in reverse order (they are
    /// popped from `pending`).
    fn label(&mut self) -> Vec<(usize, MachineToken<'a>, usize)> {
        let rest = self.rest();
        let line = &rest[..rest.find('\n').unwrap_or(rest.len())];
        let Some((end, arrow)) = label_end(line) else {
            // A block may open on the next line: `when p` then `{ … }`, which stays.
            self.activity_next = true;
            return vec![self.line_text(MachineToken::LabelText)];
        };
        let raw = &line[..end];
        let start = self.at + (raw.len() - raw.trim_start().len());
        let label = raw.trim();
        let label = (start, MachineToken::LabelText(label), start + label.len());
        let end_at = self.at + end;
        if arrow {
            self.at = end_at + 2;
            self.target_next = true;
            vec![(end_at, MachineToken::Arrow, end_at + 2), label]
        } else {
            // `when p { … }`: a transition that stays, its actions in the block.
            self.at = end_at;
            self.activity_next = true;
            vec![label]
        }
    }

    fn string(&mut self) -> Spanned<'a> {
        let start = self.at;
        // A quoted target is a target as a word is: what follows is its actions or an item.
        self.activity_next = std::mem::take(&mut self.target_next);
        let mut out = String::new();
        let mut chars = self.rest()[1..].char_indices();
        while let Some((i, c)) = chars.next() {
            match c {
                '"' => {
                    self.at = start + 1 + i + 1;
                    return Ok((start, MachineToken::Str(out), self.at));
                }
                '\\' => match chars.next() {
                    Some((_, 'n')) => out.push('\n'),
                    Some((_, 't')) => out.push('\t'),
                    Some((_, c)) => out.push(c),
                    None => break,
                },
                '\n' => break,
                c => out.push(c),
            }
        }
        let line_end = self.rest().find('\n').unwrap_or(self.rest().len());
        self.at += line_end;
        Err(LexError {
            at: start,
            message: "string has no closing `\"` on its line".into(),
        })
    }
}

/// Where a label's line ends the label, outside quoted text: at its `->` (true) or at the `{`
/// of a transition that stays (false), whichever comes first; a label holds neither.
fn label_end(line: &str) -> Option<(usize, bool)> {
    let mut quote: Option<char> = None;
    let mut escaped = false;
    for (i, c) in line.char_indices() {
        match (quote, c) {
            _ if escaped => escaped = false,
            (Some(_), '\\') => escaped = true,
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '{') => return Some((i, false)),
            (None, '-') if line[i..].starts_with("->") => return Some((i, true)),
            (None, _) => {}
        }
    }
    None
}

impl<'a> Iterator for MachineLexer<'a> {
    type Item = Spanned<'a>;

    fn next(&mut self) -> Option<Spanned<'a>> {
        self.next_token()
    }
}

/// The length of the statement that starts `text`: up to and with its `;`, or the `}` that
/// closes a block it opened, or up to (without) a `}` it did not open, or the end.
fn statement_length(text: &str) -> usize {
    let (mut parens, mut braces) = (0i32, 0i32);
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        match c {
            '"' | '\'' => {
                let mut escaped = false;
                for (_, inner) in chars.by_ref() {
                    match inner {
                        _ if escaped => escaped = false,
                        '\\' => escaped = true,
                        '\n' => break,
                        q if q == c => break,
                        _ => {}
                    }
                }
            }
            '/' if chars.peek().is_some_and(|(_, n)| *n == '/') => {
                for (_, inner) in chars.by_ref() {
                    if inner == '\n' {
                        break;
                    }
                }
            }
            '(' | '[' => parens += 1,
            ')' | ']' => parens -= 1,
            '{' => braces += 1,
            '}' if braces == 0 => return i,
            '}' => {
                braces -= 1;
                if braces == 0 && parens <= 0 {
                    return i + 1;
                }
            }
            ';' if parens <= 0 && braces == 0 => return i + 1,
            _ => {}
        }
    }
    text.len()
}
