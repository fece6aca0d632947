//! Writing outputs: where an output path leads, and writing there completely or not at all (the output rules of
//! README.md#exit-status-and-output-files).
//!
//! - `-` is standard output; so is a path that is the very file or pipe standard output already writes to (a shell's
//!   `--csv /dev/stdout`), so that nothing else is printed into it.
//! - A path that exists and is not a regular file (a device, a FIFO) is written in place: opened for writing, never
//!   replaced and never truncated.
//! - A symbolic link is followed: the file it points to receives the output, the link stays a link.
//! - A regular file is written to a temporary file beside it, then renamed over it: it is complete or absent. A
//!   temporary is removed on every error (its guard's `Drop`) and on Ctrl-C or SIGTERM: live temporaries are listed
//!   in a process-wide registry that the handler of [`remove_temporaries_on_signal`] empties before exiting.
//!
//! [`Identity`] tells whether two paths name one file, so that the command line can refuse, before any work, an
//! output that would replace an input or another output.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::os::fd::AsFd;
use std::os::unix::fs::{FileTypeExt, MetadataExt};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Why an output cannot be written (an I/O failure, exit status 1).
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    #[error("cannot write {path}")]
    Write {
        path: String,
        #[source]
        source: io::Error,
    },
    #[error("cannot create the folder {path}")]
    Folder {
        path: String,
        #[source]
        source: io::Error,
    },
    #[error("cannot write {path}: it is a folder")]
    IsFolder { path: String },
}

/// Which file a path names, symbolic links followed: for telling whether two paths name one file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Identity {
    StandardOutput,
    File {
        /// Absolute, with every symbolic link and `..` resolved as far as the path exists; the part that does not
        /// exist yet is kept as written.
        path: PathBuf,
        /// Device and inode, when the file exists: catches hard links, and bind mounts that paths alone miss.
        node: Option<(u64, u64)>,
    },
}

impl Identity {
    /// The identity of an existing or future file (`-` is not special here: inputs read no standard input).
    pub fn of(path: &Path) -> Identity {
        let node = fs::metadata(path).ok().map(|meta| (meta.dev(), meta.ino()));
        Identity::File { path: resolved(path, 0), node }
    }

    /// Whether both name the same file (or both standard output).
    pub fn same_as(&self, other: &Identity) -> bool {
        match (self, other) {
            (Identity::StandardOutput, Identity::StandardOutput) => true,
            (Identity::File { path: a, node: m }, Identity::File { path: b, node: n }) => {
                a == b || (m.is_some() && m == n)
            }
            _ => false,
        }
    }

    /// Whether `self` lies in a folder that `other` names (so one of them could not be written as a file).
    pub fn is_inside(&self, other: &Identity) -> bool {
        match (self, other) {
            (Identity::File { path: inner, .. }, Identity::File { path: outer, .. }) => {
                inner != outer && inner.starts_with(outer)
            }
            _ => false,
        }
    }
}

/// `path` made absolute with the symbolic links and `..` of its existing part resolved (a dangling link is followed
/// to the file it will create); what does not exist yet is kept as written, `.` and `..` applied to it.
fn resolved(path: &Path, depth: usize) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    if let Ok(canonical) = fs::canonicalize(&absolute) {
        return canonical;
    }
    let mut done = PathBuf::new();
    let mut missing = false;
    for component in absolute.components() {
        match component {
            Component::CurDir => {}
            // On the resolved (link-free) part, and on the part that does not exist, `..` is the parent as written.
            Component::ParentDir => {
                done.pop();
            }
            Component::Normal(name) if !missing => {
                done.push(name);
                if let Ok(canonical) = fs::canonicalize(&done) {
                    done = canonical;
                } else {
                    // A link to a file that does not exist yet is followed (40 links, as the kernel allows).
                    if let Ok(target) = fs::read_link(&done)
                        && depth < 40
                    {
                        done.pop();
                        done = resolved(&done.join(target), depth + 1);
                    }
                    missing = true;
                }
            }
            other => done.push(other),
        }
    }
    done
}

/// Device and inode of standard output when it is a regular file or a pipe (not a terminal or `/dev/null`, which
/// many outputs may share harmlessly).
fn standard_output_node() -> Option<(u64, u64)> {
    let handle = io::stdout().as_fd().try_clone_to_owned().ok()?;
    let meta = File::from(handle).metadata().ok()?;
    let kind = meta.file_type();
    (kind.is_file() || kind.is_fifo() || kind.is_socket()).then(|| (meta.dev(), meta.ino()))
}

