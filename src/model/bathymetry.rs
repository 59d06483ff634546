//! A seabed given as a grid of heights (MoorDyn's `SeafloorFile` format), interpolated
//! bilinearly (docs/src/model/seabed.md).
//!
//! The file is plain text: a line `nx ny`, a line of the `nx` grid abscissae `x`, a line
//! of the `ny` ordinates `y` (each strictly increasing), then one line `x y z` per grid
//! point (`nx ny` of them, in any order), `z` the seabed's height (m, negative under
//! the surface). Blank lines and lines starting with `#` or `--` are skipped.

use crate::error::Error;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A seabed grid: heights `z` at the points `(xs[i], ys[j])`, kept packed as the GPU
/// reads it (see [`Bathymetry::packed`]).
#[derive(Debug, PartialEq)]
pub struct Bathymetry {
    /// The file it was read from (for messages).
    pub path: PathBuf,
    /// Grid abscissae, strictly increasing, m.
    pub xs: Vec<f64>,
    /// Grid ordinates, strictly increasing, m.
    pub ys: Vec<f64>,
    /// Heights, `z[i * ny + j]` at `(xs[i], ys[j])`, m.
    pub z: Vec<f64>,
    /// `[nx, ny, xs.., ys.., z..]`: the layout `physics::seabed_height` (and its WGSL
    /// twin) reads.
    pub packed: Vec<f64>,
}

fn bad(path: &Path, line: usize, message: impl Into<String>) -> Error {
    Error::Scenario {
        path: path.to_path_buf(),
        field: format!("line {line}"),
        message: message.into(),
    }
}

fn number(path: &Path, line: usize, what: &str, tok: &str) -> Result<f64, Error> {
    match tok.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(bad(path, line, format!("{what} is {x}: must be finite"))),
        Err(_) => Err(bad(path, line, format!("{what} \"{tok}\" is not a number"))),
    }
}

fn ticks(path: &Path, line: usize, axis: &str, n: usize, toks: &[&str]) -> Result<Vec<f64>, Error> {
    if toks.len() != n {
        return Err(bad(
            path,
            line,
            format!(
                "the {axis} row has {} values; the first line says {n}",
                toks.len()
            ),
        ));
    }
    let mut v = Vec::with_capacity(n);
    for (k, t) in toks.iter().enumerate() {
        let x = number(path, line, &format!("{axis}[{k}]"), t)?;
        if let Some(&prev) = v.last() {
            if x <= prev {
                return Err(bad(
                    path,
                    line,
                    format!("{axis}[{k}] = {x} does not exceed {axis}[{}] = {prev}: the {axis} values must increase strictly", k - 1),
                ));
            }
        }
        v.push(x);
    }
    Ok(v)
}

/// The grid index of `x` among `ticks` (within a millionth of the grid's extent).
fn index_of(ticks: &[f64], x: f64) -> Option<usize> {
    let span = (ticks[ticks.len() - 1] - ticks[0]).abs().max(1.0);
    let tol = 1e-6 * span;
    ticks.iter().position(|t| (t - x).abs() <= tol)
}

