//! `--input FILE`: a CSV whose header names the options, one call per row.
//! Every row is answered, by its result or by its error in its place: one
//! JSON object per line with `--json` (`{"row": n, "error": "…"}` for a
//! failure), CSV otherwise (`# row n: error: …` for a failure).

use crate::joint::pose as pose_json;
use crate::options::{number, parse_angle, warn};
use flexure::kinematics::{Pose, par_poses_root_tip};
use flexure::{Flexure, StaticsData, TipLoad, deflect, energy};
use serde_json::{Value, json};
use std::path::Path;

/// The answers to a file's rows, in order.
pub struct Rows {
    /// Where the rows came from, for messages.
    pub source: String,
    /// The CSV header of the table form; each answer's leaves, in order, are its columns.
    pub header: String,
    /// Each row's result, or why it has none.
    pub answers: Vec<Result<Value, String>>,
}

/// A CSV's header names, and each data row's numbers or why it cannot be read.
struct Table {
    columns: Vec<String>,
    rows: Vec<Result<Vec<f64>, String>>,
}

/// Reads `path`; blank lines and lines starting with `#` are skipped. The
/// header must name each column once, from `allowed`; a cell of an `angle`
/// column may end in `deg`. A row that cannot be read is an error of that
/// row only.
fn read(path: &Path, allowed: &[&str]) -> Result<Table, String> {
    let file = path.display();
    let text = crate::input::read_text(path, "--input ")?;
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (_, header) = lines.next().ok_or_else(|| format!("--input {file}: no header line"))?;
    let columns: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
    for (i, c) in columns.iter().enumerate() {
        if !allowed.contains(&c.as_str()) {
            return Err(format!("--input {file}: unknown column {c:?}; expected some of {}", allowed.join(", ")));
        }
        if columns[..i].contains(c) {
            return Err(format!("--input {file}: column {c:?} appears twice"));
        }
    }
    let mut suspicious: Vec<(usize, String)> = Vec::new();
    let mut rows = Vec::new();
    for (i, line) in lines {
        let line_no = i + 1;
        let cells: Vec<&str> = line.split(',').collect();
        if cells.len() != columns.len() {
            rows.push(Err(format!("line {line_no}: {} values for {} columns", cells.len(), columns.len())));
            continue;
        }
        let row = cells
            .iter()
            .zip(&columns)
            .map(|(c, name)| {
                let v = if name == "angle" {
                    parse_angle(c).map(|(v, bare_and_large)| {
                        if bare_and_large {
                            suspicious.push((line_no, c.trim().to_string()));
                        }
                        v
                    })
                } else {
                    number(c)
                };
                v.map_err(|e| format!("line {line_no}, column {name}: {e}"))
            })
            .collect::<Result<Vec<f64>, String>>();
        rows.push(row);
    }
    if let Some((line_no, cell)) = suspicious.first() {
        let others = match suspicious.len() - 1 {
            0 => String::new(),
            n => format!(" (and {n} more rows)"),
        };
        warn(format!(
            "--input {file} line {line_no}: angle {cell} is read as radians{others}; write {cell}deg for degrees"
        ));
    }
    if rows.is_empty() {
        // An answer with nothing in it would pass for success.
        return Err(format!("--input {file}: no rows after the header (nothing to answer)"));
    }
    Ok(Table { columns, rows })
}

fn column(table: &Table, name: &str) -> Option<usize> {
    table.columns.iter().position(|c| c == name)
}

