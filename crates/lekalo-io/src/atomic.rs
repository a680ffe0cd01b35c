//! Atomic output: write to a temporary file in the target's directory, then rename it over the
//! target, so a reader never sees a half-written file and a failed run leaves no debris. Inputs
//! are never overwritten.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{IoError, IoResult};

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
/// Refuses to write over any of `inputs` (compared after resolving symbolic links).
///
/// A symbolic link is followed (the file it points to is replaced, the link stays). A target
/// that exists but is not a regular file — `/dev/null`, a named pipe, a terminal — is written
/// to directly: it cannot be replaced by a rename, and must not be.
///
/// # Errors
/// [`IoError::WouldOverwriteInput`] if `path` is one of `inputs`; [`IoError::Write`] if the
/// target is a directory, the directory is not writable or the rename fails.
pub fn write_atomic(path: &Path, bytes: &[u8], inputs: &[PathBuf]) -> IoResult<()> {
    check_not_input(path, inputs)?;
    let write_err = |error| IoError::Write {
        path: path.to_path_buf(),
        error,
    };
    let target = match Target::of(path) {
        Target::Special => {
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(write_err)?;
            return f.write_all(bytes).map_err(write_err);
        }
        Target::Directory => {
            return Err(write_err(std::io::Error::other(
                "it is a directory; give a file name",
            )))
        }
        Target::File(resolved) => resolved,
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(&dir).map_err(write_err)?;
    tmp.write_all(bytes).map_err(write_err)?;
    tmp.as_file().sync_all().map_err(write_err)?;
    tmp.persist(&target).map_err(|e| write_err(e.error))?;
    Ok(())
}

/// What an output path names.
#[derive(Debug, PartialEq)]
enum Target {
    /// A regular file (resolved through symbolic links) or a path that does not exist yet.
    File(PathBuf),
    /// A directory.
    Directory,
    /// Something that exists but is neither: a device, a pipe, a socket.
    Special,
}

impl Target {
    fn of(path: &Path) -> Target {
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Target::Directory,
            Ok(m) if !m.is_file() => Target::Special,
            Ok(_) => {
                Target::File(std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()))
            }
            Err(_) => Target::File(path.to_path_buf()),
        }
    }
}

/// [`IoError::WouldOverwriteInput`] if `path` names the same file as one of `inputs`.
///
/// # Errors
/// As described.
pub fn check_not_input(path: &Path, inputs: &[PathBuf]) -> IoResult<()> {
    let target = std::fs::canonicalize(path).ok();
    for input in inputs {
        let same = match (&target, std::fs::canonicalize(input).ok()) {
            (Some(a), Some(b)) => *a == b,
            _ => path == input.as_path(),
        };
        if same {
            return Err(IoError::WouldOverwriteInput {
                path: path.to_path_buf(),
            });
        }
    }
    Ok(())
}

/// Reads a whole input: a file, or standard input when `path` is `-`. Returns the text and the
/// name to use in messages.
///
/// # Errors
/// [`IoError::Read`] if the file is missing, unreadable or not UTF-8.
pub fn read_input(path: &Path) -> IoResult<(String, String)> {
    if path.as_os_str() == "-" {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut s).map_err(|error| {
            IoError::Read {
                path: PathBuf::from("<stdin>"),
                error,
            }
        })?;
        return Ok((s, "<stdin>".to_string()));
    }
    let text = std::fs::read_to_string(path).map_err(|error| IoError::Read {
        path: path.to_path_buf(),
        error,
    })?;
    Ok((text, path.display().to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn devices_are_written_in_place_and_links_followed() {
        // never rename over /dev/null (that would replace the device with a file)
        assert_eq!(Target::of(Path::new("/dev/null")), Target::Special);
        write_atomic(Path::new("/dev/null"), b"discarded", &[]).unwrap();
        use std::os::unix::fs::FileTypeExt;
        let ft = std::fs::metadata("/dev/null").unwrap().file_type();
        assert!(ft.is_char_device(), "/dev/null is still a device");
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.txt");
        let link = dir.path().join("link.txt");
        std::fs::write(&real, "old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_atomic(&link, b"new", &[]).unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink(),
            "link kept"
        );
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        let e = write_atomic(&link, b"x", std::slice::from_ref(&real)).unwrap_err();
        assert!(matches!(e, IoError::WouldOverwriteInput { .. }), "{e}");
    }

    #[test]
    fn writes_replaces_and_protects_inputs() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.txt");
        write_atomic(&out, b"one", &[]).unwrap();
        write_atomic(&out, b"two", &[]).unwrap();
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "two");
        let e = write_atomic(&out, b"three", std::slice::from_ref(&out)).unwrap_err();
        assert!(matches!(e, IoError::WouldOverwriteInput { .. }), "{e}");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "two");
        // only the output remains: no temporary files left behind
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        let e = write_atomic(&dir.path().join("no/such/dir/x"), b"", &[]).unwrap_err();
        assert!(
            matches!(e, IoError::Write { .. }) && !e.is_bad_input(),
            "{e}"
        );
        let e = write_atomic(dir.path(), b"", &[]).unwrap_err();
        assert!(e.to_string().contains("it is a directory"), "{e}");
        let e = read_input(&dir.path().join("missing.json")).unwrap_err();
        assert!(e.to_string().contains("missing.json"), "{e}");
    }
}
