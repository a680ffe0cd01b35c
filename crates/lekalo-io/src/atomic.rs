//! Atomic output: write to a temporary file in the target's directory, then rename it over the
//! target, so a reader never sees a half-written file and a failed run leaves no debris. Inputs
//! are never overwritten.

use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use crate::error::{IoError, IoResult};

/// How [`write_atomic_with`] treats an existing target.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WriteOptions {
    /// Replace a write-protected file (no write permission for anyone) too; without it such a
    /// file is refused with [`IoError::WriteProtected`], as a shell's `>` refuses it.
    pub force: bool,
}

/// Temporary files being written, removed by [`remove_temporary_files`] when the process is
/// interrupted (a signal handler cannot run destructors).
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    PENDING
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The files this process has read, once [`protect_files_read`] has turned the record on
/// (`None` until then): every atomic write refuses them as it refuses its `inputs`.
static READ: Mutex<Option<Vec<PathBuf>>> = Mutex::new(None);

fn files_read() -> std::sync::MutexGuard<'static, Option<Vec<PathBuf>>> {
    READ.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// From now on, every file that the readers of this crate open by path ([`read_input`],
/// [`read_input_bytes`], the `.npy` and Parquet file readers), and every path given to
/// [`note_read`], is protected from the atomic writes of this process as if it were among
/// their `inputs`. A command-line tool that reads files through several options calls this at
/// the start of each command (each call starts an empty record), so that no option can name an
/// output that replaces one of the command's inputs; a program that reads a file, changes it
/// and saves it on purpose does not call it.
pub fn protect_files_read() {
    *files_read() = Some(Vec::new());
}

/// Records `path` as read, for [`protect_files_read`] (nothing happens while the record is
/// off). Standard input (`-`) is not a file and is not recorded.
pub fn note_read(path: &Path) {
    if path.as_os_str() == "-" {
        return;
    }
    if let Some(read) = files_read().as_mut() {
        // resolved now, while it exists, so that a later relative or linked name still matches
        let p = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        if !read.contains(&p) {
            read.push(p);
        }
    }
}

/// Removes every temporary file that a [`write_atomic`] in progress has created and not yet
/// renamed into place, and keeps the registry locked so that no new one is started: call it
/// from a SIGINT/SIGTERM handler just before the process exits. Returns how many were removed.
pub fn remove_temporary_files() -> usize {
    let mut guard = pending();
    let n = guard
        .drain(..)
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count();
    // Hold the lock until the process exits: a writer that gets here later blocks instead of
    // creating a new temporary file.
    std::mem::forget(guard);
    n
}

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
/// Refuses to write over any of `inputs` (compared after resolving symbolic links) and over a
/// write-protected file; see [`write_atomic_with`].
///
/// # Errors
/// As [`write_atomic_with`].
pub fn write_atomic(path: &Path, bytes: &[u8], inputs: &[PathBuf]) -> IoResult<()> {
    write_atomic_with(path, bytes, inputs, WriteOptions::default())
}

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
/// Refuses to write over any of `inputs` (compared after resolving symbolic links).
///
/// A new file is created with mode `0666` minus the umask, like a shell's `>`; a replaced file
/// keeps its mode. A write-protected target is refused unless `options.force`.
/// A symbolic link is followed (the file it points to is replaced, the link stays). A target
/// that exists but is not a regular file — `/dev/null`, a named pipe, a terminal — is written
/// to directly: it cannot be replaced by a rename, and must not be. The temporary file is
/// removed if anything fails, and by [`remove_temporary_files`] on an interrupt.
///
/// # Errors
/// [`IoError::WouldOverwriteInput`] if `path` is one of `inputs`; [`IoError::WriteProtected`]
/// for a write-protected target without `force`; [`IoError::OutputPath`] if the target is a
/// directory, or its folder does not exist or is not writable; [`IoError::Write`] if writing
/// or the rename fails.
pub fn write_atomic_with(
    path: &Path,
    bytes: &[u8],
    inputs: &[PathBuf],
    options: WriteOptions,
) -> IoResult<()> {
    write_atomic_stream(path, inputs, options, |w| w.write_all(bytes))
}

