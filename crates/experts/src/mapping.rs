//! The mapping file of a reasoner expert: which whiteboard message feeds which input atom, one
//! `atom = MessageType` a line, `#` comments.

use proclaim_syntax::{code_lines, LineError, LineErrors};
use rustc_hash::FxHashMap;

/// Reads a mapping: input atom → message type. Every bad line is reported.
pub fn parse_mapping(text: &str) -> Result<FxHashMap<String, String>, LineErrors> {
    let mut map = FxHashMap::default();
    let mut errors = Vec::new();
    for (line, code) in code_lines(text) {
        match code.split_once('=') {
            Some((atom, ty)) if !atom.trim().is_empty() && !ty.trim().is_empty() => {
                if map
                    .insert(atom.trim().to_string(), ty.trim().to_string())
                    .is_some()
                {
                    errors.push(LineError {
                        line,
                        message: format!("`{}` is mapped twice", atom.trim()),
                    });
                }
            }
            _ => errors.push(LineError {
                line,
                message: format!("expected `atom = MessageType`, found `{code}`"),
            }),
        }
    }
    if errors.is_empty() {
        Ok(map)
    } else {
        Err(LineErrors(errors))
    }
}
