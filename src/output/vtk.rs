//! ParaView files ([`VtkSink`]): VTK XML PolyData (`.vtp`, ASCII) per output time and
//! a `.pvd` collection listing them with their times.

use super::sink::{OutputSink, Snapshot};
use super::summary::Summary;
use crate::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Writes a run for ParaView into one directory (`DIR/vtk` for `cablesim run`):
/// - `cables_NNNNN.vtp` per output time `NNNNN` (0, 1, ...): every cable's nodes as
///   points (m) and each element as a two-point line (cable order, start to end);
///   point data `velocity` (m/s) and `tension` (N: at an inner node the mean of its two
///   elements' tensions, at an end node its end element's), cell data
///   `element_tension` (N, the element's own axial force) and `cable` (the cable's
///   index in scenario order). A node shared by several cables appears once per cable.
/// - `points_NNNNN.vtp` when the run has vessel bodies or shared points: the bodies'
///   reference points (scenario order) then the shared points (`[[points]]`), as
///   vertices, with point data `force` (N: the cables' total force on the body, the
///   net force on a free point or the reaction of a held one) and `kind` (0 body,
///   1 shared point).
/// - `cablesim.pvd`: the collection, each file with its time (s) and `part` (0 cables,
///   1 bodies and points), written when the run ends (also when it diverged).
pub struct VtkSink {
    dir: PathBuf,
    /// `(time, part, file name)` of every file written.
    written: Vec<(f64, u32, String)>,
    frames: usize,
}

impl VtkSink {
    /// A sink writing into `dir` (created when needed).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self {
            dir: dir.into(),
            written: Vec::new(),
            frames: 0,
        }
    }

    /// The output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn write(&self, name: &str, text: &str) -> Result<(), Error> {
        let path = self.dir.join(name);
        std::fs::write(&path, text).map_err(|source| Error::Output { path, source })
    }

    fn collection(&self) -> String {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n",
        );
        for (t, part, file) in &self.written {
            let _ = writeln!(
                s,
                "<DataSet timestep=\"{t}\" group=\"\" part=\"{part}\" file=\"{file}\"/>"
            );
        }
        s.push_str("</Collection>\n</VTKFile>\n");
        s
    }
}

/// One `DataArray` of `Float64` values, `comps` per tuple.
fn array(s: &mut String, name: Option<&str>, comps: usize, values: impl Iterator<Item = f64>) {
    let name = name.map(|n| format!(" Name=\"{n}\"")).unwrap_or_default();
    let _ = write!(
        s,
        "<DataArray type=\"Float64\"{name} NumberOfComponents=\"{comps}\" format=\"ascii\">"
    );
    for (k, v) in values.enumerate() {
        if k > 0 {
            s.push(' ');
        }
        // VTK's ASCII parser does not read `NaN` or `inf`: a blown-up value becomes a
        // huge number that stands out in the colour map.
        let v = if v.is_finite() {
            v
        } else {
            f64::MAX.copysign(v)
        };
        let _ = write!(s, "{v}");
    }
    s.push_str("</DataArray>\n");
}

/// One `DataArray` of `Int64` values.
fn int_array(s: &mut String, name: &str, values: impl Iterator<Item = usize>) {
    let _ = write!(
        s,
        "<DataArray type=\"Int64\" Name=\"{name}\" format=\"ascii\">"
    );
    let v: Vec<String> = values.map(|v| v.to_string()).collect();
    s.push_str(&v.join(" "));
    s.push_str("</DataArray>\n");
}

const HEAD: &str =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n";
const TAIL: &str = "</Piece>\n</PolyData>\n</VTKFile>\n";

