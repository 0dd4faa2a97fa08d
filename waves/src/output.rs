//! Writing output files. A regular file (or a new one) is written to `NAME.partial` and
//! renamed into place when complete, so a failed or interrupted write never leaves a
//! half-written file under the real name. Anything else is written through: a device
//! (`/dev/null`, `/dev/full`), a pipe or a socket is opened and written as it is, and a write
//! error is reported; a symbolic link is followed, and its target is written the same way
//! (atomically when it is a regular file), so the link itself stays.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The temporary name `path` is written under before the rename.
pub fn partial(path: &Path) -> PathBuf {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    PathBuf::from(tmp)
}

/// One output file being written; see the module documentation for the two ways. An output
/// that is dropped without [`Staged::commit`] removes its partial file.
#[derive(Debug)]
pub struct Staged {
    /// The path as the user named it (messages name this one).
    path: PathBuf,
    /// Where the bytes go: `NAME.partial`, or the device/pipe/link target itself.
    write: PathBuf,
    /// The final name of an atomic write (`None` when written through).
    rename_to: Option<PathBuf>,
    committed: bool,
}

/// How a path that exists is to be written: atomically at `real`, or through.
enum Kind {
    /// Written to this temporary name, renamed into place when complete.
    Atomic(PathBuf),
    /// Written through as it is (a device, a pipe, a socket).
    Through,
}

fn kind(path: &Path) -> Kind {
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Kind::Atomic(path.to_path_buf());
    };
    if meta.file_type().is_symlink() {
        return match (std::fs::metadata(path), std::fs::canonicalize(path)) {
            (Ok(m), Ok(real)) if m.is_file() => Kind::Atomic(real),
            // A link to a device or pipe, or a dangling link (its target is created).
            _ => Kind::Through,
        };
    }
    if meta.is_file() || meta.is_dir() {
        // A folder fails at the rename with a message naming the path.
        Kind::Atomic(path.to_path_buf())
    } else {
        Kind::Through
    }
}

impl Staged {
    /// Decides how `path` is written (from what is there now); creates nothing.
    pub fn new(path: &Path) -> Staged {
        let (write, rename_to) = match kind(path) {
            Kind::Atomic(real) => (partial(&real), Some(real)),
            Kind::Through => (path.to_path_buf(), None),
        };
        Staged {
            path: path.to_path_buf(),
            write,
            rename_to,
            committed: false,
        }
    }

    /// The path as named.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The path the bytes are written to (for writers that open the file themselves).
    pub fn write_path(&self) -> &Path {
        &self.write
    }

    /// Whether the output is a regular file named as the user named it, replaced atomically
    /// (false for a device, a pipe, or any symbolic link: `/dev/stdout` redirected to a file
    /// is still `/dev/stdout`). Files that go beside an output (a `.gtkw` beside a `.vcd`) are
    /// only written beside such a file, never into `/dev` or beside a link.
    pub fn is_file(&self) -> bool {
        self.rename_to.as_deref() == Some(self.path.as_path())
    }

    /// An error naming the output as the user named it.
    pub fn err(&self, e: impl std::fmt::Display) -> io::Error {
        io::Error::other(format!("{}: {e}", self.path.display()))
    }

    /// Opens the file to write (created or truncated).
    pub fn create(&self) -> io::Result<File> {
        OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .open(&self.write)
            .map_err(|e| self.err(e))
    }

    /// Puts a completely written file in place (the rename); nothing for a written-through
    /// output.
    pub fn commit(mut self) -> io::Result<()> {
        if let Some(to) = &self.rename_to {
            std::fs::rename(&self.write, to).map_err(|e| self.err(e))?;
        }
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed && self.rename_to.is_some() {
            let _ = std::fs::remove_file(&self.write);
        }
    }
}

/// Writes `contents` to `path` as the module describes; errors name `path`.
pub fn write_output(path: &Path, contents: &[u8]) -> io::Result<()> {
    let out = Staged::new(path);
    let mut f = out.create()?;
    f.write_all(contents).map_err(|e| out.err(e))?;
    f.flush().map_err(|e| out.err(e))?;
    drop(f);
    out.commit()
}

/// `s` with every control character (a newline, a tab) written as its escape, so a message
/// quoting a value or a file name stays one line.
pub fn escape_controls(s: &str) -> String {
    s.chars()
        .flat_map(|c| {
            if c.is_control() {
                c.escape_default().collect::<Vec<_>>()
            } else {
                vec![c]
            }
        })
        .collect()
}

/// A value shown in a message, its control characters escaped and cut to at most 40
/// characters (a long option value or file name does not flood the one-line message that
/// names it, and a newline in it does not split that line).
pub fn shorten(s: &str) -> String {
    const MAX: usize = 40;
    let s = &escape_controls(s);
    if s.chars().count() <= MAX {
        s.to_string()
    } else {
        let head: String = s.chars().take(MAX - 3).collect();
        format!("{head}...")
    }
}