/// How an output is written.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Kind {
    StandardOutput,
    /// An existing file that is not a regular file (a device, a FIFO): opened and written in place.
    InPlace(PathBuf),
    /// A regular file, existing or not, at this resolved path: written through a temporary file beside it.
    Regular(PathBuf),
}

/// Where one output goes, decided before any work ([`Destination::resolve`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Destination {
    /// The path as given, for messages.
    shown: String,
    kind: Kind,
    identity: Identity,
}

impl Destination {
    /// Resolves an output path by the rules of this module. An existing folder is an error (a file cannot replace
    /// it), as is a path that cannot be examined (a parent that is a file, a folder that may not be read).
    pub fn resolve(path: &Path) -> Result<Destination, FileError> {
        if path.as_os_str() == "-" {
            return Ok(Destination::standard_output());
        }
        let shown = path.display().to_string();
        let meta = match fs::metadata(path) {
            Ok(meta) => meta,
            Err(error) if error.kind() == io::ErrorKind::NotFound => {
                let target = resolved(path, 0);
                let identity = Identity::File { path: target.clone(), node: None };
                return Ok(Destination { shown, kind: Kind::Regular(target), identity });
            }
            Err(source) => return Err(FileError::Write { path: shown, source }),
        };
        if meta.is_dir() {
            return Err(FileError::IsFolder { path: shown });
        }
        let node = (meta.dev(), meta.ino());
        if standard_output_node() == Some(node) {
            return Ok(Destination::standard_output());
        }
        let target = resolved(path, 0);
        let identity = Identity::File { path: target.clone(), node: Some(node) };
        let kind = if meta.is_file() { Kind::Regular(target) } else { Kind::InPlace(path.to_path_buf()) };
        Ok(Destination { shown, kind, identity })
    }

    /// Standard output (`-`).
    pub fn standard_output() -> Destination {
        Destination { shown: "standard output".into(), kind: Kind::StandardOutput, identity: Identity::StandardOutput }
    }

    pub fn identity(&self) -> &Identity {
        &self.identity
    }

    pub fn is_standard_output(&self) -> bool {
        self.kind == Kind::StandardOutput
    }

    /// The path as given, or "standard output".
    pub fn shown(&self) -> &str {
        &self.shown
    }
}

/// One live temporary file or folder (see the module's comment).
struct Live {
    id: u64,
    path: PathBuf,
    folder: bool,
}

static LIVE: Mutex<Vec<Live>> = Mutex::new(Vec::new());
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// The registry; a panic elsewhere while it was held leaves it usable (it is a plain list).
fn live() -> MutexGuard<'static, Vec<Live>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

fn remove(path: &Path, folder: bool) {
    let _ = if folder { fs::remove_dir_all(path) } else { fs::remove_file(path) };
}

/// A temporary file or folder, registered while it lives: removed when dropped, unless renamed into place.
struct Temporary {
    id: u64,
    path: PathBuf,
    folder: bool,
    /// Renamed into place: nothing to remove.
    kept: bool,
}

impl Temporary {
    /// A new empty file `.NAME.partial-PID-N` in `folder`, for the target file NAME.
    fn file(folder: &Path, name: &str) -> io::Result<(Temporary, File)> {
        // Created under the registry's lock: the signal handler, which holds it until the process exits, then never
        // misses a temporary created while it cleans up.
        let mut registry = live();
        let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        // A short stem keeps the name within the file system's 255 bytes whatever the target's length.
        let stem: String = name.chars().take(64).collect();
        let path = folder.join(format!(".{stem}.partial-{}-{id}", std::process::id()));
        let file = OpenOptions::new().write(true).create_new(true).open(&path)?;
        registry.push(Live { id, path: path.clone(), folder: false });
        Ok((Temporary { id, path, folder: false, kept: false }, file))
    }

    /// A new empty folder `.impact-partial-PID-N` in `folder`.
    fn folder(folder: &Path) -> io::Result<Temporary> {
        let mut registry = live();
        let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        let path = folder.join(format!(".impact-partial-{}-{id}", std::process::id()));
        fs::create_dir(&path)?;
        registry.push(Live { id, path: path.clone(), folder: true });
        Ok(Temporary { id, path, folder: true, kept: false })
    }

    /// Renames the file onto `target` and forgets it.
    fn rename_onto(mut self, target: &Path) -> io::Result<()> {
        let registry = live();
        fs::rename(&self.path, target)?;
        self.kept = true;
        // Dropping `self` unregisters it, and needs the lock.
        drop(registry);
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        let mut registry = live();
        if !self.kept {
            remove(&self.path, self.folder);
        }
        registry.retain(|entry| entry.id != self.id);
    }
}

