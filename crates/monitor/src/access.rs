//! Who may change a run from its page, decided from the address the page listens on, and the
//! addresses a page is given (`7480`, `127.0.0.1:7480`, `[::1]:7480`); which requests come from
//! another site (DNS rebinding, a foreign `Origin`).

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

/// Why a request that would change something comes from somewhere it may not, if it does.
/// A page on loopback is open to whoever reaches it, so it answers only loopback host names:
/// a web page the operator visits could otherwise rebind its own name to 127.0.0.1 and drive
/// the robot. On any page, a browser's `Origin` must be the page's own: a cross-site form or
/// fetch changes nothing (the token guards a page on the network as well).
pub fn foreign(access: &Access, host: Option<&str>, origin: Option<&str>) -> Option<String> {
    let host = host.map(str::trim).unwrap_or_default();
    if *access == Access::Open && !is_loopback_name(host) {
        return Some(format!(
            "this page listens on loopback and answers only loopback host names (localhost, 127.0.0.1, [::1]), not `Host: {host}`"
        ));
    }
    let origin = origin?.trim();
    let own = origin
        .strip_prefix("http://")
        .or_else(|| origin.strip_prefix("https://"))
        .is_some_and(|authority| authority.eq_ignore_ascii_case(host));
    (!own).then(|| {
        format!("a request from another site (`Origin: {origin}`) changes nothing on this page")
    })
}

/// `localhost`, a name under `.localhost`, or a loopback address, with or without a port.
fn is_loopback_name(host: &str) -> bool {
    let name = match host.strip_prefix('[') {
        Some(rest) => rest.split(']').next().unwrap_or_default(),
        None => host.rsplit_once(':').map_or(host, |(name, _)| name),
    };
    let name = name.to_ascii_lowercase();
    name == "localhost"
        || name.ends_with(".localhost")
        || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
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
    fn a_page_on_loopback_answers_loopback_names_and_its_own_origin_only() {
        let open = |host: &str, origin: Option<&str>| foreign(&Access::Open, Some(host), origin);
        for host in [
            "localhost:7480",
            "127.0.0.1:80",
            "127.1.2.3",
            "[::1]:7480",
            "a.localhost",
        ] {
            assert_eq!(open(host, None), None, "{host}");
        }
        assert_eq!(open("127.0.0.1:7480", Some("http://127.0.0.1:7480")), None);
        let rebound = open("evil.example:7480", None).unwrap();
        assert!(rebound.contains("`Host: evil.example:7480`"), "{rebound}");
        assert!(open("localhost.evil.example", None).is_some());
        assert!(foreign(&Access::Open, None, None).is_some());
        let cross = open("127.0.0.1:7480", Some("http://evil.example")).unwrap();
        assert!(cross.contains("`Origin: http://evil.example`"), "{cross}");
        assert!(open("127.0.0.1:7480", Some("null")).is_some());
        // On the network any name may reach the page (the token guards it); origins still must match.
        let token = Access::Token("t".into());
        assert_eq!(foreign(&token, Some("robot.lan:7480"), None), None);
        assert_eq!(
            foreign(
                &token,
                Some("robot.lan:7480"),
                Some("http://robot.lan:7480")
            ),
            None
        );
        assert!(foreign(&token, Some("robot.lan:7480"), Some("http://evil.example")).is_some());
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