/// [`write_atomic_with`] for output made piece by piece: `fill` writes into the temporary
/// file (buffered), which is renamed over `path` only if `fill` succeeds, so a large output
/// never has to be held in memory whole.
///
/// # Errors
/// As [`write_atomic_with`]; an error of `fill` as [`IoError::Write`].
pub fn write_atomic_stream(
    path: &Path,
    inputs: &[PathBuf],
    options: WriteOptions,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> IoResult<()> {
    write_atomic_send(path, inputs, options, |w| fill(w))
}

/// [`write_atomic_stream`] for a `fill` that needs a writer it can send to other threads (the
/// Parquet writer).
///
/// # Errors
/// As [`write_atomic_with`]; an error of `fill` as [`IoError::Write`].
pub fn write_atomic_send(
    path: &Path,
    inputs: &[PathBuf],
    options: WriteOptions,
    fill: impl FnOnce(&mut (dyn Write + Send)) -> std::io::Result<()>,
) -> IoResult<()> {
    write_atomic_core(path, inputs, options, false, |w| fill(&mut Writes(w)))
}

/// A writer that can also seek and be sent to other threads: what [`write_atomic_seek`] gives
/// its `fill`.
pub trait WriteSeek: Write + Seek + Send {}

impl<T: Write + Seek + Send> WriteSeek for T {}

/// [`write_atomic_stream`] for a `fill` that seeks back in what it wrote (a zip archive fills in
/// each member's size and checksum after the member), so that such a file is written straight
/// into its temporary file rather than built in memory first. A target that cannot seek (a pipe,
/// a device) is given the file made in memory.
///
/// # Errors
/// As [`write_atomic_with`]; an error of `fill` as [`IoError::Write`].
pub fn write_atomic_seek(
    path: &Path,
    inputs: &[PathBuf],
    options: WriteOptions,
    fill: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
) -> IoResult<()> {
    write_atomic_core(path, inputs, options, true, fill)
}

/// `&mut dyn WriteSeek` as a `dyn Write + Send` (no trait upcasting at the crate's Rust version).
struct Writes<'a>(&'a mut dyn WriteSeek);

impl Write for Writes<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.write(buf)
    }
    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.0.write_all(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.0.flush()
    }
}