/// Installs a handler for SIGINT (Ctrl-C) and SIGTERM that removes every live temporary file and folder, then exits
/// with status 128 + the signal's number (130 for Ctrl-C), as a shell reports a command a signal ended.
pub fn remove_temporaries_on_signal() -> io::Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
    std::thread::Builder::new().name("signals".into()).spawn(move || {
        if let Some(signal) = signals.forever().next() {
            // Held until the process ends: no temporary can be created or renamed into place after the clean-up.
            let registry = live();
            for entry in registry.iter() {
                remove(&entry.path, entry.folder);
            }
            eprintln!("\nimpact: interrupted; unfinished outputs removed");
            std::process::exit(128 + signal);
        }
    })?;
    Ok(())
}

/// Bytes gathered before each write to a regular file: a sweep writes hundreds of megabytes, which 8 kB at a time
/// (the standard library's default) take tens of thousands of system calls.
const WRITE_BUFFER: usize = 1 << 20;

enum Sink {
    StandardOutput(BufWriter<io::Stdout>),
    InPlace(BufWriter<File>),
    /// The writer is declared before the temporary so that it is closed before the temporary is removed.
    Temporary {
        writer: BufWriter<File>,
        temporary: Temporary,
        target: PathBuf,
    },
}

/// An output being written, a stream of bytes at a time. [`OutputFile::finish`] completes it; dropped unfinished, a
/// regular file's temporary is removed and the target is left as it was. (Standard output and files written in
/// place receive the bytes as they come: a reader of a pipe cannot be spared a partial stream.)
pub struct OutputFile {
    shown: String,
    sink: Sink,
}

impl OutputFile {
    /// Opens the output: standard output, the existing device or FIFO (which may wait for a reader), or a new
    /// temporary file beside the regular target (creating its folder).
    pub fn create(destination: &Destination) -> Result<OutputFile, FileError> {
        let shown = destination.shown.clone();
        let failed = |source| FileError::Write { path: destination.shown.clone(), source };
        let sink = match &destination.kind {
            Kind::StandardOutput => Sink::StandardOutput(BufWriter::new(io::stdout())),
            // (A pipe or a device keeps the standard buffer, as standard output does: a reader of a named pipe follows
            // the rows as they come.)
            Kind::InPlace(path) => {
                Sink::InPlace(BufWriter::new(OpenOptions::new().write(true).open(path).map_err(failed)?))
            }
            Kind::Regular(target) => {
                let folder = target.parent().unwrap_or(Path::new("/"));
                fs::create_dir_all(folder)
                    .map_err(|source| FileError::Folder { path: folder.display().to_string(), source })?;
                let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                let (temporary, file) = Temporary::file(folder, &name).map_err(failed)?;
                Sink::Temporary {
                    writer: BufWriter::with_capacity(WRITE_BUFFER, file),
                    temporary,
                    target: target.clone(),
                }
            }
        };
        Ok(OutputFile { shown, sink })
    }

    /// The output's path as given, or "standard output".
    pub fn shown(&self) -> &str {
        &self.shown
    }

    pub fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), FileError> {
        let written = match &mut self.sink {
            Sink::StandardOutput(writer) => writer.write_all(bytes),
            Sink::InPlace(writer) | Sink::Temporary { writer, .. } => writer.write_all(bytes),
        };
        written.map_err(|source| FileError::Write { path: self.shown.clone(), source })
    }

    /// Completes the output: flushes it, and for a regular file makes it durable and renames it into place (keeping
    /// the permissions of the file it replaces).
    pub fn finish(self) -> Result<(), FileError> {
        let shown = self.shown;
        let failed = |source| FileError::Write { path: shown.clone(), source };
        match self.sink {
            Sink::StandardOutput(mut writer) => writer.flush().map_err(failed),
            Sink::InPlace(mut writer) => writer.flush().map_err(failed),
            Sink::Temporary { writer, temporary, target } => {
                let file = writer.into_inner().map_err(|error| failed(error.into_error()))?;
                file.sync_all().map_err(failed)?;
                if let Ok(meta) = fs::metadata(&target) {
                    let _ = fs::set_permissions(&temporary.path, meta.permissions());
                }
                drop(file);
                temporary.rename_onto(&target).map_err(failed)
            }
        }
    }
}

