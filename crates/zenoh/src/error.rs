//! Why a whiteboard across processes could not be held, joined or pinged, each variant saying
//! what; shown to the person as one line naming the endpoint or key.

use std::fmt;
use std::path::PathBuf;

#[derive(Debug)]
pub enum NetworkError {
    /// Zenoh's own configuration file could not be read.
    Config { path: PathBuf, cause: String },
    /// An endpoint not written as Zenoh's `tcp/HOST:PORT`.
    Endpoint(String),
    /// A process of a mesh listening on every address (`tcp/0.0.0.0:7447`): it cannot tell
    /// itself among its peers, and would dial itself.
    MeshListen(String),
    /// Zenoh refused a setting or a call: what was being done, and Zenoh's word.
    Zenoh { doing: String, cause: String },
    /// No whiteboard answered at the endpoint in time.
    NoBoard {
        board: Option<String>,
        endpoint: String,
    },
    /// The board's processes answered, then stopped.
    Stopped { endpoint: String },
}

impl NetworkError {
    /// A failed Zenoh call while `doing` something.
    pub(crate) fn zenoh(doing: impl Into<String>, cause: impl fmt::Display) -> NetworkError {
        NetworkError::Zenoh {
            doing: doing.into(),
            cause: cause.to_string(),
        }
    }
}

impl fmt::Display for NetworkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NetworkError::Config { path, cause } => write!(
                f,
                "cannot read the Zenoh configuration {}: {cause}",
                path.display()
            ),
            NetworkError::Endpoint(e) => write!(
                f,
                "`{e}` is not a Zenoh endpoint; write it as tcp/HOST:PORT (tcp/127.0.0.1:7447)"
            ),
            NetworkError::MeshListen(e) => write!(
                f,
                "with --peer, --listen names this robot's own address as its teammates dial it (tcp/10.0.5.1:7447), not `{e}`: the robot finds itself in the list by it"
            ),
            NetworkError::Zenoh { doing, cause } => write!(f, "{doing}: {cause}"),
            NetworkError::NoBoard { board, endpoint } => {
                let which = board
                    .as_ref()
                    .map_or_else(|| "whiteboard".to_string(), |b| format!("whiteboard `{b}`"));
                write!(
                    f,
                    "no {which} answered at {endpoint} (is a `proclaim run … --listen {endpoint}` running?)"
                )
            }
            NetworkError::Stopped { endpoint } => {
                write!(f, "the whiteboard at {endpoint} stopped answering")
            }
        }
    }
}

impl std::error::Error for NetworkError {}
