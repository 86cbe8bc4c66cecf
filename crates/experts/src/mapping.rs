//! The mapping file of a reasoner expert: which whiteboard message feeds which input atom, one
//! `atom = MessageType` a line, `#` comments.

use rustc_hash::FxHashMap;
use std::fmt;

/// A line of a mapping file that is not `atom = MessageType`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MappingError {
    pub line: usize,
    pub message: String,
}

impl fmt::Display for MappingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for MappingError {}

/// Reads a mapping: input atom → message type. Every bad line is reported.
pub fn parse_mapping(text: &str) -> Result<FxHashMap<String, String>, Vec<MappingError>> {
    let mut map = FxHashMap::default();
    let mut errors = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.split('#').next().unwrap_or("").trim();
        if code.is_empty() {
            continue;
        }
        match code.split_once('=') {
            Some((atom, ty)) if !atom.trim().is_empty() && !ty.trim().is_empty() => {
                if map
                    .insert(atom.trim().to_string(), ty.trim().to_string())
                    .is_some()
                {
                    errors.push(MappingError {
                        line: i + 1,
                        message: format!("`{}` is mapped twice", atom.trim()),
                    });
                }
            }
            _ => errors.push(MappingError {
                line: i + 1,
                message: format!("expected `atom = MessageType`, found `{code}`"),
            }),
        }
    }
    if errors.is_empty() {
        Ok(map)
    } else {
        Err(errors)
    }
}
