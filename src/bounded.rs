//! Reading a file the user names (a recording, a trace, a checkpoint) whole, refused before a
//! byte is read when it is larger than such a file can be here: a wrong path must end in an
//! error that says so, not in the process taking all the machine's memory.

use crate::failure::Failure;
use proclaim_syntax::Unread;
use std::path::Path;

/// The largest recording, trace or checkpoint read: far beyond a long match's (hours of
/// rounds), well within what parsing it takes in memory.
pub const LARGEST: u64 = 1 << 30;

/// The text of `path`, `what` it should be naming it in the refusal. The bound holds for what
/// is read, not what the file says it holds: a device or a pipe (`/dev/zero`) says 0.
pub fn read_text(path: &Path, what: &'static str) -> Result<String, Failure> {
    let failed = |error| Failure::Read {
        path: path.to_path_buf(),
        error,
    };
    let too_large = |size| Failure::TooLarge {
        path: path.to_path_buf(),
        what,
        size,
        limit: LARGEST,
    };
    let bytes = proclaim_syntax::read_within(path, LARGEST).map_err(|unread| match unread {
        Unread::Io(error) => failed(error),
        Unread::TooLarge(size) => too_large(size),
    })?;
    String::from_utf8(bytes)
        .map_err(|e| failed(std::io::Error::new(std::io::ErrorKind::InvalidData, e)))
}
