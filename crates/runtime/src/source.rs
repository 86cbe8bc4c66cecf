//! A source file read whole, within a bound (the one file of this crate besides `host.rs` that
//! does I/O). Every reader holds a file's text and the tree it
//! builds from it in memory at once, many times the file's size, so a file past the bound is
//! refused before it is read, saying how large it is and what the bound is. The bound holds
//! for what is read, not only for what the file says it holds: a pipe or a device
//! (`/dev/zero`) says 0, and a file may grow while it is read.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// The most bytes a source file (a theory, a machine, a manifest, a script, a chart) may hold.
pub const MAX_SOURCE_BYTES: u64 = 256 << 20;

/// Why a file was not read.
#[derive(Debug)]
pub enum Unread {
    /// The file system's own error.
    Io(Error),
    /// The file holds (or said it holds) this many bytes, more than the bound.
    TooLarge(u64),
}

/// The bytes of the file at `path`, when it holds at most `limit`.
pub fn read_within(path: impl AsRef<Path>, limit: u64) -> Result<Vec<u8>, Unread> {
    let file = std::fs::File::open(path).map_err(Unread::Io)?;
    let said = file.metadata().map_err(Unread::Io)?.len();
    if said > limit {
        return Err(Unread::TooLarge(said));
    }
    let mut bytes = Vec::new();
    (file.take(limit + 1).read_to_end(&mut bytes)).map_err(Unread::Io)?;
    match bytes.len() as u64 {
        read if read > limit => Err(Unread::TooLarge(read)),
        _ => Ok(bytes),
    }
}

/// The text of the source file at `path`: an error of kind `InvalidData` saying its size where
/// it holds more than [`MAX_SOURCE_BYTES`], or where it is not UTF-8; else the file system's.
pub fn read_source(path: impl AsRef<Path>) -> std::io::Result<String> {
    let bytes = read_within(path, MAX_SOURCE_BYTES).map_err(|unread| match unread {
        Unread::Io(e) => e,
        Unread::TooLarge(size) => Error::new(ErrorKind::InvalidData, too_large(size)),
    })?;
    String::from_utf8(bytes).map_err(|e| Error::new(ErrorKind::InvalidData, e))
}

/// The refusal of a source file of `size` bytes.
pub fn too_large(size: u64) -> String {
    let mib = |bytes: u64| bytes as f64 / f64::from(1 << 20);
    format!(
        "the file is {:.0} MiB, over the {:.0} MiB a source file may be (sources are read whole)",
        mib(size),
        mib(MAX_SOURCE_BYTES)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_past_the_bound_is_refused_saying_its_size_and_one_within_is_read() {
        let dir = std::env::temp_dir().join(format!("proclaim-source-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let large = dir.join("large.dl");
        // Sparse: no disk is taken by the bytes never written.
        let file = std::fs::File::create(&large).unwrap();
        file.set_len(MAX_SOURCE_BYTES + (44 << 20)).unwrap();
        let error = read_source(&large).unwrap_err();
        assert_eq!(error.kind(), ErrorKind::InvalidData);
        assert_eq!(
            error.to_string(),
            "the file is 300 MiB, over the 256 MiB a source file may be (sources are read whole)"
        );
        let small = dir.join("small.dl");
        std::fs::write(&small, "a.\n").unwrap();
        assert_eq!(read_source(&small).unwrap(), "a.\n");
        assert!(matches!(read_within(&small, 2), Err(Unread::TooLarge(3))));
        let missing = read_source(dir.join("missing.dl")).unwrap_err();
        assert_eq!(missing.kind(), ErrorKind::NotFound);
        std::fs::write(&small, [0xff, 0xfe]).unwrap();
        assert_eq!(
            read_source(&small).unwrap_err().kind(),
            ErrorKind::InvalidData
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A device says it holds nothing and never ends: the bound holds for what is read.
    #[test]
    fn an_endless_device_is_read_no_further_than_the_bound() {
        assert!(matches!(
            read_within("/dev/zero", 1 << 20),
            Err(Unread::TooLarge(size)) if size == (1 << 20) + 1
        ));
    }
}
