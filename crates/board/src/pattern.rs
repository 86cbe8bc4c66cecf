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

#[cfg(test)]
mod tests {
    use super::Pattern;

    #[test]
    fn patterns_match_what_they_name() {
        for (pattern, ty, matches) in [
            ("*", "anything", true),
            ("", "anything", true),
            ("*Received", "readyReceived", true),
            ("*Received", "ReceivedNot", false),
            ("UDPsays*", "UDPsaysBlueKickOff", true),
            ("a*b*c", "axxbyyc", true),
            ("a*b*c", "axxbyy", false),
            ("doorOpen", "doorOpen", true),
            ("doorOpen", "doorOpened", false),
        ] {
            assert_eq!(
                Pattern::parse(pattern).matches(ty),
                matches,
                "{pattern} ~ {ty}"
            );
        }
        let any = Pattern::Any(vec!["a".into(), "b".into()]);
        assert!(any.matches("b") && !any.matches("c"));
    }
}