/// A hidden folder for files that a library can only write by path (the plotting backends), removed with
/// everything in it when dropped or on Ctrl-C. Its files reach their destinations through [`OutputFile`]s
/// ([`Staging::publish`]).
pub struct Staging {
    temporary: Temporary,
}

impl Staging {
    /// A new staging folder inside `folder` (created if missing).
    pub fn inside(folder: &Path) -> Result<Staging, FileError> {
        let failed = |source| FileError::Folder { path: folder.display().to_string(), source };
        fs::create_dir_all(folder).map_err(failed)?;
        Ok(Staging { temporary: Temporary::folder(folder).map_err(failed)? })
    }

    pub fn path(&self) -> &Path {
        &self.temporary.path
    }

    /// Copies the staged file `staged` to `destination`, unfinished: the caller finishes it with the run's other
    /// outputs, so that they appear together.
    pub fn publish(&self, staged: &Path, destination: &Destination) -> Result<OutputFile, FileError> {
        let bytes = fs::read(staged).map_err(|source| FileError::Write { path: destination.shown.clone(), source })?;
        let mut output = OutputFile::create(destination)?;
        output.write_bytes(&bytes)?;
        Ok(output)
    }
}

/// Writes `bytes` to `path` by the rules of this module: `-` is standard output, a device or FIFO is written in
/// place, a symbolic link is followed, and a regular file is written through a temporary file in its folder and a
/// rename, so that a reader never sees a partial file and a failure leaves any earlier file intact. Creates missing
/// folders.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let mut output = OutputFile::create(&Destination::resolve(path)?)?;
    output.write_bytes(bytes)?;
    Ok(output.finish()?)
}

/// Why `path` cannot name an output file, if it cannot: it is empty or names a folder (`out/`, `.`, `out/..`).
/// `-` (standard output) is a file name here.
pub fn file_name_problem(path: &Path) -> Option<&'static str> {
    let text = path.as_os_str().as_encoded_bytes();
    if text.is_empty() {
        return Some("the file name is empty");
    }
    // `Path` forgets a trailing `/` or `/.`, so the text is read as written.
    if text.ends_with(b"/") || text.ends_with(b"/.") || text == b"." {
        return Some("the name ends in `/` or `.`, so it names a folder: give a file name");
    }
    match path.components().next_back() {
        Some(Component::Normal(_)) => None,
        _ => Some("the name is a folder (`..` or `/`): give a file name"),
    }
}

/// Why `path` cannot name the folder that receives a run's figures, if it cannot: it is empty, `-` (several figures
/// cannot share standard output), or the name of one figure (`fig.png`), which would make a folder of that name.
pub fn figure_folder_problem(path: &Path) -> Option<&'static str> {
    if path.as_os_str().is_empty() {
        return Some("the folder name is empty");
    }
    if path.as_os_str() == "-" {
        return Some("figures cannot go to standard output: give the folder to write them into");
    }
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(extension.as_deref(), Some("png" | "svg")) {
        return Some("this takes a folder for the figures (each in PNG and SVG), not a figure's file name");
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_folders_are_not_file_names() {
        for folder in ["", "out/", ".", "out/.", "out/..", "/"] {
            assert!(file_name_problem(Path::new(folder)).is_some(), "`{folder}` names no file");
        }
        for file in ["-", "s.csv", "out/s.csv", "../s.csv", ".hidden"] {
            assert_eq!(file_name_problem(Path::new(file)), None, "`{file}` names a file");
        }
    }

    #[test]
    fn a_figure_folder_is_not_a_figure() {
        for bad in ["", "-", "fig.png", "out/Fig.SVG"] {
            assert!(figure_folder_problem(Path::new(bad)).is_some(), "`{bad}` is no folder for figures");
        }
        assert_eq!(figure_folder_problem(Path::new("out/figures")), None);
    }

    #[test]
    fn paths_to_files_not_yet_written_resolve_as_written() {
        let missing = Path::new("/no-such-folder-for-impact/a/../b/./c.csv");
        assert_eq!(resolved(missing, 0), Path::new("/no-such-folder-for-impact/b/c.csv"));
        let a = Identity::File { path: "/x/figs".into(), node: None };
        let b = Identity::File { path: "/x/figs/force_time.png".into(), node: None };
        assert!(b.is_inside(&a) && !a.is_inside(&b) && !a.is_inside(&a));
        let c = Identity::File { path: "/x/figs2".into(), node: None };
        assert!(!c.is_inside(&a), "a path component, not a string prefix");
    }
}
