//! Where relative file names in a scene are looked up: Mitsuba 3's `FileResolver`.
//!
//! A scene has one list of search folders, first match wins:
//! 1. the folders of its `<path value="..."/>` elements, the last declared first (each one is
//!    prepended, as in Mitsuba);
//! 2. the folder of the main scene file (for a scene given as a string, the loader's base
//!    folder).
//!
//! `<include filename>`s and every plugin's `filename` (meshes, textures, environment maps, MERL
//! tables) are resolved against this list, so a fragment in `parts/` that names
//! `meshes/x.obj` finds it beside the main scene, as Mitsuba finds it. An `<include>` is
//! resolved with the folders declared before it; a plugin's file with all of them (Mitsuba
//! builds its plugins after parsing the whole file).
//!
//! Where steradian differs on purpose:
//! - the working directory is not searched (Mitsuba's default resolver holds it): the same
//!   scene renders the same wherever it is started from;
//! - a name found in none of the folders is tried relative to the file that wrote it (an
//!   included fragment's own folder), which older steradian scenes rely on; where Mitsuba
//!   finds the file, this fallback is never reached, so both renderers open the same file.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

/// The search folders of one scene, in lookup order, and the files the scene has read so far.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileResolver {
    paths: Vec<PathBuf>,
    /// Files read: the scene file, its includes, each plugin's `filename` (in order, once).
    read: RefCell<Vec<PathBuf>>,
}

impl FileResolver {
    /// A resolver that searches `base` (the main scene's folder).
    pub fn new(base: &Path) -> FileResolver {
        FileResolver { paths: vec![base.to_path_buf()], read: RefCell::default() }
    }

    /// Searches `dir` before every folder added so far (`<path>`).
    pub fn prepend(&mut self, dir: PathBuf) {
        if let Some(i) = self.paths.iter().position(|p| *p == dir) {
            self.paths.remove(i);
        }
        self.paths.insert(0, dir);
    }

    /// Notes that the scene reads `file` (what [`files_read`](Self::files_read) lists).
    pub fn record(&self, file: &Path) {
        let mut read = self.read.borrow_mut();
        if !read.iter().any(|p| p == file) {
            read.push(file.to_path_buf());
        }
    }

    /// The files the scene read, in the order first read: what a scene needs to be loaded
    /// elsewhere (a distributed render ships them), and what its digest covers.
    pub fn files_read(&self) -> Vec<PathBuf> {
        self.read.borrow().iter().filter(|p| p.is_file()).cloned().collect()
    }

    /// The search folders, first match first.
    pub fn paths(&self) -> &[PathBuf] {
        &self.paths
    }

    /// The first existing `folder/file` of the search folders; else `fallback_dir/file` (the
    /// declaring file's folder), which need not exist (the caller reports a missing file with
    /// that path). Absolute names are returned as they are.
    pub fn resolve(&self, file: &str, fallback_dir: &Path) -> PathBuf {
        let p = Path::new(file);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        self.paths
            .iter()
            .map(|d| d.join(p))
            .find(|c| c.exists())
            .unwrap_or_else(|| fallback_dir.join(p))
    }
}

#[cfg(test)]
mod tests {
    use std::fs;

    use steradian::testkit::{temp_dir, write_file};

    use super::*;

    #[test]
    fn first_folder_holding_the_file_wins_and_the_fallback_is_last() {
        let root = temp_dir("file-resolver");
        let (a, b, c) = (root.join("a"), root.join("b"), root.join("c"));
        for d in [&a, &b, &c] {
            fs::create_dir_all(d).unwrap();
        }
        write_file(&a, "x.obj", "");
        write_file(&b, "x.obj", "");
        write_file(&c, "y.obj", "");
        let mut r = FileResolver::new(&a);
        assert_eq!(r.resolve("x.obj", &c), a.join("x.obj"));
        r.prepend(b.clone());
        assert_eq!(r.resolve("x.obj", &c), b.join("x.obj"), "the last <path> is searched first");
        assert_eq!(r.paths(), &[b.clone(), a.clone()]);
        r.prepend(a.clone());
        assert_eq!(r.paths(), &[a.clone(), b.clone()], "a folder is listed once");
        assert_eq!(r.resolve("y.obj", &c), c.join("y.obj"), "fallback to the declaring folder");
        assert_eq!(r.resolve("z.obj", &c), c.join("z.obj"), "missing: the fallback path");
        let abs = c.join("y.obj");
        assert_eq!(r.resolve(abs.to_str().unwrap(), &a), abs);
        fs::remove_dir_all(&root).unwrap();
    }
}