/// The atomic write behind the public functions; `seeks` says that `fill` may seek, so that a
/// target that cannot is given the output made in memory.
fn write_atomic_core(
    path: &Path,
    inputs: &[PathBuf],
    options: WriteOptions,
    seeks: bool,
    fill: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
) -> IoResult<()> {
    check_not_input(path, inputs)?;
    let write_err = |error| IoError::Write {
        path: path.to_path_buf(),
        error,
    };
    let target = match Target::of(path) {
        Target::Special => {
            let f = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(write_err)?;
            let mut w = std::io::BufWriter::new(f);
            if seeks {
                let mut made = std::io::Cursor::new(Vec::new());
                return fill(&mut made)
                    .and_then(|()| w.write_all(made.get_ref()))
                    .and_then(|()| w.flush())
                    .map_err(write_err);
            }
            return fill(&mut w).and_then(|()| w.flush()).map_err(write_err);
        }
        Target::Directory => {
            return Err(IoError::OutputPath {
                path: path.to_path_buf(),
                reason: "it is a directory; give a file name".into(),
            })
        }
        Target::File(resolved) => resolved,
    };
    let existing = std::fs::metadata(&target).ok().map(|m| m.permissions());
    if let Some(perm) = &existing {
        if perm.readonly() && !options.force {
            return Err(IoError::WriteProtected {
                path: path.to_path_buf(),
            });
        }
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".lekalo-").suffix(".tmp");
    #[cfg(unix)]
    {
        // 0666 at creation: the kernel applies the umask, as for a shell's `>`
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let tmp = {
        let mut guard = pending();
        // tempfile adds its own name for the file (".lekalo-XXXXXX.tmp"), which the user never
        // gave: the error names the output, with the operating system's reason only
        let tmp = builder
            .tempfile_in(&dir)
            .map_err(|e| temporary_file_error(path, &e, &dir))?;
        guard.push(tmp.path().to_path_buf());
        tmp
    };
    let tmp_path = tmp.path().to_path_buf();
    let result = (|| {
        let tmp = fill_syncing(tmp, SYNC_EVERY, fill)?;
        if let Some(perm) = existing {
            tmp.as_file().set_permissions(perm)?;
        }
        tmp.as_file().sync_all()?;
        tmp.persist(&target).map(|_| ()).map_err(|e| e.error)
    })();
    pending().retain(|p| *p != tmp_path);
    // on failure the temporary file was dropped (and removed) inside the closure
    result.map_err(write_err)
}

/// The error of creating the temporary file in `dir` for the output `path`, in the words of the
/// output's folder: tempfile's own text names the temporary file (".lekalo-XXXXXX.tmp"), which
/// the user never gave. A missing or closed folder is the user's choice of path
/// ([`IoError::OutputPath`]); anything else a failure to write ([`IoError::Write`]).
fn temporary_file_error(path: &Path, e: &std::io::Error, dir: &Path) -> IoError {
    let output_path = |reason: String| IoError::OutputPath {
        path: path.to_path_buf(),
        reason,
    };
    match e.kind() {
        std::io::ErrorKind::NotFound => output_path(format!(
            "the folder {} does not exist; create it or choose another output path",
            dir.display()
        )),
        std::io::ErrorKind::PermissionDenied => output_path(format!(
            "no permission to create a file in {}; choose another output path",
            dir.display()
        )),
        kind => IoError::Write {
            path: path.to_path_buf(),
            error: std::io::Error::new(
                kind,
                format!("cannot create a file in {}: {kind}", dir.display()),
            ),
        },
    }
}

/// Bytes written to a temporary file between two requests to flush it to the disk.
const SYNC_EVERY: u64 = 16 << 20;

/// Runs `fill` on `tmp` (buffered) while a helper thread flushes what has been written so far
/// to the disk (`sync_data`) each time another `every` bytes have gone in, so that the disk
/// works while the output is still being made and the final `fsync` waits for the last part
/// only. A failed flush fails the write: the helper shares the file's open description, so an
/// error it was told of would not be told again to the final `fsync`.
fn fill_syncing(
    tmp: tempfile::NamedTempFile,
    every: u64,
    fill: impl FnOnce(&mut dyn WriteSeek) -> std::io::Result<()>,
) -> std::io::Result<tempfile::NamedTempFile> {
    let file = tmp.as_file().try_clone()?;
    let failed: Mutex<Option<std::io::Error>> = Mutex::new(None);
    let (ask, asked) = std::sync::mpsc::sync_channel::<()>(1);
    let tmp = std::thread::scope(|s| {
        let (file, failed) = (&file, &failed);
        s.spawn(move || {
            while asked.recv().is_ok() {
                if let Err(e) = file.sync_data() {
                    if let Ok(mut f) = failed.lock() {
                        f.get_or_insert(e);
                    }
                }
            }
        });
        // small enough that the large blocks of the list writers go to the file without a copy
        let mut w = std::io::BufWriter::with_capacity(
            1 << 16,
            Syncing {
                file: tmp,
                since: 0,
                every,
                ask: Some(ask),
            },
        );
        fill(&mut w)?;
        // the request channel closes with the writer, which ends the helper
        w.into_inner()
            .map_err(std::io::IntoInnerError::into_error)
            .map(|s| s.file)
    })?;
    if let Some(e) = failed.into_inner().ok().flatten() {
        return Err(e);
    }
    Ok(tmp)
}

/// A temporary file that asks for a flush to the disk every `every` bytes written.
struct Syncing {
    file: tempfile::NamedTempFile,
    since: u64,
    every: u64,
    ask: Option<std::sync::mpsc::SyncSender<()>>,
}

impl Write for Syncing {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.since += n as u64;
        if self.since >= self.every {
            self.since = 0;
            // a request already waiting covers this one too
            if let Some(ask) = &self.ask {
                let _ = ask.try_send(());
            }
        }
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl Seek for Syncing {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        self.file.seek(pos)
    }
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

/// [`IoError::WouldOverwriteInput`] if `path` names the same file as one of `inputs`, or as a
/// file this process has read (see [`protect_files_read`]).
///
/// # Errors
/// As described.
pub fn check_not_input(path: &Path, inputs: &[PathBuf]) -> IoResult<()> {
    let target = std::fs::canonicalize(path).ok();
    let read = files_read().clone().unwrap_or_default();
    for input in inputs.iter().chain(&read) {
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
/// A UTF-8 byte-order mark at the start is removed (editors on Windows write one), so that it
/// cannot glue itself to the first field of every text format.
///
/// A STEP or IGES file (by its extension) is the exception: those formats are ASCII, anything
/// else belongs in a string (a name, a description) written with escapes, yet CAD systems
/// write names in Latin-1 or another 8-bit code page. Each byte of such a file that is not part
/// of UTF-8 text is read as `?` (one byte for one, so IGES columns and Hollerith counts hold),
/// and the geometry is read; only names can show the `?`.
///
/// # Errors
/// [`IoError::Read`] if the file is missing, unreadable or not UTF-8 (outside STEP and IGES);
/// [`IoError::TooLarge`] if memory for it cannot be reserved; [`IoError::OverLimit`] above the
/// input limit ([`limit_input_bytes`]).
pub fn read_input(path: &Path) -> IoResult<(String, String)> {
    read_input_within(path, MAX_INPUT_BYTES.load(Ordering::Relaxed))
}

/// [`read_input`] with the input limit `max_bytes` of this call instead of the process's (a
/// library caller's own limit, such as Python's `max_input_bytes=`).
///
/// # Errors
/// As [`read_input`].
pub fn read_input_within(path: &Path, max_bytes: u64) -> IoResult<(String, String)> {
    let (mut bytes, name) = read_input_bytes_within(path, max_bytes)?;
    if let Some(kind) = utf16(&bytes) {
        return Err(IoError::Read {
            path: PathBuf::from(name),
            error: std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("{kind} text; lekalo reads UTF-8: save the file as UTF-8"),
            ),
        });
    }
    if is_cad_file(path) {
        eight_bit_as_question_marks(&mut bytes);
    }
    let text = String::from_utf8(bytes)
        .map_err(|e| not_utf8(&name, e.as_bytes(), e.utf8_error().valid_up_to()))?;
    Ok((strip_bom(text), name))
}

/// Whether `path` names a STEP or IGES file by its extension (any case).
fn is_cad_file(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
        ["step", "stp", "p21", "igs", "iges"]
            .iter()
            .any(|c| e.eq_ignore_ascii_case(c))
    })
}

/// Replaces, in place, every byte of `bytes` that is not part of a UTF-8 character by `?`:
/// valid characters are kept and the length is unchanged. O(n).
fn eight_bit_as_question_marks(bytes: &mut [u8]) {
    let mut at = 0;
    while let Err(e) = std::str::from_utf8(&bytes[at..]) {
        let bad = at + e.valid_up_to();
        let len = e.error_len().unwrap_or(bytes.len() - bad);
        bytes[bad..bad + len].fill(b'?');
        at = bad + len;
    }
}

/// The kind of UTF-16 text `bytes` starts with: a UTF-16 byte-order mark, or a zero byte in one
/// of the first two (an ASCII character in UTF-16), which no UTF-8 text of lekalo's formats
/// holds. Such a file is otherwise refused at its first byte or read as JSON with an error in
/// column 1, which names neither the encoding nor the fix.
fn utf16(bytes: &[u8]) -> Option<&'static str> {
    match bytes {
        [0xFF, 0xFE, ..] => Some("UTF-16 (little-endian, with a byte-order mark)"),
        [0xFE, 0xFF, ..] => Some("UTF-16 (big-endian, with a byte-order mark)"),
        [0, b, ..] if *b != 0 => Some("UTF-16 (big-endian)"),
        [a, 0, ..] if *a != 0 => Some("UTF-16 (little-endian)"),
        _ => None,
    }
}

