//! Machine files named on the command line: native `.machine`, Qfsm `.fsm`, or either file of
//! a T/A pair.

use crate::failure::Failure;
use proclaim_behaviour::{read_machines, Folder};
use proclaim_fsm::{is_native, partner_of, Imported};
use std::path::Path;

/// A native or Qfsm file, or either file of a T/A pair (its partner is found beside it); `None`
/// for anything else (a theory).
pub fn machine_file(name: &str) -> Result<Option<Imported>, Failure> {
    let path = Path::new(name);
    let file_name = path
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or_default();
    let qfsm = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("fsm"));
    let table =
        file_name.ends_with(".txt") && (file_name.starts_with('T') || file_name.starts_with('A'));
    let is_machine = is_native(name)
        || qfsm
        || table && partner_of(path).is_some_and(|partner| partner.exists());
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
