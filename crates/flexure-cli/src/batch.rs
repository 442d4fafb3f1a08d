//! `--input FILE`: a CSV whose header names the options, one call per row.
//! Output is one JSON object per line with `--json`, CSV otherwise.

use crate::joint::pose as pose_json;
use crate::options::number;
use flexure::kinematics::{Pose, par_poses_root_tip};
use flexure::{Flexure, Statics, TipLoad, deflect, energy};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// A parsed CSV: header names and rows of finite numbers.
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

/// Reads `path`; blank lines and lines starting with `#` are skipped.
pub fn read(path: &Path) -> Result<Table, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("--input {}: {e}", path.display()))?;
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (_, header) = lines.next().ok_or_else(|| format!("--input {}: no header line", path.display()))?;
    let columns: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
    let mut rows = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').collect();
        if cells.len() != columns.len() {
            return Err(format!(
                "--input {} line {}: {} values for {} columns",
                path.display(),
                i + 1,
                cells.len(),
                columns.len()
            ));
        }
        let row = cells
            .iter()
            .zip(&columns)
            .map(|(c, name)| {
                number(c).map_err(|e| format!("--input {} line {}, column {name}: {e}", path.display(), i + 1))
            })
            .collect::<Result<Vec<f64>, String>>()?;
        rows.push(row);
    }
    Ok(Table { columns, rows })
}

fn column(table: &Table, name: &str) -> Option<usize> {
    table.columns.iter().position(|c| c == name)
}

fn check_columns(table: &Table, allowed: &[&str], path: &Path) -> Result<(), String> {
    for c in &table.columns {
        if !allowed.contains(&c.as_str()) {
            return Err(format!(
                "--input {}: unknown column {c:?}; expected some of {}",
                path.display(),
                allowed.join(", ")
            ));
        }
    }
    Ok(())
}

/// Poses (and energies) of the α rows `a1,a2,…`, through the parallel batch API.
pub fn kinematics(f: &Flexure, path: &Path, as_json: bool) -> Result<String, String> {
    let table = read(path)?;
    let names: Vec<String> = (1..=f.order()).map(|i| format!("a{i}")).collect();
    let allowed: Vec<&str> = names.iter().map(String::as_str).collect();
    check_columns(&table, &allowed, path)?;
    let idx = names
        .iter()
        .map(|n| {
            column(&table, n)
                .ok_or_else(|| format!("--input {}: missing column {n:?} (order {})", path.display(), f.order()))
        })
        .collect::<Result<Vec<usize>, String>>()?;
    let alphas: Vec<f64> = table.rows.iter().flat_map(|r| idx.iter().map(move |&i| r[i])).collect();
    let mut poses = vec![Pose::default(); table.rows.len()];
    par_poses_root_tip(f, &alphas, &mut poses).map_err(|e| e.to_string())?;
    let mut out = String::new();
    if !as_json {
        let _ = writeln!(out, "{},phi,x,y,energy", names.join(","));
    }
    for (alpha, p) in alphas.chunks_exact(f.order()).zip(&poses) {
        let u = energy(f, alpha);
        if as_json {
            let _ = writeln!(out, "{}", json!({ "alpha": alpha, "pose": pose_json(p), "energy": u }));
        } else {
            let a: Vec<String> = alpha.iter().map(|v| v.to_string()).collect();
            let _ = writeln!(out, "{},{},{},{},{u}", a.join(","), p.phi, p.x, p.y);
        }
    }
    Ok(out)
}

/// Equilibria for the load rows: columns among `moment,fx,fy` or `moment,force,angle`.
pub fn deflect_rows(f: &Flexure, path: &Path, as_json: bool) -> Result<String, String> {
    let table = read(path)?;
    check_columns(&table, &["moment", "fx", "fy", "force", "angle"], path)?;
    let get = |r: &Vec<f64>, name: &str| column(&table, name).map_or(0.0, |i| r[i]);
    let polar = column(&table, "force").is_some() || column(&table, "angle").is_some();
    if polar && (column(&table, "fx").is_some() || column(&table, "fy").is_some()) {
        return Err(format!("--input {}: give force,angle or fx,fy, not both", path.display()));
    }
    let mut data = Statics::new(f);
    let mut out = String::new();
    if !as_json {
        let a: Vec<String> = (1..=f.order()).map(|i| format!("a{i}")).collect();
        let _ = writeln!(out, "moment,fx,fy,{},phi,x,y,stable", a.join(","));
    }
    for (line, r) in table.rows.iter().enumerate() {
        let load = if polar {
            TipLoad::polar(get(r, "moment"), get(r, "force"), get(r, "angle"))
        } else {
            TipLoad { moment: get(r, "moment"), fx: get(r, "fx"), fy: get(r, "fy") }
        };
        let eq = deflect(f, &load, &mut data, &Default::default())
            .map_err(|e| format!("--input {} row {}: {e}", path.display(), line + 1))?;
        let p = data.pose_root_tip();
        if as_json {
            let v: Value = json!({
                "load": { "moment": load.moment, "fx": load.fx, "fy": load.fy },
                "alpha": data.alpha(), "pose": pose_json(&p), "stable": eq.stable,
            });
            let _ = writeln!(out, "{v}");
        } else {
            let a: Vec<String> = data.alpha().iter().map(|v| v.to_string()).collect();
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{}",
                load.moment,
                load.fx,
                load.fy,
                a.join(","),
                p.phi,
                p.x,
                p.y,
                eq.stable
            );
        }
    }
    Ok(out)
}