/// `bytes`, a whole input named `name`, as UTF-8 text: the check of [`read_input`] for text
/// that did not come from a file (a request's body).
///
/// ```
/// let e = lekalo_io::utf8_text(b"{\n  \"x\xff\": 1}", "file").unwrap_err();
/// assert!(e.to_string().contains("file: not UTF-8 text at line 2, column 5 (byte 6)"), "{e}");
/// ```
///
/// # Errors
/// [`IoError::Read`] naming the line, column and byte of the first byte that is not UTF-8.
pub fn utf8_text<'t>(bytes: &'t [u8], name: &str) -> IoResult<&'t str> {
    std::str::from_utf8(bytes).map_err(|e| not_utf8(name, bytes, e.valid_up_to()))
}

/// The error of the text `bytes` (a whole input) that is not UTF-8 at byte `at`, which is named
/// by its line and column (counted from 1, the column in characters) as well as its byte, so
/// that an editor can go to it. The line's bytes before `at` are read as they are (a byte that
/// is not UTF-8 among them counts as one character).
pub(crate) fn not_utf8(name: &str, bytes: &[u8], at: usize) -> IoError {
    let before = &bytes[..at.min(bytes.len())];
    let line_start = memchr::memrchr(b'\n', before).map_or(0, |i| i + 1);
    let line = 1 + memchr::memchr_iter(b'\n', before).count();
    let column = 1 + String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count();
    IoError::Read {
        path: PathBuf::from(name),
        error: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text at line {line}, column {column} (byte {at}); lekalo reads \
                 UTF-8: save the file as UTF-8"
            ),
        ),
    }
}

