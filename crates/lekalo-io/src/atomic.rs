//! Atomic output: write to a temporary file in the target's directory, then rename it over the
//! target, so a reader never sees a half-written file and a failed run leaves no debris. Inputs
//! are never overwritten.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{IoError, IoResult};

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
/// Refuses to write over any of `inputs` (compared after resolving symbolic links).
///
/// # Errors
/// [`IoError::WouldOverwriteInput`] if `path` is one of `inputs`; [`IoError::Write`] if the
/// directory is not writable or the rename fails.
pub fn write_atomic(path: &Path, bytes: &[u8], inputs: &[PathBuf]) -> IoResult<()> {
    check_not_input(path, inputs)?;
    let write_err = |error| IoError::Write {
        path: path.to_path_buf(),
        error,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(&dir).map_err(write_err)?;
    tmp.write_all(bytes).map_err(write_err)?;
    tmp.as_file().sync_all().map_err(write_err)?;
    tmp.persist(path).map_err(|e| write_err(e.error))?;
    Ok(())
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
        let e = read_input(&dir.path().join("missing.json")).unwrap_err();
        assert!(e.to_string().contains("missing.json"), "{e}");
    }
}
