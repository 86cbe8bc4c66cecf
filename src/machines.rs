//! Machine files named on the command line: native `.machine`, Qfsm `.fsm`, or either file of
//! a T/A pair.

use crate::failure::Failure;
use proclaim_behaviour::{read_machines, Folder};
use proclaim_fsm::{machine_format, Imported, MachineFormat};
use std::path::Path;

/// A native or Qfsm file, or either file of a T/A pair (its partner is found beside it); `None`
/// for anything else (a theory).
pub fn machine_file(name: &str) -> Result<Option<Imported>, Failure> {
    let path = Path::new(name);
    let file_name = path
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or_default();
    let is_machine = match machine_format(path) {
        None => false,
        // A `T…txt` without its partner is more likely a text file than half a machine.
        Some(MachineFormat::TablePair { t, a, .. }) => if t == path { a } else { t }.exists(),
        Some(_) => true,
    };
    if !is_machine {
        return Ok(None);
    }
    if let Err(error) = std::fs::metadata(path) {
        return Err(Failure::Read {
            path: path.to_path_buf(),
            error,
        });
    }
    let folder = path.parent().unwrap_or(Path::new(""));
    Ok(Some(read_machines(&Folder::new(folder), file_name)))
}
