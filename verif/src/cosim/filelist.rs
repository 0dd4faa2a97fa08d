//! File lists: [`FileList`], read by texrtl for both simulators alike.

use super::library::push_once;
use super::Library;
use std::path::{Path, PathBuf};
use waves::output::shorten;

/// Where a relative path in a file list is taken from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathsFrom {
    /// The current folder (a list read as `-f`).
    Cwd,
    /// The list's own folder (a list read as `-F`).
    List,
}

/// A file list (a `.f` file), as an RTL team keeps one for every tool: the sources of a build,
/// one or more to a line, with `+incdir+DIR`, `+define+NAME[=VALUE]` (several joined by `+`),
/// `-I DIR`, `-D NAME[=VALUE]`, module libraries ([`Library`]: `-y DIR`, `+libdir+DIR`,
/// `-v FILE`, `+libext+EXT[+EXT]`) and nested lists (`-f LIST`, `-F LIST`). Comments are `//` to
/// the end of the line, `/* ... */` and lines starting with `#`; `$VAR`, `${VAR}` and
/// `$(VAR)` are taken from the environment.
///
/// texrtl reads the list itself and gives both simulators the same sources, folders and
/// macros, so a run's cache key and its `` `include `` scan see every file. A relative path
/// is taken from the current folder in a list read as `-f` (Verilator's and Icarus' rule),
/// from the list's own folder in one read as `-F`. Anything else a list may hold for one tool
/// (a tool's options) is refused by name.
///
/// What a list gives a build, its nested lists included: paths absolute, each source and
/// library file an existing file and each include and library folder an existing folder.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FileList {
    /// The Verilog sources, in the list's order, each file once.
    pub sources: Vec<PathBuf>,
    /// Folders searched for `` `include `` files.
    pub include_dirs: Vec<PathBuf>,
    /// Macros: `NAME` or `NAME=VALUE`.
    pub defines: Vec<String>,
    /// Where modules the sources do not define are looked for.
    pub library: Library,
}

/// The largest list read (a list of sources, not a source).
const MAX_BYTES: u64 = 1 << 20;
/// Lists nested deeper than this are refused, and more than `MAX_LISTS` read in all.
const MAX_DEPTH: usize = 16;
const MAX_LISTS: usize = 256;

impl FileList {
    /// Reads the list at `path`, its nested lists with it. An error names the list, the line
    /// and what is wrong on it.
    pub fn read(path: &Path, from: PathsFrom) -> Result<FileList, String> {
        let mut r = Reader {
            list: FileList::default(),
            open: Vec::new(),
            read: 0,
            real: Vec::new(),
        };
        r.read(path, from)?;
        Ok(r.list)
    }
}

struct Reader {
    list: FileList,
    /// The lists being read, outermost first (a list met again among them is a cycle).
    open: Vec<PathBuf>,
    read: usize,
    /// The sources' real paths (a source named twice, by two spellings, is compiled once).
    real: Vec<PathBuf>,
}

impl Reader {
    fn read(&mut self, path: &Path, from: PathsFrom) -> Result<(), String> {
        let shown = path.display();
        let meta = std::fs::metadata(path).map_err(|_| format!("{shown}: no such file list"))?;
        if !meta.is_file() {
            return Err(format!("{shown}: not a file list (not a regular file)"));
        }
        if meta.len() > MAX_BYTES {
            return Err(format!(
                "{shown}: {} bytes; a file list holds at most {MAX_BYTES}",
                meta.len()
            ));
        }
        let real = path.canonicalize().map_err(|e| format!("{shown}: {e}"))?;
        if self.open.contains(&real) {
            return Err(format!("{shown}: the list includes itself"));
        }
        if self.open.len() >= MAX_DEPTH || self.read >= MAX_LISTS {
            return Err(format!(
                "{shown}: lists nested more than {MAX_DEPTH} deep or more than {MAX_LISTS} in all"
            ));
        }
        let text = std::fs::read_to_string(path)
            .map_err(|_| format!("{shown}: not a file list (not UTF-8 text)"))?;
        let base = match from {
            PathsFrom::Cwd => None,
            PathsFrom::List => real.parent().map(Path::to_path_buf),
        };
        self.read += 1;
        self.open.push(real);
        let done = self.entries(&text, base.as_deref());
        self.open.pop();
        done.map_err(|(line, e)| format!("{shown}:{line}: {e}"))
    }

