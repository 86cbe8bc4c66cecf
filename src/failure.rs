//! Why a command could not do its job, each variant saying what went wrong; printed once, then
//! the process exits with status 2.

use std::fmt;
use std::io::Write;
use std::path::PathBuf;

pub enum Failure {
    /// The file could not be read.
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    /// The file is larger than `what` it should be can be here (`limit` bytes).
    TooLarge {
        path: PathBuf,
        what: &'static str,
        size: u64,
        limit: u64,
    },
    /// The output could not be written.
    Write {
        path: PathBuf,
        error: std::io::Error,
    },
    /// A theory or a query has errors; `rendered` already says where and why; `what` names it.
    Invalid {
        what: &'static str,
        rendered: String,
        errors: usize,
    },
    /// A command-line argument is wrong (an unknown atom, a malformed `--set`).
    Argument(String),
    /// A benchmark child process failed.
    Bench(String),
    /// A behaviour could not be started (a socket could not be opened).
    Start(proclaim_behaviour::BehaviourError),
    /// A whiteboard across processes could not be held or joined; the message names the
    /// endpoint and why.
    Network(String),
    /// The async runtime could not be built (out of threads or file descriptors).
    Runtime(std::io::Error),
}

impl Failure {
    pub fn report(&self) {
        let mut err = std::io::stderr().lock();
        let _ = match self {
            Failure::Invalid {
                what,
                rendered,
                errors,
            } => writeln!(
                err,
                "{rendered}error: {what} has {errors} error{}",
                if *errors == 1 { "" } else { "s" }
            ),
            other => writeln!(err, "error: {other}"),
        };
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Read { path, error } => write!(f, "cannot read {}: {error}", path.display()),
            Failure::TooLarge {
                path,
                what,
                size,
                limit,
            } => write!(
                f,
                "{}: {size} bytes, more than {what} here can be ({limit} at most)",
                path.display()
            ),
            Failure::Write { path, error } => write!(f, "cannot write {}: {error}", path.display()),
            Failure::Invalid { what, errors, .. } => write!(f, "{what} has {errors} errors"),
            Failure::Argument(message) => f.write_str(message),
            Failure::Bench(message) => write!(f, "benchmark failed: {message}"),
            Failure::Start(message) => write!(f, "cannot start the behaviour: {message}"),
            Failure::Network(message) => f.write_str(message),
            Failure::Runtime(error) => write!(f, "cannot start the async runtime: {error}"),
        }
    }
}
