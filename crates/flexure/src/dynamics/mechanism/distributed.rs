//! A flexure's distributed mass in a mechanism: the nested quadrature
//! tables of its sections ([`Distributed`]), and the coordinates a body or a
//! section moves with ([`path_columns`]).

use crate::error::Result;
use crate::flexure::{Basis, Flexure};
use crate::mass::MassModel;
use crate::mechanism::Mechanism;
use crate::quadrature::GaussLegendre;

/// One flexure's distributed mass: the nested quadrature tables of
/// [`crate::mass`], with the positions of the sections kept (they turn
/// with everything upstream).
#[derive(Debug, Clone)]
pub(super) struct Distributed {
    pub(super) joint: usize,
    pub(super) order: usize,
    pub(super) per_panel: usize,
    /// $\psi$ at the inner nodes, `[node * order + i]`.
    pub(super) inner_psi: Vec<f64>,
    /// $L\Delta\tau$ of the inner nodes.
    pub(super) inner_weight: Vec<f64>,
    /// $L\Delta_k\mu(t_k)$ of the node ending each panel (0 at a piece's end).
    pub(super) mass: Vec<f64>,
    /// $L\Delta_k\rho I(t_k)$ of the node ending each panel.
    pub(super) rotary: Vec<f64>,
    /// $\psi(t_k)$ of the node ending each panel.
    pub(super) outer_psi: Vec<f64>,
    /// The coordinates its sections' positions depend on: the path to its parent, then its own.
    pub(super) columns: Vec<usize>,
}

impl Distributed {
    /// The distributed inertia of flexure `f`, joint `joint` of `m`, with the
    /// rule and refinement its [`MassModel`] (from [`crate::mechanism::Joint::inertia`]) settled on.
    pub(super) fn new(m: &Mechanism, joint: usize, f: &Flexure, model: &MassModel) -> Result<Self> {
        let (n, l) = (f.order(), f.length());
        let section = f.section();
        let (outer, inner, sub) = model.rule();
        let (outer, inner) = (GaussLegendre::new(outer)?, GaussLegendre::new(inner)?);
        let mut breaks = section.breakpoints(l);
        if f.basis() == Basis::Segments {
            breaks.extend((1..n).map(|j| j as f64 / n as f64));
            breaks.sort_by(f64::total_cmp);
            breaks.dedup();
        }
        let ends: Vec<f64> = std::iter::once(0.0).chain(breaks.iter().copied()).chain(std::iter::once(1.0)).collect();
        // (t, μ weight, ρI weight) of every point that ends a panel.
        let mut points: Vec<(f64, f64, f64)> = Vec::new();
        for p in 0..ends.len() - 1 {
            for q in 0..sub {
                let a = ends[p] + (ends[p + 1] - ends[p]) * q as f64 / sub as f64;
                let b = ends[p] + (ends[p + 1] - ends[p]) * (q + 1) as f64 / sub as f64;
                for (&x, &w) in outer.nodes().iter().zip(outer.weights()) {
                    let t = a + (b - a) * x;
                    let weight = l * (b - a) * w;
                    let mu = section.mass_per_length(t, l).unwrap_or(0.0);
                    let rho_i = section.rotary_inertia_per_length(t, l).unwrap_or(0.0);
                    points.push((t, weight * mu, weight * rho_i));
                }
                points.push((b, 0.0, 0.0));
            }
        }
        let mut psi = vec![0.0; n];
        let mut d = Distributed {
            joint,
            order: n,
            per_panel: inner.len(),
            inner_psi: Vec::with_capacity(points.len() * inner.len() * n),
            inner_weight: Vec::with_capacity(points.len() * inner.len()),
            mass: Vec::with_capacity(points.len()),
            rotary: Vec::with_capacity(points.len()),
            outer_psi: Vec::with_capacity(points.len() * n),
            columns: Vec::new(),
        };
        let mut start = 0.0;
        for &(end, mass, rotary) in &points {
            for (&x, &w) in inner.nodes().iter().zip(inner.weights()) {
                f.angle_shapes(start + (end - start) * x, &mut psi);
                d.inner_psi.extend_from_slice(&psi);
                d.inner_weight.push(l * (end - start) * w);
            }
            f.angle_shapes(end, &mut psi);
            d.outer_psi.extend_from_slice(&psi);
            d.mass.push(mass);
            d.rotary.push(rotary);
            start = end;
        }
        d.columns = path_columns(m, m.joints[joint].parent);
        d.columns.extend((0..n).map(|i| m.joints[joint].offset + i));
        Ok(d)
    }
}

/// The coordinates of the joints from the ground to `body`.
pub(super) fn path_columns(m: &Mechanism, body: usize) -> Vec<usize> {
    m.path(body)
        .into_iter()
        .flat_map(|j| (0..m.joints[j].kind.joint().dof()).map(move |i| m.joints[j].offset + i))
        .collect()
}