    /// Every entry of one list's text; an error with its line.
    fn entries(&mut self, text: &str, base: Option<&Path>) -> Result<(), (usize, String)> {
        let words = words(text)?;
        let mut k = 0;
        while k < words.len() {
            let (line, word) = &words[k];
            let at = |e: String| (*line, e);
            let word = expand(word).map_err(at)?;
            let mut operand = || {
                k += 1;
                match words.get(k) {
                    Some((_, w)) => expand(w).map_err(at),
                    None => Err(at(format!("{word} needs its operand"))),
                }
            };
            match word.as_str() {
                "-f" | "-F" => {
                    let from = if word == "-f" {
                        PathsFrom::Cwd
                    } else {
                        PathsFrom::List
                    };
                    let nested = resolve(base, &operand()?);
                    self.read(&nested, from).map_err(at)?;
                }
                "-I" => self.include_dir(base, &operand()?).map_err(at)?,
                "-y" => self.library_dir(base, &operand()?).map_err(at)?,
                "-v" => self.library_file(base, &operand()?).map_err(at)?,
                "-D" => self.define(&operand()?).map_err(at)?,
                _ => self.entry(base, &word).map_err(at)?,
            }
            k += 1;
        }
        Ok(())
    }

    /// One entry that is a word alone: `+incdir+`, `+define+`, `+libdir+`, `+libext+`,
    /// `-IDIR`, `-DNAME` or a source.
    fn entry(&mut self, base: Option<&Path>, word: &str) -> Result<(), String> {
        if let Some(dirs) = word.strip_prefix("+incdir+") {
            for d in dirs.split('+').filter(|d| !d.is_empty()) {
                self.include_dir(base, d)?;
            }
        } else if let Some(defs) = word.strip_prefix("+define+") {
            for m in defs.split('+').filter(|m| !m.is_empty()) {
                self.define(m)?;
            }
        } else if let Some(d) = word.strip_prefix("-I") {
            self.include_dir(base, d)?;
        } else if let Some(m) = word.strip_prefix("-D") {
            self.define(m)?;
        } else if let Some(dirs) = word.strip_prefix("+libdir+") {
            for d in dirs.split('+').filter(|d| !d.is_empty()) {
                self.library_dir(base, d)?;
            }
        } else if let Some(exts) = word.strip_prefix("+libext+") {
            for e in exts.split('+').filter(|e| !e.is_empty()) {
                self.library_ext(e)?;
            }
        } else if word.starts_with(['-', '+']) {
            return Err(format!(
                "{}: not read (a file list here holds sources, +incdir+, +define+, -I, -D, -y, -v, +libdir+, +libext+, -f and -F)",
                shorten(word)
            ));
        } else {
            let s = resolve(base, word);
            if !s.is_file() {
                return Err(format!("{}: no such Verilog file", shown(&s, word)));
            }
            let real = s
                .canonicalize()
                .map_err(|e| format!("{}: {e}", s.display()))?;
            if !self.real.contains(&real) {
                self.real.push(real);
                self.list.sources.push(s);
            }
        }
        Ok(())
    }

    fn include_dir(&mut self, base: Option<&Path>, word: &str) -> Result<(), String> {
        let d = existing(base, word, Path::is_dir, "include folder", "folder")?;
        push_once(&mut self.list.include_dirs, d);
        Ok(())
    }

    fn library_dir(&mut self, base: Option<&Path>, word: &str) -> Result<(), String> {
        let d = existing(base, word, Path::is_dir, "library folder", "folder")?;
        push_once(&mut self.list.library.dirs, d);
        Ok(())
    }

    fn library_file(&mut self, base: Option<&Path>, word: &str) -> Result<(), String> {
        let f = existing(base, word, Path::is_file, "library file", "Verilog file")?;
        push_once(&mut self.list.library.files, f);
        Ok(())
    }

    /// An extension as Verilator appends it to a module's name: `.v`, `.sv`, `_cell.v`.
    fn library_ext(&mut self, e: &str) -> Result<(), String> {
        let ok = |c: char| c.is_ascii_alphanumeric() || "._-".contains(c);
        if !e.chars().all(ok) {
            return Err(format!("+libext+{}: not a file name ending", shorten(e)));
        }
        push_once(&mut self.list.library.exts, e.to_string());
        Ok(())
    }

    fn define(&mut self, m: &str) -> Result<(), String> {
        if !super::is_define(m) {
            let m = shorten(m);
            return Err(format!("define '{m}': not NAME or NAME=VALUE"));
        }
        self.list.defines.push(m.to_string());
        Ok(())
    }
}

/// Where `word` leads from `base`, when it is what `is` asks (else "`what` PATH: no such
/// `kind`").
fn existing(
    base: Option<&Path>,
    word: &str,
    is: fn(&Path) -> bool,
    what: &str,
    kind: &str,
) -> Result<PathBuf, String> {
    let p = resolve(base, word);
    if is(&p) {
        return Ok(p);
    }
    Err(format!("{what} {}: no such {kind}", shown(&p, word)))
}

