//! `--checkpoint` and `--resume`: the render's sums kept in a file while it runs.
//!
//! The driver hands the sums to [`Writer::maybe_write`] after every pass; the writer saves
//! them (atomically: `RenderSums::save`) when the interval has passed since the last write.
//! A pass of a Cornell box at 256×256 is a 4 MB file written in milliseconds, so the interval
//! bounds the work lost to a crash, not the cost.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use steradian::render::RenderSums;

/// Reads a checkpoint to resume.
pub fn read(path: &Path) -> Result<RenderSums, String> {
    let sums = RenderSums::load(path)?;
    if !sums.is_prefix() {
        return Err(format!(
            "{} holds samples {}..{} of a render, not the render from its start: it is not a checkpoint",
            path.display(),
            sums.first(),
            sums.end()
        ));
    }
    Ok(sums)
}

/// Saves the sums every `interval`.
pub struct Writer {
    path: PathBuf,
    interval: Duration,
    last: Mutex<Instant>,
    /// The first failed write, reported once at the end.
    failed: Mutex<Option<String>>,
}

impl Writer {
    pub fn new(path: &Path, interval: Duration) -> Writer {
        Writer {
            path: path.to_path_buf(),
            interval,
            last: Mutex::new(Instant::now()),
            failed: Mutex::new(None),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Saves `sums` if the interval has passed since the last save (a failure is kept and
    /// the render goes on: the image is still written at the end).
    pub fn maybe_write(&self, sums: &RenderSums) {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if last.elapsed() < self.interval {
            return;
        }
        if let Err(e) = self.write(sums) {
            let mut failed = self.failed.lock().unwrap_or_else(|e| e.into_inner());
            failed.get_or_insert(e);
        }
        *last = Instant::now();
    }

    /// Saves `sums` now.
    pub fn write(&self, sums: &RenderSums) -> Result<(), String> {
        sums.save(&self.path)
            .map_err(|e| format!("cannot write checkpoint {}: {e}", self.path.display()))
    }

    /// Prints the first failed write, if any.
    pub fn warn_if_failed(&self) {
        if let Some(e) = self.failed.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            eprintln!("warning: {e}");
        }
    }

    /// Deletes the checkpoint (the render is complete and written).
    pub fn remove(&self) {
        // a render finished before its first checkpoint has no file to delete
        let _ = std::fs::remove_file(&self.path);
    }
}
