//! Reading a file the user names (a recording, a trace, a checkpoint) whole, refused before a
//! byte is read when it is larger than such a file can be here: a wrong path must end in an
//! error that says so, not in the process taking all the machine's memory.

use crate::failure::Failure;
use std::path::Path;

/// The largest recording, trace or checkpoint read: far beyond a long match's (hours of
/// rounds), well within what parsing it takes in memory.
pub const LARGEST: u64 = 1 << 30;

/// The text of `path`, `what` it should be naming it in the refusal.
pub fn read_text(path: &Path, what: &'static str) -> Result<String, Failure> {
    let failed = |error| Failure::Read {
        path: path.to_path_buf(),
        error,
    };
    let size = std::fs::metadata(path).map_err(failed)?.len();
    if size > LARGEST {
        return Err(Failure::TooLarge {
            path: path.to_path_buf(),
            what,
            size,
            limit: LARGEST,
        });
    }
    std::fs::read_to_string(path).map_err(failed)
}