/// A path for a message: where `word` led, or the word itself shortened when it is long or
/// holds control characters (a damaged list).
fn shown(resolved: &Path, word: &str) -> String {
    if shorten(word) == word {
        resolved.display().to_string()
    } else {
        shorten(word)
    }
}

/// `p` absolute: from `base` when given and `p` is relative, else from the current folder.
fn resolve(base: Option<&Path>, p: &str) -> PathBuf {
    let p = match base {
        Some(b) if Path::new(p).is_relative() => b.join(p),
        _ => PathBuf::from(p),
    };
    std::path::absolute(&p).unwrap_or(p)
}

/// The list's words with their lines, comments left out. A double-quoted stretch (a macro's
/// string value) is part of its word, spaces and all.
fn words(text: &str) -> Result<Vec<(usize, String)>, (usize, String)> {
    let mut out = Vec::new();
    for (k, line) in uncommented(text)?.lines().enumerate() {
        if line.trim_start().starts_with('#') {
            continue;
        }
        let (mut word, mut quoted) = (String::new(), false);
        for c in line.chars() {
            if c.is_whitespace() && !quoted {
                if !word.is_empty() {
                    out.push((k + 1, std::mem::take(&mut word)));
                }
                continue;
            }
            quoted ^= c == '"';
            word.push(c);
        }
        if quoted {
            return Err((k + 1, "a \" string is not closed on its line".into()));
        }
        if !word.is_empty() {
            out.push((k + 1, word));
        }
    }
    Ok(out)
}

/// `text` with its `//` and `/* */` comments made spaces (their line breaks kept, so lines
/// keep their numbers).
fn uncommented(text: &str) -> Result<String, (usize, String)> {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut line = 1;
    while let Some(c) = chars.next() {
        match (c, chars.peek()) {
            ('/', Some('/')) => while chars.next_if(|&c| c != '\n').is_some() {},
            ('/', Some('*')) => {
                chars.next();
                let (open, mut last) = (line, ' ');
                loop {
                    match chars.next() {
                        Some('/') if last == '*' => break,
                        Some(c) => {
                            if c == '\n' {
                                line += 1;
                                out.push('\n');
                            }
                            last = c;
                        }
                        None => return Err((open, "a /* comment is not closed".into())),
                    }
                }
                out.push(' ');
            }
            _ => {
                line += usize::from(c == '\n');
                out.push(c);
            }
        }
    }
    Ok(out)
}