/// Default of the input limit ([`limit_input_bytes`], the command line's `--max-input-bytes`):
/// 1 GiB, above the largest file `--max-size`'s default of ten million entities, control points
/// or samples makes in any of lekalo's text formats.
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 1 << 30;

/// The most bytes one input may have ([`limit_input_bytes`]).
static MAX_INPUT_BYTES: AtomicU64 = AtomicU64::new(DEFAULT_MAX_INPUT_BYTES);

/// Sets the most bytes that [`read_input`] and [`read_input_bytes`] read of one input, for the
/// rest of the process ([`DEFAULT_MAX_INPUT_BYTES`] until then). It is checked against a
/// regular file's size before anything is reserved, and against what arrives from standard
/// input, a pipe or a device (`/dev/zero`, a named pipe), which has no size to check first and
/// is read through a cap of one byte more: an endless stream is refused once it passes the
/// limit instead of filling the memory. The command line sets it from `--max-input-bytes` at
/// the start of each command.
pub fn limit_input_bytes(max: u64) {
    MAX_INPUT_BYTES.store(max, Ordering::Relaxed);
}

/// [`IoError::OverLimit`] for the input `name` with more than `limit` bytes (`size` when known).
fn input_too_large(name: &str, size: Option<u64>, limit: u64) -> IoError {
    let has = match size {
        Some(n) => format!("{n} bytes"),
        None => format!("more than {limit} bytes"),
    };
    IoError::OverLimit {
        what: format!("{name}: {has}, above the input limit of {limit} bytes"),
        limit: crate::Limit::InputBytes,
        raise_to: size,
    }
}

/// Files of at least this many bytes are read by all cores at once, each a stretch of
/// [`READ_PART`] bytes by positioned reads: the copy from the page cache and the first touch of
/// the buffer's pages are then shared instead of done by one thread before any parsing starts.
const PARALLEL_READ_MIN: usize = 8 << 20;

/// The stretch of a file one positioned read fills (see [`PARALLEL_READ_MIN`]).
const READ_PART: usize = 2 << 20;

/// The bytes of a whole input, as [`read_input`] without the UTF-8 check (a reader that checks
/// the parts of a text as it parses them, in parallel, starts from here) and with the
/// byte-order mark kept.
///
/// At most the input limit ([`limit_input_bytes`]) is read: a regular file above it is refused
/// by its size, anything else (standard input, a pipe, a device) once more bytes arrive.
///
/// ```
/// lekalo_io::limit_input_bytes(1000);
/// let e = lekalo_io::read_input_bytes("/dev/zero".as_ref()).unwrap_err().to_string();
/// lekalo_io::limit_input_bytes(lekalo_io::DEFAULT_MAX_INPUT_BYTES);
/// # #[cfg(target_os = "linux")]
/// assert!(e.contains("/dev/zero: more than 1000 bytes, above the input limit of 1000 bytes; raise the limit with a larger --max-input-bytes"), "{e}");
/// ```
///
/// # Errors
/// [`IoError::Read`] if the file is missing or unreadable; [`IoError::OverLimit`] naming the
/// input, its size and the limit if it is above the input limit, or if memory for it cannot be
/// reserved.
pub fn read_input_bytes(path: &Path) -> IoResult<(Vec<u8>, String)> {
    read_input_bytes_within(path, MAX_INPUT_BYTES.load(Ordering::Relaxed))
}

