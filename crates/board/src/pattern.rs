//! What a subscription listens to: one type, a glob with `*` (`*Received`, `UDPsays*`), or all.

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pattern {
    Type(String),
    Glob(String),
    /// Any of these types.
    Any(Vec<String>),
    All,
}

impl Pattern {
    /// `*` alone is everything; a text with `*` is a glob; anything else one type.
    pub fn parse(text: &str) -> Pattern {
        match text {
            "*" | "" => Pattern::All,
            t if t.contains('*') => Pattern::Glob(t.to_string()),
            t => Pattern::Type(t.to_string()),
        }
    }

    pub fn matches(&self, ty: &str) -> bool {
        match self {
            Pattern::All => true,
            Pattern::Type(t) => t == ty,
            Pattern::Glob(g) => glob(g.as_bytes(), ty.as_bytes()),
            Pattern::Any(types) => types.iter().any(|t| t == ty),
        }
    }
}

fn glob(pattern: &[u8], text: &[u8]) -> bool {
    match pattern.split_first() {
        None => text.is_empty(),
        Some((b'*', rest)) => (0..=text.len()).any(|i| glob(rest, &text[i..])),
        Some((&c, rest)) => text.first() == Some(&c) && glob(rest, &text[1..]),
    }
}
