//! A render's sums kept in a file while it runs ([`Checkpoint`]), for `--checkpoint` and
//! Python's `render(checkpoint=)`.
//!
//! The driver hands the sums to [`Checkpoint::maybe_save`] after every pass (through
//! `RenderOptions::on_pass`); it saves them (atomically: [`RenderSums::save`]) when the
//! interval has passed since the last save. A pass of a Cornell box at 256×256 is a 4 MB file
//! written in milliseconds, so the interval bounds the work lost to a crash, not the cost.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use super::sums::RenderSums;

/// A checkpoint file and how often it is written.
#[derive(Debug)]
pub struct Checkpoint {
    path: PathBuf,
    interval: Duration,
    last: Mutex<Instant>,
    /// The first failed save: the render goes on, and front ends report it at the end.
    failed: Mutex<Option<String>>,
}

impl Checkpoint {
    pub fn new(path: &Path, interval: Duration) -> Checkpoint {
        Checkpoint {
            path: path.to_path_buf(),
            interval,
            last: Mutex::new(Instant::now()),
            failed: Mutex::new(None),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The sums the file holds, to resume: an error names the file, and sums that do not
    /// start at sample 0 are not a checkpoint.
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

    /// Saves `sums` if the interval has passed since the last save.
    pub fn maybe_save(&self, sums: &RenderSums) {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if last.elapsed() < self.interval {
            return;
        }
        if let Err(e) = self.save(sums) {
            self.failed.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(e);
        }
        *last = Instant::now();
    }

    /// Saves `sums` now.
    pub fn save(&self, sums: &RenderSums) -> Result<(), String> {
        sums.save(&self.path)
            .map_err(|e| format!("cannot write checkpoint {}: {e}", self.path.display()))
    }

    /// The first save that failed, if any.
    pub fn failure(&self) -> Option<String> {
        self.failed.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// Deletes the file (the render is complete).
    pub fn remove(&self) {
        // a render finished before its first save has no file to delete
        let _ = std::fs::remove_file(&self.path);
    }
}