/// [`read_input_bytes`] with the input limit `limit` of this call instead of the process's.
///
/// # Errors
/// As [`read_input_bytes`].
pub fn read_input_bytes_within(path: &Path, limit: u64) -> IoResult<(Vec<u8>, String)> {
    let (name, read): (String, Box<dyn std::io::Read>) = if path.as_os_str() == "-" {
        ("<stdin>".to_string(), Box::new(std::io::stdin()))
    } else {
        let f = std::fs::File::open(path).map_err(|error| IoError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        note_read(path);
        (path.display().to_string(), Box::new(f))
    };
    let read_err = |error| IoError::Read {
        path: PathBuf::from(&name),
        error,
    };
    let mut bytes = Vec::new();
    let file_meta = (path.as_os_str() != "-")
        .then(|| std::fs::metadata(path).ok())
        .flatten();
    // a regular file's size is known: refused before anything is reserved (the size of a
    // device or a pipe says nothing, 0 for both /dev/zero and a named pipe)
    let file_meta = file_meta.filter(std::fs::Metadata::is_file);
    if let Some(m) = &file_meta {
        if m.len() > limit {
            return Err(input_too_large(&name, Some(m.len()), limit));
        }
        let len = usize::try_from(m.len()).unwrap_or(usize::MAX);
        bytes
            .try_reserve_exact(len)
            .map_err(|_| IoError::TooLarge {
                what: format!(
                    "{name}: cannot reserve {} bytes of memory to read it",
                    m.len()
                ),
            })?;
        #[cfg(unix)]
        if len >= PARALLEL_READ_MIN {
            read_parallel(path, len, limit, &mut bytes).map_err(read_err)?;
            return within_limit(bytes, name, limit);
        }
    }
    // one byte past the limit is read, so that more than the limit is seen and refused
    let capped = read.take(limit.saturating_add(1));
    if file_meta.is_some() {
        // the whole length is reserved: the standard reader fills it in place (no copy through
        // a chunk buffer) and reports, rather than aborts on, a failure to grow further
        let mut capped = capped;
        capped.read_to_end(&mut bytes).map_err(read_err)?;
    } else {
        read_to_end_fallible(capped, &mut bytes).map_err(read_err)?;
    }
    within_limit(bytes, name, limit)
}

/// `bytes` of the input `name`, read through a cap of `limit + 1` bytes, or the refusal of an
/// input with more than `limit` bytes (one that grew past it while being read, or a stream).
fn within_limit(bytes: Vec<u8>, name: String, limit: u64) -> IoResult<(Vec<u8>, String)> {
    if bytes.len() as u64 > limit {
        return Err(input_too_large(&name, None, limit));
    }
    Ok((bytes, name))
}

/// Reads the file at `path`, of `len` bytes when its size was taken, into `bytes` (empty, with
/// room for `len`): the room is zeroed and then filled by positioned reads of [`READ_PART`]
/// bytes, both in parallel. A file that has grown since is read on to its end; one that has
/// shrunk is read again from the start, sequentially; either reads at most `limit + 1` bytes, so
/// that the caller sees a file that grew past the input limit.
#[cfg(unix)]
fn read_parallel(path: &Path, len: usize, limit: u64, bytes: &mut Vec<u8>) -> std::io::Result<()> {
    use rayon::prelude::*;
    use std::os::unix::fs::FileExt;
    let file = std::fs::File::open(path)?;
    // written in place, on all cores, into the room reserved (no serial pass over fresh pages)
    bytes.par_extend(rayon::iter::repeat_n(0u8, len));
    let whole = bytes
        .par_chunks_mut(READ_PART)
        .enumerate()
        .try_for_each(|(i, part)| file.read_exact_at(part, (i * READ_PART) as u64));
    match whole {
        Ok(()) => {
            let mut rest = &file;
            rest.seek(std::io::SeekFrom::Start(len as u64))?;
            let left = limit.saturating_add(1).saturating_sub(len as u64);
            read_to_end_fallible(rest.take(left), bytes)
        }
        Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            bytes.clear();
            read_to_end_fallible(
                std::fs::File::open(path)?.take(limit.saturating_add(1)),
                bytes,
            )
        }
        Err(e) => Err(e),
    }
}

