//! Writing output files: a regular file is written to `NAME.partial` and renamed, so a failed
//! or interrupted write never leaves a half-written file under the real name.

use std::path::{Path, PathBuf};

/// The temporary name `path` is written under before the rename.
pub fn partial(path: &Path) -> PathBuf {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    PathBuf::from(tmp)
}

/// Writes `contents` to `path` through a temporary file, so no partial file is ever left.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let tmp = partial(path);
    if let Err(e) = std::fs::write(&tmp, contents) {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path)
}
