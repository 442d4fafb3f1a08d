//! `simulate --out`: the CSV of a run, one row per sample, written as the
//! integrator reaches each sample, so a run stopped by Ctrl-C, SIGTERM or
//! a crash keeps on disk every sample it reached.

use flexure::dynamics::integrate::{Sample, with_samples};
use flexure::model::Model;
use flexure::report::BodyPose;
use std::cell::RefCell;
use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How often the rows written so far reach the disk, at most: often enough
/// that a killed run loses well under a second of samples, seldom enough
/// that a run of a million samples is not a million system calls.
const FLUSH_EVERY: Duration = Duration::from_millis(200);

/// The file being written and what each row needs.
struct Rows {
    model: Model,
    path: PathBuf,
    file: BufWriter<File>,
    flushed: Instant,
    /// The first write that failed: the run goes on, the command says it.
    error: Option<String>,
}

thread_local! {
    static ROWS: RefCell<Option<Rows>> = const { RefCell::new(None) };
}

/// Runs `work` (a simulation of `model`) writing its header to `file`
/// first, then each sample's row as it is reached; the rows reach the disk
/// at the end, and every [`FLUSH_EVERY`] on the way. Gives what `work`
/// returned and, apart, a failed write by the file's name.
pub fn written_as_reached<R>(
    model: &Model,
    (path, file): (&Path, File),
    work: impl FnOnce() -> R,
) -> (R, Result<(), String>) {
    let mut file = BufWriter::new(file);
    let header = file.write_all(header(model).as_bytes()).map_err(|e| format!("writing {}: {e}", path.display()));
    let rows =
        Rows { model: model.clone(), path: path.to_path_buf(), file, flushed: Instant::now(), error: header.err() };
    ROWS.with(|r| *r.borrow_mut() = Some(rows));
    let result = with_samples(write_row, work);
    let Some(mut rows) = ROWS.with(|r| r.borrow_mut().take()) else {
        return (result, Err("the rows' file was lost".into()));
    };
    if rows.error.is_none() {
        rows.error = rows.file.flush().err().map(|e| format!("writing {}: {e}", rows.path.display()));
    }
    (result, rows.error.map_or(Ok(()), Err))
}

/// The hook of [`with_samples`]: one row, flushed when the last flush is [`FLUSH_EVERY`] old.
fn write_row(sample: &Sample) {
    ROWS.with(|r| {
        let mut r = r.borrow_mut();
        let Some(rows) = r.as_mut().filter(|rows| rows.error.is_none()) else { return };
        let line = row(&rows.model, sample);
        let mut written = rows.file.write_all(line.as_bytes());
        if written.is_ok() && rows.flushed.elapsed() >= FLUSH_EVERY {
            written = rows.file.flush();
            rows.flushed = Instant::now();
        }
        if let Err(e) = written {
            rows.error = Some(format!("writing {}: {e}", rows.path.display()));
        }
    });
}

/// `time`, each moving body's pose columns, each joint's coordinates then
/// their rates, `energy`, then each pair's push where it has geoms.
fn header(model: &Model) -> String {
    let columns: &[&str] = match model.dimension() {
        2 => &["x", "y", "phi"],
        _ => &["x", "y", "z", "qw", "qx", "qy", "qz"],
    };
    let mut header = vec!["time".to_string()];
    for b in &model.body_names()[1..] {
        header.extend(columns.iter().map(|c| format!("{b}.{c}")));
    }
    let joints = model.joints();
    for suffix in ["", ".rate"] {
        for (name, range) in &joints {
            header.extend((0..range.len()).map(|i| format!("{name}[{i}]{suffix}")));
        }
    }
    header.push("energy".into());
    header.extend(model.contact_columns());
    header.join(",") + "\n"
}

/// One sample's row, each number written so that it reads back exactly.
fn row(model: &Model, sample: &Sample) -> String {
    let mut row = vec![sample.time];
    for pose in model.body_poses(sample.coordinates).into_iter().skip(1) {
        match pose {
            BodyPose::Planar { x, y, phi } => row.extend([x, y, phi]),
            BodyPose::Spatial { x, y, z, rotation, .. } => {
                let r = nalgebra::Matrix3::from_fn(|i, j| rotation[i][j]);
                let q = nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(r));
                // MuJoCo's sign: w ≥ 0.
                let q = if q.w < 0.0 { -q.into_inner() } else { q.into_inner() };
                row.extend([x, y, z, q.w, q.i, q.j, q.k]);
            }
        }
    }
    row.extend(sample.coordinates);
    row.extend(sample.velocities);
    row.push(sample.energy);
    row.extend(sample.columns);
    let mut text = String::new();
    for (i, x) in row.iter().enumerate() {
        let _ = write!(text, "{}{}", if i > 0 { "," } else { "" }, crate::render::shortest(*x));
    }
    text + "\n"
}