/// `read_to_end` that reports a failed allocation as an error instead of aborting.
fn read_to_end_fallible(mut r: impl std::io::Read, buf: &mut Vec<u8>) -> std::io::Result<()> {
    let mut chunk = [0u8; 64 * 1024];
    loop {
        let n = match r.read(&mut chunk) {
            Ok(0) => return Ok(()),
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if buf.capacity() - buf.len() < n {
            buf.try_reserve(n.max(buf.len()))
                .map_err(|_| std::io::Error::other("out of memory while reading"))?;
        }
        buf.extend_from_slice(&chunk[..n]);
    }
}

/// `text` without a leading UTF-8 byte-order mark.
#[must_use]
pub fn strip_bom_str(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// `text` without a leading UTF-8 byte-order mark.
#[must_use]
pub fn strip_bom(mut text: String) -> String {
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    text
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

    /// Output flushed to the disk while it is written is the output written: every byte in
    /// order, seeks back included, and the temporary file renamed into place.
    #[test]
    fn flushing_while_writing_keeps_every_byte() {
        let dir = tempfile::tempdir().unwrap();
        let tmp = tempfile::NamedTempFile::new_in(dir.path()).unwrap();
        let text: Vec<u8> = (0..300_000u32).flat_map(u32::to_le_bytes).collect();
        let tmp = fill_syncing(tmp, 4096, |w| {
            for piece in text.chunks(7919) {
                w.write_all(piece)?;
            }
            w.seek(std::io::SeekFrom::Start(4))?;
            w.write_all(b"seek")
        })
        .unwrap();
        let path = dir.path().join("out.bin");
        tmp.persist(&path).unwrap();
        let mut want = text.clone();
        want[4..8].copy_from_slice(b"seek");
        assert_eq!(std::fs::read(&path).unwrap(), want);
        // a failing fill leaves its error, and no file in place
        let tmp = tempfile::NamedTempFile::new_in(dir.path()).unwrap();
        let e = fill_syncing(tmp, 1, |w| {
            w.write_all(&text)?;
            Err(std::io::Error::other("stopped"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "stopped");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
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
        // a missing folder is the caller's choice of path, not a failure to write
        let e = write_atomic(&dir.path().join("no/such/dir/x"), b"", &[]).unwrap_err();
        assert!(
            matches!(e, IoError::OutputPath { .. }) && e.is_bad_input(),
            "{e}"
        );
        let text = e.to_string();
        assert!(
            text.contains("no/such/dir/x") && text.contains("does not exist; create it"),
            "the output and the reason: {text}"
        );
        assert!(!text.contains(".lekalo-"), "no temporary name: {text}");
        let e = write_atomic(dir.path(), b"", &[]).unwrap_err();
        assert!(e.to_string().contains("it is a directory"), "{e}");
        assert!(e.is_bad_input(), "a folder given as the output: {e}");
        let e = read_input(&dir.path().join("missing.json")).unwrap_err();
        assert!(e.to_string().contains("missing.json"), "{e}");
    }

    /// A file that has grown or shrunk between the size taken and the parallel read is still
    /// read to exactly its bytes (the rest read on, or the whole read again).
    #[cfg(unix)]
    #[test]
    fn a_file_that_changed_size_is_read_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("changing.txt");
        let bytes: Vec<u8> = (0..3 * READ_PART + 5).map(|i| b"lekalo\n"[i % 7]).collect();
        std::fs::write(&path, &bytes).unwrap();
        for taken in [bytes.len() - READ_PART - 3, bytes.len() + READ_PART + 3] {
            let mut read = Vec::new();
            read_parallel(&path, taken, u64::MAX, &mut read).unwrap();
            assert!(
                read == bytes,
                "size taken {taken}: {} bytes read",
                read.len()
            );
        }
    }

    /// UTF-16 text, with or without a byte-order mark, is named as such with the fix; UTF-8
    /// with a byte-order mark is read.
    #[test]
    fn utf16_text_is_named_with_the_fix() {
        let dir = tempfile::tempdir().unwrap();
        let text = "{\"a\": 1}";
        let le: Vec<u8> = text.encode_utf16().flat_map(u16::to_le_bytes).collect();
        let be: Vec<u8> = text.encode_utf16().flat_map(u16::to_be_bytes).collect();
        let cases: [(&str, Vec<u8>, &str); 4] = [
            (
                "le-bom.json",
                [&[0xFF, 0xFE][..], &le].concat(),
                "little-endian, with a byte-order mark",
            ),
            (
                "be-bom.json",
                [&[0xFE, 0xFF][..], &be].concat(),
                "big-endian, with a byte-order mark",
            ),
            ("le.json", le, "UTF-16 (little-endian)"),
            ("be.json", be, "UTF-16 (big-endian)"),
        ];
        for (name, bytes, kind) in cases {
            let path = dir.path().join(name);
            std::fs::write(&path, bytes).unwrap();
            let e = read_input(&path).unwrap_err().to_string();
            assert!(
                e.contains(kind) && e.contains("save the file as UTF-8"),
                "{name}: {e}"
            );
        }
        let path = dir.path().join("bom8.json");
        std::fs::write(&path, [&[0xEF, 0xBB, 0xBF][..], text.as_bytes()].concat()).unwrap();
        assert_eq!(read_input(&path).unwrap().0, text, "UTF-8 with a mark");
    }

    /// A file above the parallel threshold, and not a whole number of parts long, is read in
    /// parallel to exactly its bytes; text that is not UTF-8 is named with its byte.
    #[test]
    fn eight_bit_names_in_cad_files_are_read_as_question_marks() {
        let dir = tempfile::tempdir().unwrap();
        // a Latin-1 name (0xFC), a truncated UTF-8 character at the end, and a valid 'é'
        let bytes = b"#1=CARTESIAN_POINT('M\xfcller \xc3\xa9',(0.,0.,0.));\n\xe2\x82";
        for ext in ["step", "STP", "igs"] {
            let path = dir.path().join(format!("latin1.{ext}"));
            std::fs::write(&path, bytes).unwrap();
            let (text, _) = read_input(&path).unwrap();
            assert_eq!(text.len(), bytes.len(), "one byte for one");
            assert!(
                text.starts_with("#1=CARTESIAN_POINT('M?ller é',") && text.ends_with("\n??"),
                "{text}"
            );
        }
        let path = dir.path().join("latin1.csv");
        std::fs::write(&path, bytes).unwrap();
        let e = read_input(&path).unwrap_err().to_string();
        assert!(
            e.contains("not UTF-8 text at line 1, column 22 (byte 21)"),
            "{e}"
        );
        // after a newline and a two-byte character: the line, and the column in characters
        std::fs::write(&path, b"x,y\n\xc3\xa9,\xff\n").unwrap();
        let e = read_input(&path).unwrap_err().to_string();
        assert!(e.contains("at line 2, column 3 (byte 7)"), "{e}");
    }

    #[test]
    fn large_files_are_read_whole_in_parallel() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.csv");
        let len = PARALLEL_READ_MIN + READ_PART / 3 + 7;
        let mut bytes: Vec<u8> = (0..len).map(|i| b"0123456789,\n"[i % 12]).collect();
        std::fs::write(&path, &bytes).unwrap();
        let (read, name) = read_input_bytes(&path).unwrap();
        assert_eq!(name, path.display().to_string());
        assert!(read == bytes, "the bytes read are the file's");
        let at = len - READ_PART / 2;
        bytes[at] = 0xfe;
        std::fs::write(&path, &bytes).unwrap();
        let e = read_input(&path).unwrap_err();
        // every line of the pattern is 12 bytes long, ending in its `\n`
        let (line, column) = (at / 12 + 1, at % 12 + 1);
        let want = format!("not UTF-8 text at line {line}, column {column} (byte {at})");
        assert!(e.to_string().contains(&want), "{e}");
    }
}
