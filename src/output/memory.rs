//! A run's output kept in memory ([`MemorySink`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::Summary;
use crate::error::Error;

/// Keeps every output time's [`Snapshot`] and the [`Summary`] in memory (studies, tests,
/// the Python package).
#[derive(Clone, Debug, Default)]
pub struct MemorySink {
    /// The snapshots, in time order (`t = 0` first).
    pub frames: Vec<Snapshot>,
    /// The summary, once the run has ended.
    pub summary: Option<Summary>,
}

impl MemorySink {
    /// An empty sink.
    pub fn new() -> Self {
        Self::default()
    }
}

impl OutputSink for MemorySink {
    fn frame(&mut self, snapshot: &Snapshot) -> Result<(), Error> {
        self.frames.push(snapshot.clone());
        Ok(())
    }

    fn finish(&mut self, summary: &Summary) -> Result<(), Error> {
        self.summary = Some(summary.clone());
        Ok(())
    }
}