/// Poses (and energies) of the α rows `a1,a2,…`, through the parallel batch API.
pub fn kinematics(f: &Flexure, path: &Path) -> Result<Rows, String> {
    let names: Vec<String> = (1..=f.order()).map(|i| format!("a{i}")).collect();
    let allowed: Vec<&str> = names.iter().map(String::as_str).collect();
    let table = read(path, &allowed)?;
    let idx = names
        .iter()
        .map(|n| {
            column(&table, n)
                .ok_or_else(|| format!("--input {}: missing column {n:?} (order {})", path.display(), f.order()))
        })
        .collect::<Result<Vec<usize>, String>>()?;
    let alpha_rows: Vec<Result<Vec<f64>, String>> =
        table.rows.into_iter().map(|r| r.map(|cells| idx.iter().map(|&i| cells[i]).collect())).collect();
    let alphas: Vec<f64> = alpha_rows.iter().flatten().flatten().copied().collect();
    let mut poses = vec![Pose::default(); alphas.len() / f.order()];
    let batch = par_poses_root_tip(f, &alphas, &mut poses).map_err(|e| e.to_string());
    let mut poses = poses.iter();
    let answers = alpha_rows
        .into_iter()
        .map(|row| {
            let alpha = row?;
            let pose = poses.next().ok_or("no pose computed for this row")?;
            batch.clone()?;
            Ok(json!({ "alpha": alpha, "pose": pose_json(pose), "energy": energy(f, &alpha) }))
        })
        .collect();
    Ok(Rows {
        source: format!("--input {}", path.display()),
        header: format!("{},phi,x,y,energy", names.join(",")),
        answers,
    })
}

/// Equilibria for the load rows: columns among `moment,fx,fy` or `moment,force,angle`.
pub fn deflect_rows(f: &Flexure, path: &Path, target: &flexure::estimate::Accuracy) -> Result<Rows, String> {
    let table = read(path, &["moment", "fx", "fy", "force", "angle"])?;
    let get = |r: &[f64], name: &str| column(&table, name).map_or(0.0, |i| r[i]);
    let polar = column(&table, "force").is_some() || column(&table, "angle").is_some();
    if polar && (column(&table, "fx").is_some() || column(&table, "fy").is_some()) {
        return Err(format!("--input {}: give force,angle or fx,fy, not both", path.display()));
    }
    let mut data = StaticsData::new(f);
    // The rows share the flexure, so its reference model is built once.
    let mut estimator = flexure::estimate::Estimator::new();
    let mut flagged = 0;
    let mut answers = Vec::with_capacity(table.rows.len());
    for row in &table.rows {
        let answer = row.as_ref().map_err(String::clone).and_then(|r| {
            let load = if polar {
                TipLoad::polar(get(r, "moment"), get(r, "force"), get(r, "angle"))
            } else {
                TipLoad { moment: get(r, "moment"), fx: get(r, "fx"), fy: get(r, "fy") }
            };
            let solved = deflect(f, &load, &mut data, &Default::default()).and_then(|eq| {
                let e = estimator.deflect_error(f, &load, data.alpha(), target)?;
                Ok((eq, e))
            });
            match solved {
                Ok((eq, e)) => {
                    flagged += usize::from(e.flagged);
                    Ok(json!({
                        "load": { "moment": load.moment, "fx": load.fx, "fy": load.fy },
                        "alpha": data.alpha(), "pose": pose_json(&data.pose_root_tip()), "stable": eq.stable,
                        "error_estimate": crate::answer::estimate(&e), "flagged": e.flagged,
                    }))
                }
                Err(e) => {
                    // Nothing of a failed solve carries over to the next row.
                    data = StaticsData::new(f);
                    Err(e.to_string())
                }
            }
        });
        answers.push(answer);
    }
    if flagged > 0 {
        crate::options::warn(format!(
            "--input {}: {flagged} rows have an estimated error above the accuracy target (flagged); try a higher --order",
            path.display()
        ));
    }
    let a: Vec<String> = (1..=f.order()).map(|i| format!("a{i}")).collect();
    Ok(Rows {
        source: format!("--input {}", path.display()),
        header: format!("moment,fx,fy,{},phi,x,y,stable,{},flagged", a.join(","), estimate_columns(f).join(",")),
        answers,
    })
}

/// The table form's columns of a row's `error_estimate`, in its order
/// (`stress` only for a flexure with a thickness, as the estimate has it).
fn estimate_columns(f: &Flexure) -> Vec<&'static str> {
    let stress = f.section().modulus().is_some();
    ["error_position", "error_angle", "error_stress", "error_curvature"]
        .into_iter()
        .filter(|c| stress || *c != "error_stress")
        .chain(["error_reference_order", "error_reference_quadrature", "error_reference"])
        .collect()
}