impl Bathymetry {
    /// Parses the grid in `text` (read from `path`, named in errors with the line).
    pub fn parse(path: &Path, text: &str) -> Result<Self, Error> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#') && !l.starts_with("--"));
        let toks = |l: &str| -> Vec<String> { l.split_whitespace().map(str::to_string).collect() };
        let Some((l1, first)) = lines.next() else {
            return Err(bad(
                path,
                1,
                "empty file: expected `nx ny`, the x row, the y row and `x y z` rows",
            ));
        };
        let t = toks(first);
        let count = |k: usize, what: &str| -> Result<usize, Error> {
            let s = t
                .get(k)
                .ok_or_else(|| bad(path, l1, format!("expected `nx ny`, found \"{first}\"")))?;
            match s.parse::<usize>() {
                Ok(n) if n >= 1 => Ok(n),
                _ => Err(bad(
                    path,
                    l1,
                    format!("{what} = \"{s}\": must be a whole number of at least 1"),
                )),
            }
        };
        let (nx, ny) = (count(0, "nx")?, count(1, "ny")?);
        if t.len() != 2 {
            return Err(bad(
                path,
                l1,
                format!("expected `nx ny`, found \"{first}\""),
            ));
        }
        let Some((lx, xrow)) = lines.next() else {
            return Err(bad(path, l1 + 1, "the x row is missing"));
        };
        let xs = ticks(
            path,
            lx,
            "x",
            nx,
            &xrow.split_whitespace().collect::<Vec<_>>(),
        )?;
        let Some((ly, yrow)) = lines.next() else {
            return Err(bad(path, lx + 1, "the y row is missing"));
        };
        let ys = ticks(
            path,
            ly,
            "y",
            ny,
            &yrow.split_whitespace().collect::<Vec<_>>(),
        )?;
        let mut z = vec![f64::NAN; nx * ny];
        let mut given = vec![0usize; nx * ny];
        let mut last = ly;
        for (l, row) in lines {
            last = l;
            let t: Vec<&str> = row.split_whitespace().collect();
            if t.len() != 3 {
                return Err(bad(path, l, format!("expected `x y z`, found \"{row}\"")));
            }
            let x = number(path, l, "x", t[0])?;
            let y = number(path, l, "y", t[1])?;
            let h = number(path, l, "z", t[2])?;
            let i = index_of(&xs, x).ok_or_else(|| {
                bad(
                    path,
                    l,
                    format!("x = {x} is not one of the grid's x values (line {lx})"),
                )
            })?;
            let j = index_of(&ys, y).ok_or_else(|| {
                bad(
                    path,
                    l,
                    format!("y = {y} is not one of the grid's y values (line {ly})"),
                )
            })?;
            if given[i * ny + j] != 0 {
                return Err(bad(
                    path,
                    l,
                    format!(
                        "the point x = {x}, y = {y} is given twice (also on line {})",
                        given[i * ny + j]
                    ),
                ));
            }
            if h > 0.0 {
                return Err(bad(
                    path,
                    l,
                    format!("z = {h} m puts the seabed above the water surface (z = 0)"),
                ));
            }
            given[i * ny + j] = l;
            z[i * ny + j] = h;
        }
        if let Some(k) = given.iter().position(|&g| g == 0) {
            let (i, j) = (k / ny, k % ny);
            let n = given.iter().filter(|&&g| g == 0).count();
            return Err(bad(
                path,
                last,
                format!(
                    "the grid is not complete: {n} of its {} points have no `x y z` row, the first x = {}, y = {}",
                    nx * ny,
                    xs[i],
                    ys[j]
                ),
            ));
        }
        Ok(Self::new(path.to_path_buf(), xs, ys, z))
    }

    /// A grid from its values (`z[i * ys.len() + j]` at `(xs[i], ys[j])`), unchecked.
    pub fn new(path: PathBuf, xs: Vec<f64>, ys: Vec<f64>, z: Vec<f64>) -> Self {
        let mut packed = Vec::with_capacity(2 + xs.len() + ys.len() + z.len());
        packed.push(xs.len() as f64);
        packed.push(ys.len() as f64);
        packed.extend_from_slice(&xs);
        packed.extend_from_slice(&ys);
        packed.extend_from_slice(&z);
        Self {
            path,
            xs,
            ys,
            z,
            packed,
        }
    }

    /// Reads and parses the file at `path`.
    pub fn read(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Scenario {
            path: path.to_path_buf(),
            field: "seabed file".into(),
            message: format!("cannot read it: {e}"),
        })?;
        Self::parse(path, &text)
    }

    /// Height of the seabed at `(x, y)`, m (clamped to the edge values outside the grid).
    pub fn height(&self, x: f64, y: f64) -> f64 {
        crate::physics::seabed_height(&self.packed[..], x, y).x
    }

    /// Whether `(x, y)` lies within the grid's extent (with `tol` metres to spare).
    pub fn covers(&self, x: f64, y: f64, tol: f64) -> bool {
        let (x0, x1) = (self.xs[0], self.xs[self.xs.len() - 1]);
        let (y0, y1) = (self.ys[0], self.ys[self.ys.len() - 1]);
        let inside = |v: f64, a: f64, b: f64, n: usize| n == 1 || (v >= a - tol && v <= b + tol);
        inside(x, x0, x1, self.xs.len()) && inside(y, y0, y1, self.ys.len())
    }

    /// The grid's extent in words, for messages.
    pub fn extent(&self) -> String {
        format!(
            "x in [{}, {}] m, y in [{}, {}] m",
            self.xs[0],
            self.xs[self.xs.len() - 1],
            self.ys[0],
            self.ys[self.ys.len() - 1]
        )
    }

    /// The lowest and the mean height of the grid, m.
    pub fn lowest_and_mean(&self) -> (f64, f64) {
        let low = self.z.iter().copied().fold(f64::INFINITY, f64::min);
        (low, self.z.iter().sum::<f64>() / self.z.len() as f64)
    }

    /// The grid kept for the rest of the process: `Seabed` (and with it the whole
    /// environment) is `Copy`, so it holds the grid by a `'static` reference. A grid
    /// equal to one kept before is shared, so loading the same file again (a study's
    /// members) keeps no second copy.
    pub fn keep(self) -> &'static Bathymetry {
        static KEPT: Mutex<Vec<&'static Bathymetry>> = Mutex::new(Vec::new());
        let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(&b) = kept.iter().find(|b| ***b == self) {
            return b;
        }
        let b: &'static Bathymetry = Box::leak(Box::new(self));
        kept.push(b);
        b
    }
}
