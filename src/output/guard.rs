//! The files the writer thread writes: each counts the bytes that reached it, so that
//! after a failed write (a full disk) it can be cut back to its last whole frame; a
//! test can make one act as a full disk past a given size.

use crate::error::Error;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// An output file that knows how many bytes reached it.
pub(crate) struct GuardedFile {
    file: File,
    path: PathBuf,
    /// Bytes written to the file so far.
    written: u64,
    /// Acts as a full disk past this many bytes (tests, [`super::FileSink::with_disk_limit`]).
    cap: Option<u64>,
}

impl GuardedFile {
    /// Creates (truncates) `path`.
    pub fn create(path: &Path, cap: Option<u64>) -> Result<Self, Error> {
        let file = File::create(path).map_err(|source| Error::Output {
            path: path.to_path_buf(),
            source,
        })?;
        Ok(Self {
            file,
            path: path.to_path_buf(),
            written: 0,
            cap,
        })
    }

    /// Opens `path` again for writing, as it is (to cut it back).
    pub fn reopen(path: &Path, cap: Option<u64>) -> std::io::Result<Self> {
        let file = File::options().write(true).open(path)?;
        let written = file.metadata()?.len();
        Ok(Self {
            file,
            path: path.to_path_buf(),
            written,
            cap,
        })
    }

    /// Bytes written to the file so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    /// The path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Cuts the file back to `len` bytes (its last whole frame) and appends `tail`
    /// (a Parquet footer; empty for CSV). Best effort after a write error: the error it
    /// meets is returned for the log.
    pub fn cut_back(&mut self, len: u64, tail: &[u8]) -> std::io::Result<()> {
        use std::io::{Seek, SeekFrom};
        self.file.set_len(len)?;
        self.file.seek(SeekFrom::Start(len))?;
        self.written = len;
        self.write_all(tail)?;
        self.file.flush()
    }
}

impl Write for GuardedFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let room = self
            .cap
            .map_or(u64::MAX, |c| c.saturating_sub(self.written));
        if room == 0 && !buf.is_empty() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                "no space left on device (a test's limit on the file's size)",
            ));
        }
        let take = buf.len().min(room.min(usize::MAX as u64) as usize);
        let n = self.file.write(&buf[..take])?;
        self.written += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

/// An I/O error on `path`, with what the files hold after it.
pub(crate) fn write_error(path: &Path, e: std::io::Error, kept: &str) -> Error {
    Error::Output {
        path: path.to_path_buf(),
        source: std::io::Error::new(e.kind(), format!("{e}; {kept}")),
    }
}
