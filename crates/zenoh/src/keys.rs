//! The key expressions of one board: its types' own keys and the `@` keys of its processes
//! (liveliness, kinds, the registry, pings), and which type names can be keys at all.

use crate::wire::WireKind;

/// Key expressions of one board, under its name. Every key but the types' starts with a chunk
/// beginning with `@`, which Zenoh's wildcards never match: `proclaim/B/**` is the types alone.
#[derive(Clone)]
pub(crate) struct Keys {
    board: String,
}

impl Keys {
    pub(crate) fn new(board: &str) -> Keys {
        Keys {
            board: board.to_string(),
        }
    }

    pub(crate) fn ty(&self, ty: &str) -> String {
        format!("proclaim/{}/{ty}", self.board)
    }

    pub(crate) fn every_type(&self) -> String {
        format!("proclaim/{}/*", self.board)
    }

    /// The type a key names, when it is one of this board's types.
    pub(crate) fn type_of<'k>(&self, key: &'k str) -> Option<&'k str> {
        let rest = key.strip_prefix("proclaim/")?.strip_prefix(&*self.board)?;
        rest.strip_prefix('/')
            .filter(|t| type_key_error(t).is_none())
    }

    pub(crate) fn alive(&self, process: &str) -> String {
        format!("proclaim/{}/@alive/{process}", self.board)
    }

    pub(crate) fn every_alive(&self) -> String {
        format!("proclaim/{}/@alive/*", self.board)
    }

    pub(crate) fn kind(&self, ty: &str, kind: WireKind, since_ns: u64, process: &str) -> String {
        format!(
            "proclaim/{}/@kind/{ty}/{}/{since_ns}/{process}",
            self.board,
            kind.name()
        )
    }

    pub(crate) fn every_kind(&self) -> String {
        format!("proclaim/{}/@kind/*/*/*/*", self.board)
    }

    pub(crate) fn registry(&self) -> String {
        format!("proclaim/{}/@registry", self.board)
    }

    pub(crate) fn ping(&self) -> String {
        format!("proclaim/{}/@ping", self.board)
    }
}

/// Why a type's name cannot be a key's last chunk, if it cannot.
pub(crate) fn type_key_error(ty: &str) -> Option<&'static str> {
    if ty.is_empty() {
        Some("it is empty")
    } else if ty.starts_with('@') {
        Some("it starts with `@`, which Zenoh keeps for its own keys")
    } else if ty.contains(['/', '*', '$', '?', '#']) {
        Some("it holds one of / * $ ? #, which Zenoh's keys cannot")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_type_has_its_own_key_under_the_board() {
        let keys = Keys::new("team18");
        assert_eq!(keys.ty("ballNear"), "proclaim/team18/ballNear");
        assert_eq!(keys.type_of(&keys.ty("ballNear")), Some("ballNear"));
        assert_eq!(keys.every_type(), "proclaim/team18/*");
    }

    #[test]
    fn only_this_boards_types_are_read_as_types() {
        let keys = Keys::new("team18");
        assert_eq!(keys.type_of("proclaim/team5/ballNear"), None);
        assert_eq!(keys.type_of("proclaim/team181/ballNear"), None);
        assert_eq!(keys.type_of("other/team18/ballNear"), None);
        for own in [
            keys.alive("ab12"),
            keys.registry(),
            keys.ping(),
            keys.kind("ballNear", WireKind::Signal, 5, "ab12"),
        ] {
            assert!(own.starts_with("proclaim/team18/@"), "{own}");
            assert_eq!(keys.type_of(&own), None, "{own}");
        }
    }

    #[test]
    fn a_type_name_that_cannot_be_a_key_says_why() {
        assert_eq!(type_key_error("ballNear"), None);
        assert_eq!(type_key_error("ball.near-2"), None);
        assert_eq!(type_key_error(""), Some("it is empty"));
        assert!(type_key_error("@alive").unwrap().contains("`@`"));
        for bad in ["a/b", "a*", "a$b", "a?", "#a"] {
            assert!(type_key_error(bad).unwrap().contains("/ * $ ? #"), "{bad}");
        }
    }
}
