//! One sink that hands everything to several ([`FanOut`]).

use super::sink::{OutputSink, Snapshot};
use super::summary::Summary;
use crate::error::Error;

/// Hands each frame and the summary to every sink it holds, in order (e.g. a
/// [`super::FileSink`] and a [`super::VtkSink`]); the first error stops it.
#[derive(Default)]
pub struct FanOut<'a> {
    sinks: Vec<&'a mut dyn OutputSink>,
}

impl<'a> FanOut<'a> {
    /// An empty fan-out.
    pub fn new() -> Self {
        Self { sinks: Vec::new() }
    }

    /// Adds a sink.
    pub fn with(mut self, sink: &'a mut dyn OutputSink) -> Self {
        self.sinks.push(sink);
        self
    }
}

impl OutputSink for FanOut<'_> {
    fn frame(&mut self, snapshot: &Snapshot) -> Result<(), Error> {
        self.sinks.iter_mut().try_for_each(|s| s.frame(snapshot))
    }

    fn frame_owned(&mut self, snapshot: Snapshot) -> Result<(), Error> {
        // Every sink but the last reads it; the last takes it.
        let Some((last, rest)) = self.sinks.split_last_mut() else {
            return Ok(());
        };
        rest.iter_mut().try_for_each(|s| s.frame(&snapshot))?;
        last.frame_owned(snapshot)
    }

    fn finish(&mut self, summary: &Summary) -> Result<(), Error> {
        self.sinks.iter_mut().try_for_each(|s| s.finish(summary))
    }
}
