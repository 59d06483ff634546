//! Reading input files with a size cap: a scenario, route, payout, motion, RAO, sea-state
//! or MoorDyn file larger than [`MAX_INPUT_BYTES`] is refused (a device such as
//! `/dev/zero` or a runaway generated file would otherwise be read until memory runs
//! out).

use std::io::Read;
use std::path::Path;

/// The largest input file read, bytes (64 MiB): far above any real scenario or table
/// (the largest example is a few kB; a 1 Hz motion table of a year is about 40 MB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// The bytes of `path`, at most [`MAX_INPUT_BYTES`]; the error is a sentence to put
/// after the file's name.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, String> {
    let f = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    // A regular file says its size: refuse before reading. Devices and pipes do not:
    // read one byte past the cap and stop there.
    if let Ok(m) = f.metadata() {
        if m.is_file() && m.len() > MAX_INPUT_BYTES {
            return Err(too_big(m.len()));
        }
        if m.is_dir() {
            return Err("cannot read: it is a directory".into());
        }
    }
    let mut buf = Vec::new();
    f.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut buf)
        .map_err(|e| format!("cannot read: {e}"))?;
    if buf.len() as u64 > MAX_INPUT_BYTES {
        return Err(format!(
            "more than {} MiB (the cap on input files): not a scenario or table file",
            MAX_INPUT_BYTES >> 20
        ));
    }
    Ok(buf)
}

/// The text of `path` (UTF-8), at most [`MAX_INPUT_BYTES`].
pub fn read_text(path: &Path) -> Result<String, String> {
    let bytes = read_bytes(path)?;
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "cannot read: not UTF-8 text (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        )
    })
}

fn too_big(len: u64) -> String {
    format!(
        "{len} bytes, over the cap of {} MiB on input files: not a scenario or table file",
        MAX_INPUT_BYTES >> 20
    )
}