/// The cables' file: nodes, and each element a two-point line (so that its tension is
/// cell data of its own), with the node velocity and tension as point data.
pub fn cables_vtp(s: &Snapshot) -> String {
    let n: usize = s.cables.iter().map(|c| c.positions.len()).sum();
    let n_elem: usize = s
        .cables
        .iter()
        .map(|c| c.positions.len().saturating_sub(1))
        .sum();
    let mut out = String::from(HEAD);
    let _ = writeln!(
        out,
        "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"{n_elem}\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
    );
    out.push_str("<PointData Vectors=\"velocity\" Scalars=\"tension\">\n");
    array(
        &mut out,
        Some("velocity"),
        3,
        s.cables
            .iter()
            .flat_map(|c| c.velocities.iter().flatten().copied()),
    );
    let node_tension = s.cables.iter().flat_map(|c| {
        let t = &c.tensions;
        (0..c.positions.len()).map(move |k| match (k.checked_sub(1), t.get(k)) {
            (Some(a), Some(&b)) => 0.5 * (t[a] + b),
            (Some(a), None) => t[a],
            (None, Some(&b)) => b,
            (None, None) => 0.0,
        })
    });
    array(&mut out, Some("tension"), 1, node_tension);
    out.push_str("</PointData>\n<CellData Scalars=\"element_tension\">\n");
    // Per element, in cable order: its axial force (N) and its cable's index.
    array(
        &mut out,
        Some("element_tension"),
        1,
        s.cables.iter().flat_map(|c| {
            c.tensions
                .iter()
                .take(c.positions.len().saturating_sub(1))
                .copied()
        }),
    );
    int_array(
        &mut out,
        "cable",
        s.cables
            .iter()
            .enumerate()
            .flat_map(|(ci, c)| std::iter::repeat_n(ci, c.positions.len().saturating_sub(1))),
    );
    out.push_str("</CellData>\n<Points>\n");
    array(
        &mut out,
        None,
        3,
        s.cables
            .iter()
            .flat_map(|c| c.positions.iter().flatten().copied()),
    );
    out.push_str("</Points>\n<Lines>\n");
    let mut conn = Vec::with_capacity(2 * n_elem);
    let mut first = 0;
    for c in &s.cables {
        for k in 1..c.positions.len() {
            conn.push(first + k - 1);
            conn.push(first + k);
        }
        first += c.positions.len();
    }
    int_array(&mut out, "connectivity", conn.into_iter());
    int_array(&mut out, "offsets", (1..=n_elem).map(|e| 2 * e));
    out.push_str("</Lines>\n");
    out.push_str(TAIL);
    out
}

/// The bodies' and shared points' file: one vertex each, with force and kind.
pub fn points_vtp(s: &Snapshot) -> String {
    let n = s.bodies.len() + s.points.len();
    let mut out = String::from(HEAD);
    let _ = writeln!(
        out,
        "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"{n}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
    );
    out.push_str("<PointData Vectors=\"force\" Scalars=\"kind\">\n");
    let forces = s
        .bodies
        .iter()
        .map(|b| b.force)
        .chain(s.points.iter().map(|p| p.force));
    array(&mut out, Some("force"), 3, forces.flatten());
    let kinds = s.bodies.iter().map(|_| 0).chain(s.points.iter().map(|_| 1));
    int_array(&mut out, "kind", kinds);
    out.push_str("</PointData>\n<Points>\n");
    let xs = s
        .bodies
        .iter()
        .map(|b| b.position)
        .chain(s.points.iter().map(|p| p.position));
    array(&mut out, None, 3, xs.flatten());
    out.push_str("</Points>\n<Verts>\n");
    int_array(&mut out, "connectivity", 0..n);
    int_array(&mut out, "offsets", 1..=n);
    out.push_str("</Verts>\n");
    out.push_str(TAIL);
    out
}

impl OutputSink for VtkSink {
    fn frame(&mut self, s: &Snapshot) -> Result<(), Error> {
        if self.frames == 0 {
            std::fs::create_dir_all(&self.dir).map_err(|source| Error::Output {
                path: self.dir.clone(),
                source,
            })?;
        }
        let k = self.frames;
        let name = format!("cables_{k:05}.vtp");
        self.write(&name, &cables_vtp(s))?;
        self.written.push((s.time, 0, name));
        if !s.bodies.is_empty() || !s.points.is_empty() {
            let name = format!("points_{k:05}.vtp");
            self.write(&name, &points_vtp(s))?;
            self.written.push((s.time, 1, name));
        }
        self.frames += 1;
        Ok(())
    }

    fn finish(&mut self, _summary: &Summary) -> Result<(), Error> {
        if self.frames == 0 {
            return Ok(());
        }
        self.write("cablesim.pvd", &self.collection())
    }
}
