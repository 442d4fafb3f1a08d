//! The tip wrenches each flexure carries over a load range.

use super::LoadRange;
use crate::error::Result;
use crate::kinematics::{self, Kinematics, Level};
use crate::mechanism::statics::{Settings, Solution, Statics, assemble_unloaded, solve_between};
use crate::mechanism::{Loads, Mechanism};
use crate::statics::TipLoad;

/// The mechanism's equilibria along `range` (the file's loads times each
/// fraction), each continued from the last, starting from the unloaded,
/// assembled shape.
pub fn equilibria(m: &Mechanism, range: &LoadRange, settings: &Settings) -> Result<Vec<Solution>> {
    equilibria_scaled(m, range, settings, |loads, lambda| loads.scale(lambda))
}

/// [`equilibria`] in either dimension, `scale` multiplying every load by a fraction.
pub fn equilibria_scaled<D: Statics>(
    m: &Mechanism<D>,
    range: &LoadRange,
    settings: &Settings,
    scale: impl Fn(&mut Loads<D>, f64),
) -> Result<Vec<Solution<D>>> {
    range.validate()?;
    let full = m.loads();
    let mut last = assemble_unloaded(m, settings)?;
    let mut out = Vec::with_capacity(range.count);
    for lambda in range.fractions() {
        let mut loads = full.clone();
        scale(&mut loads, lambda);
        let s = solve_between(m, &last, &loads, settings)?;
        out.push(s.clone());
        last = s;
    }
    Ok(out)
}

/// The wrench $w = (M, F_x, F_y)$ at the tip of flexure joint `joint`, in
/// its root frame, that holds its coordinates $\alpha$ of the equilibrium
/// `s`: at equilibrium the flexure's elastic gradient balances what the
/// bodies beyond it pass on,
/// $$\nabla U(\alpha) = \mathcal J(\alpha)^T w,$$
/// with $\mathcal J$ its tip Jacobian (Eqs. 18–21), solved for $w$ by least
/// squares ([`crate::connect::tip_load`]). This is exact when every load on
/// the flexure's coordinates comes through its tip: forces, moments,
/// tendons (their via points are on bodies), closures and the weight of
/// bodies all do. Only the flexure's own distributed weight does not; the
/// least-squares wrench is then the tip load closest to it.
///
/// `None` when the joint is not a flexure.
pub fn tip_wrench(m: &Mechanism, joint: usize, s: &Solution) -> Option<Result<TipLoad>> {
    let spec = &m.joints[joint];
    let f = spec.kind.flexure()?;
    let alpha = &s.q[spec.offset..spec.offset + f.order()];
    let mut k = Kinematics::new(f);
    kinematics::update(f, alpha, &mut k, Level::Jacobian);
    Some(crate::connect::tip_load(f, alpha, &k))
}

/// Whether flexure joint `joint` carries its own weight along its length
/// (it has a mass and the mechanism has gravity): the one load that
/// [`tip_wrench`] cannot hold exactly.
pub fn weighs_itself(m: &Mechanism, joint: usize) -> bool {
    let Some(f) = m.joints[joint].kind.flexure() else { return false };
    m.gravity != nalgebra::Vector2::zeros() && f.section().mass_per_length(0.5, f.length()).is_some()
}
