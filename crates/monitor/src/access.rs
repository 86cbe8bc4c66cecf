//! Who may change a run from its page, decided from the address the page listens on, and the
//! addresses a page is given (`7480`, `127.0.0.1:7480`, `[::1]:7480`).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};

/// Who may change the run from the page (pause, step, post to the whiteboard).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Access {
    /// Anyone who reaches the page: for a page on loopback only.
    #[default]
    Open,
    /// Only requests that carry this token (a page on the network; the token is in the address
    /// printed once, as Jupyter does it).
    Token(String),
    /// Nobody: the page shows the run and has no controls.
    ReadOnly,
}

/// The header a page sends its token in.
pub const TOKEN_HEADER: &str = "x-proclaim-token";

impl Access {
    /// A page's access as `--monitor` decides it: none with `read_only`; open on loopback;
    /// elsewhere a new token, which only the address printed carries.
    pub fn for_address(addr: SocketAddr, read_only: bool) -> Access {
        if read_only {
            Access::ReadOnly
        } else if addr.ip().is_loopback() {
            Access::Open
        } else {
            Access::Token(new_token())
        }
    }
}

/// A port alone (on loopback) or a whole address; `None` for anything else.
pub fn parse_address(text: &str) -> Option<SocketAddr> {
    let text = text.trim();
    if let Ok(port) = text.parse::<u16>() {
        return Some(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port));
    }
    text.parse().ok()
}

/// 128 random bits in hex: the operating system's randomness where there is any, else the
/// standard library's per-process random hash keys.
pub fn new_token() -> String {
    use std::hash::{BuildHasher, Hasher};
    use std::io::Read;
    let mut bytes = [0u8; 16];
    let from_os = std::fs::File::open("/dev/urandom")
        .and_then(|mut f| f.read_exact(&mut bytes))
        .is_ok();
    if !from_os {
        for chunk in bytes.chunks_mut(8) {
            let mut hasher = std::collections::hash_map::RandomState::new().build_hasher();
            hasher.write_u128(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos()),
            );
            chunk.copy_from_slice(&hasher.finish().to_le_bytes());
        }
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_port_alone_is_on_loopback_and_anything_else_must_be_an_address() {
        assert_eq!(parse_address("7480"), "127.0.0.1:7480".parse().ok());
        assert_eq!(parse_address(" [::1]:80 "), "[::1]:80".parse().ok());
        assert_eq!(parse_address("localhost:80"), None);
    }

    #[test]
    fn only_a_page_off_loopback_needs_a_token() {
        let at = |a: &str| a.parse::<SocketAddr>().unwrap();
        assert_eq!(Access::for_address(at("127.0.0.1:1"), false), Access::Open);
        assert_eq!(Access::for_address(at("0.0.0.0:1"), true), Access::ReadOnly);
        let Access::Token(token) = Access::for_address(at("0.0.0.0:1"), false) else {
            panic!("a page on every interface needs a token");
        };
        assert_eq!(token.len(), 32);
        assert_ne!(
            Access::for_address(at("0.0.0.0:1"), false),
            Access::Token(token)
        );
    }
}
