//! Table I of the paper: buckling loads under the four tip constraints, against
//! Euler.

use super::{Run, lib, unit};
use flexure::reference::euler;
use flexure::{TipConstraint, buckling_load};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// Table I: buckling loads under the four tip constraints.
pub(super) fn table1(_out: &Path, md: &mut String) -> Run<Value> {
    let f = unit(3)?;
    let printed = [(2.4677, 2.4674, 0.014), (10.0, 9.8696, 1.321), (20.9187, 19.7392, 5.975), (42.0, 39.4784, 6.387)];
    let mut text = String::from(
        "## Table I: buckling loads (EI/L²)\n\n| tip | model | Euler | model error | paper: model | paper: Euler | paper: error |\n|---|---|---|---|---|---|---|\n",
    );
    let mut rows = Vec::new();
    for (tip, (pm, pe, perr)) in TipConstraint::ALL.into_iter().zip(printed) {
        let b = buckling_load(&f, tip).map_err(lib)?;
        let e = euler::buckling_load(tip, 1.0, 1.0);
        let err = 100.0 * (b.critical_load / e - 1.0);
        let note = if tip == TipConstraint::Pinned { " (errata: Euler is 20.1907, so +3.6 %)" } else { "" };
        let _ = writeln!(
            text,
            "| {} | {:.4} | {:.4} | {:.3} % | {pm:.4} | {pe:.4} | {perr:.3} %{note} |",
            tip.name(),
            b.critical_load,
            e,
            err
        );
        rows.push(json!({ "tip": tip.name(), "model": b.critical_load, "euler": e, "error_percent": err, "mode": b.mode.as_slice(), "paper_model": pm, "paper_euler": pe, "paper_error_percent": perr }));
    }
    text.push('\n');
    md.push_str(&text);
    Ok(json!({ "rows": rows }))
}