/// `s` with every part between two `quote` characters (what a parser quotes back: a refused
/// value, an unknown field name) shortened as [`shorten`] does.
pub fn shorten_quoted(s: &str, quote: char) -> String {
    let q = quote.to_string();
    s.split(quote)
        .enumerate()
        .map(|(k, part)| {
            if k % 2 == 1 {
                shorten(part)
            } else {
                part.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(&q)
}

/// A message of at most about `max` characters: a longer one keeps its head and its tail (a
/// parser's position, "at line 1 column 232") with `...` between, however it quotes what it
/// refuses.
pub fn shorten_message(s: &str, max: usize) -> String {
    let n = s.chars().count();
    if n <= max {
        return s.to_string();
    }
    let tail = max / 3;
    let head: String = s.chars().take(max - tail - 5).collect();
    let end: String = s.chars().skip(n - tail).collect();
    format!("{head} ... {end}")
}

/// An I/O error's reason as a person reads it: "Permission denied", without the
/// "(os error 13)" the standard library adds.
pub fn io_reason(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error ") {
        Some(i) => s[..i].to_string(),
        None => s,
    }
}

/// The bytes of `path`, at most `max`: a longer file or an endless device is refused, naming it.
pub fn read_bounded(path: &std::path::Path, max: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let name = || path.display();
    let f = std::fs::File::open(path).map_err(|e| format!("{}: {}", name(), io_reason(&e)))?;
    let mut b = Vec::new();
    f.take(max + 1)
        .read_to_end(&mut b)
        .map_err(|e| format!("{}: {}", name(), io_reason(&e)))?;
    if b.len() as u64 > max {
        return Err(format!(
            "{}: longer than {max} bytes, more than any input of its kind",
            name()
        ));
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_io_reason_drops_the_os_error_number() {
        let e = std::io::Error::from_raw_os_error(13);
        assert_eq!(io_reason(&e), "Permission denied");
        assert_eq!(io_reason(&std::io::Error::other("plain")), "plain");
        let e = read_bounded(std::path::Path::new("/no/such/input.pgm"), 10).unwrap_err();
        assert_eq!(e, "/no/such/input.pgm: No such file or directory");
    }

    #[test]
    fn quoted_parts_are_shortened_and_the_rest_kept() {
        let long = "x".repeat(300);
        let m = shorten_quoted(&format!("unknown field `{long}`, expected `drf`"), '`');
        assert_eq!(
            m,
            format!("unknown field `{}...`, expected `drf`", "x".repeat(37))
        );
        assert_eq!(shorten_quoted("no quotes at all", '`'), "no quotes at all");
        // A quote inside the quoted value: the message is bounded all the same.
        let odd = format!("unknown field `a`{long}`, expected `drf` at line 1 column 232");
        let m = shorten_message(&shorten_quoted(&odd, '`'), 200);
        assert!(
            m.chars().count() <= 200 && m.ends_with("at line 1 column 232"),
            "{m}"
        );
        assert_eq!(shorten_message("short", 200), "short");
        assert_eq!(shorten("a\nb"), "a\\nb");
    }

    /// A scratch folder, removed when the test ends.
    fn dir(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("texrtl-output-{name}-"))
            .tempdir()
            .unwrap()
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_regular_file_is_replaced_and_no_partial_is_left() {
        let d = dir("regular");
        let p = d.path().join("o.csv");
        std::fs::write(&p, "old").unwrap();
        write_output(&p, b"new").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
        assert_eq!(names(d.path()), ["o.csv"]);
    }

    #[test]
    fn an_uncommitted_output_leaves_nothing() {
        let d = dir("uncommitted");
        let out = Staged::new(&d.path().join("o.csv"));
        out.create().unwrap().write_all(b"half").unwrap();
        drop(out);
        assert!(names(d.path()).is_empty());
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_is_written_through_and_stays_a_link() {
        let d = dir("symlink");
        let target = d.path().join("target.csv");
        std::fs::write(&target, "old").unwrap();
        let link = d.path().join("link.csv");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_output(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert_eq!(names(d.path()), ["link.csv", "target.csv"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_symlink_creates_its_target() {
        let d = dir("dangling");
        let link = d.path().join("link.csv");
        std::os::unix::fs::symlink(d.path().join("t.csv"), &link).unwrap();
        write_output(&link, b"x").unwrap();
        assert_eq!(std::fs::read(d.path().join("t.csv")).unwrap(), b"x");
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn devices_are_written_through_and_their_errors_reported() {
        use std::os::unix::fs::FileTypeExt;
        let null = Path::new("/dev/null");
        assert!(!Staged::new(null).is_file());
        write_output(null, b"bytes").unwrap();
        assert!(std::fs::metadata(null)
            .unwrap()
            .file_type()
            .is_char_device());
        let e = write_output(Path::new("/dev/full"), b"bytes").unwrap_err();
        assert!(e.to_string().starts_with("/dev/full: "), "{e}");
        assert!(!Path::new("/dev/full.partial").exists());
    }

    #[test]
    fn a_missing_folder_is_an_error_naming_the_output() {
        let d = dir("missing");
        let p = d.path().join("no").join("o.csv");
        let e = write_output(&p, b"x").unwrap_err();
        assert!(
            e.to_string().starts_with(&format!("{}: ", p.display())),
            "{e}"
        );
    }
}