/// `w` with `$VAR`, `${VAR}` and `$(VAR)` replaced by the environment's values; a variable
/// not set is an error. A `$` not followed by a name is kept.
fn expand(w: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = w;
    while let Some(k) = rest.find('$') {
        out.push_str(&rest[..k]);
        let after = &rest[k + 1..];
        let (name, len) = match after.chars().next() {
            Some(open @ ('{' | '(')) => {
                let close = if open == '{' { '}' } else { ')' };
                match after.find(close) {
                    Some(e) => (&after[1..e], e + 1),
                    None => return Err(format!("{}: the ${open} is not closed", shorten(w))),
                }
            }
            _ => {
                let e = after
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(after.len());
                (&after[..e], e)
            }
        };
        if name.is_empty() {
            out.push('$');
            rest = after;
            continue;
        }
        let v = std::env::var(name).map_err(|_| {
            let name = shorten(name);
            format!("{}: the environment variable {name} is not set", shorten(w))
        })?;
        out.push_str(&v);
        rest = &after[len..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn write(p: &Path, text: &str) {
        fs::create_dir_all(p.parent().unwrap()).unwrap();
        fs::write(p, text).unwrap();
    }

    /// A project's lists as RTL teams write them: comments of three kinds, several entries a
    /// line, `+`-joined folders and macros, `-I`/`-D` with and without a space, a nested list
    /// relative to itself, environment variables in each of their three spellings (cargo's
    /// own, set for every test), a source named twice by two spellings.
    #[test]
    fn a_list_gives_its_sources_folders_and_macros_in_order() {
        let t = tempfile::tempdir().unwrap();
        let r = t.path().canonicalize().unwrap();
        for f in ["rtl/a.v", "rtl/b.sv", "rtl/sub/c.v"] {
            write(&r.join(f), "");
        }
        for d in ["inc", "rtl/sub/inc", "lib", "rtl/sub/lib"] {
            fs::create_dir_all(r.join(d)).unwrap();
        }
        let top = r.join("rtl/top.f");
        write(
            &top,
            "# the unit\n+incdir+../inc  // shared headers\na.v b.sv /* two\n lines */\n\
             +define+A=1+B -D C=\"x y\" -DD\n-F sub/sub.f\n-I ${CARGO_MANIFEST_DIR}/src\n\
             $(CARGO_MANIFEST_DIR)/Cargo.toml $CARGO_MANIFEST_DIR/Cargo.toml\n",
        );
        write(
            &r.join("rtl/sub/sub.f"),
            "c.v -Iinc ../a.v\n-y lib +libdir+../../lib -v c.v +libext+.v+_cell.sv\n-y lib\n",
        );
        let l = FileList::read(&top, PathsFrom::List).unwrap();
        let p = |s: &str| r.join(s);
        let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
        let sources = [p("rtl/a.v"), p("rtl/b.sv"), p("rtl/sub/c.v")];
        let sources = [&sources[..], &[crate_dir.join("Cargo.toml")]].concat();
        assert_eq!(l.sources, sources, "each file once, in order");
        let dirs = [p("rtl/../inc"), p("rtl/sub/inc"), crate_dir.join("src")];
        assert_eq!(l.include_dirs, dirs);
        assert_eq!(l.defines, ["A=1", "B", "C=\"x y\"", "D"]);
        let library = Library {
            dirs: vec![p("rtl/sub/lib"), p("rtl/sub/../../lib")],
            files: vec![p("rtl/sub/c.v")],
            exts: vec![".v".into(), "_cell.sv".into()],
        };
        assert_eq!(l.library, library, "each folder once");
    }

    /// Read as `-f`, a relative path is the current folder's (the crate's, under `cargo test`).
    #[test]
    fn a_cwd_list_takes_relative_paths_from_the_current_folder() {
        let t = tempfile::tempdir().unwrap();
        let list = t.path().join("x.f");
        write(&list, "Cargo.toml\n");
        let l = FileList::read(&list, PathsFrom::Cwd).unwrap();
        let here = std::env::current_dir().unwrap().join("Cargo.toml");
        assert_eq!(l.sources, [here]);
        let e = FileList::read(&list, PathsFrom::List).unwrap_err();
        assert!(
            e.contains("x.f:1: ") && e.ends_with("Cargo.toml: no such Verilog file"),
            "{e}"
        );
    }

    /// Every refusal names the list and the line, and what is wrong there.
    #[test]
    fn a_bad_entry_is_refused_with_its_list_and_line() {
        let t = tempfile::tempdir().unwrap();
        let r = t.path();
        write(&r.join("a.v"), "");
        let refused = |text: &str, why: &str, line: usize| {
            let f = r.join("bad.f");
            write(&f, text);
            let e = FileList::read(&f, PathsFrom::List).unwrap_err();
            let at = format!("bad.f:{line}: ");
            assert!(e.contains(&at) && e.contains(why), "{text:?}: {e}");
        };
        refused(
            "a.v\n+libext+.v/x\n",
            "+libext+.v/x: not a file name ending",
            2,
        );
        refused("-y lib\n", "library folder", 1);
        refused("+libdir+a.v\n", "library folder", 1);
        refused("-v cells.v\n", "library file", 1);
        refused("-y\n", "-y needs its operand", 1);
        refused("a.v --timing\n", "--timing: not read", 1);
        refused("\n\nmissing.v\n", "missing.v: no such Verilog file", 3);
        refused("+incdir+nowhere\n", "include folder", 1);
        refused("+define+3x\n", "define '3x'", 1);
        refused("-D\n", "-D needs its operand", 1);
        refused(
            "$TEXRTL_FL_NEVER_SET/a.v\n",
            "TEXRTL_FL_NEVER_SET is not set",
            1,
        );
        refused("${X\n", "is not closed", 1);
        refused("a.v /* open\n\n", "comment is not closed", 1);
        refused("+define+S=\"open\n", "string is not closed", 1);
        refused("a.v\n-F bad.f\n", "bad.f: the list includes itself", 2);
        refused("-f nothing.f\n", "nothing.f: no such file list", 1);
        let binary = r.join("bin.f");
        fs::write(&binary, [0xff, 0xfe, 0]).unwrap();
        let e = FileList::read(&binary, PathsFrom::List).unwrap_err();
        assert!(e.ends_with("not UTF-8 text)"), "{e}");
        // Too big: refused from its size, before it is read.
        let big = fs::File::create(r.join("big.f")).unwrap();
        big.set_len(MAX_BYTES + 1).unwrap();
        let e = FileList::read(&r.join("big.f"), PathsFrom::List).unwrap_err();
        assert!(e.contains("bytes; a file list holds at most"), "{e}");
    }
}
