//! Files for tests that read or write them: one fresh directory per test.

use std::path::{Path, PathBuf};

/// A fresh, empty directory `<system temp>/steradian-test-<process id>-<name>` (emptied if a
/// previous run left it). The tests of one test binary run as threads of one process, so each
/// test passes a `name` of its own.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("steradian-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// Writes `contents` to `dir/name` and returns that path.
pub fn write_file(dir: &Path, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    path
}
