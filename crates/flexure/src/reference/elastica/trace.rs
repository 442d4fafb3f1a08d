//! The exact elastica along a flexure: its cross-sections, bending moment
//! and stress anywhere, from the states at a few nodes.

use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::Pose;
use crate::ode::{Tolerance, integrate_through};
use crate::statics::TipLoad;
use crate::stress::Peak;

/// Nodes a [`Trace::shot`] keeps along the flexure: a cross-section is then
/// integrated from at most $L/16$ away.
const SHOT_NODES: usize = 16;

/// Evenly spaced samples of the scan that brackets a peak ([`Trace::peak_stress`]).
const PEAK_SAMPLES: usize = 256;

/// Golden-section steps refining a bracketed peak: $0.618^{60} \approx 3\cdot10^{-13}$ of the bracket.
const PEAK_REFINEMENTS: usize = 60;

/// A cross-section of the exact elastica.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Arc length from the root (m).
    pub s: f64,
    /// Angle (rad).
    pub phi: f64,
    /// Position in the root frame (m).
    pub x: f64,
    /// See `x`.
    pub y: f64,
    /// Bending moment $m(s)$ (N·m).
    pub moment: f64,
    /// Total curvature $\omega_0(s) + m/EI(s)$ (1/m).
    pub curvature: f64,
    /// Change of curvature from rest, $m/EI(s)$ (1/m).
    pub curvature_change: f64,
    /// Bending stress $E^{\prime}\frac{h(s)}{2}\frac{|m|}{EI(s)}$ (Pa); `None` for a section without thickness.
    pub stress: Option<f64>,
}

/// The exact elastica along a flexure: the state $(\phi, m, x, y)$ at nodes
/// from the root to the tip, from which any cross-section is integrated by
/// $$\phi^{\prime} = \omega_0(s) + \frac{m}{EI(s)}, \quad m^{\prime} = F_x\sin\phi - F_y\cos\phi, \quad x^{\prime} = \cos\phi, \quad y^{\prime} = \sin\phi,$$
/// the force $(F_x, F_y)$ carried along the beam being the tip force. Made
/// by [`deflect_traced`](super::deflect_traced), [`Trace::shot`] or [`ElasticaConnection::trace`](super::ElasticaConnection::trace).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace<'a> {
    pub(super) flexure: &'a Flexure,
    pub(super) fx: f64,
    pub(super) fy: f64,
    /// The section's breakpoints (m).
    pub(super) stops: Vec<f64>,
    /// $(s_j, [\phi, m, x, y])$ with $s_0 = 0$ and the last at $L$.
    pub(super) nodes: Vec<(f64, [f64; 4])>,
    pub(super) ode: Tolerance,
}

impl<'a> Trace<'a> {
    /// The elastica shot from the clamped root with moment $M_0$ under the
    /// force $(F_x, F_y)$, kept at 16 evenly spaced nodes.
    ///
    /// # Example
    /// ```
    /// use flexure::{reference::elastica::Trace, Flexure};
    /// let f = Flexure::new(2.0, 4.0, 3).unwrap();
    /// // A root moment 2 and no force: an arc of curvature 1/2, angle 1.
    /// let t = Trace::shot(&f, 2.0, 0.0, 0.0, &Default::default()).unwrap();
    /// assert!((t.tip().phi - 1.0).abs() < 1e-11 && (t.at(1.0).unwrap().curvature - 0.5).abs() < 1e-12);
    /// ```
    pub fn shot(flexure: &'a Flexure, root_moment: f64, fx: f64, fy: f64, tol: &Tolerance) -> Result<Self> {
        TipLoad { moment: root_moment, fx, fy }.validate()?;
        tol.validate()?;
        let l = flexure.length();
        let mut trace = Self { flexure, fx, fy, stops: crate::reference::stops(flexure), nodes: Vec::new(), ode: *tol };
        let mut node = (0.0, [0.0, root_moment, 0.0, 0.0]);
        trace.nodes.push(node);
        for j in 1..=SHOT_NODES {
            let s = if j == SHOT_NODES { l } else { l * j as f64 / SHOT_NODES as f64 };
            node = (s, trace.advance(node, s, &mut 0.0)?);
            trace.nodes.push(node);
        }
        Ok(trace)
    }

    /// The flexure traced.
    pub fn flexure(&self) -> &'a Flexure {
        self.flexure
    }

    /// The tip pose.
    pub fn tip(&self) -> Pose {
        let y = self.nodes[self.nodes.len() - 1].1;
        Pose { phi: y[0], x: y[2], y: y[3] }
    }

    /// The state at `to`, integrated from `from` (forward).
    fn advance(&self, from: (f64, [f64; 4]), to: f64, step: &mut f64) -> Result<[f64; 4]> {
        let (f, kappa, fx, fy) = (self.flexure, self.flexure.rest(), self.fx, self.fy);
        let rhs = |s: f64, y: &[f64; 4]| {
            let (sn, cs) = y[0].sin_cos();
            [f.curvature(kappa, s) + y[1] / f.ei_at(s), fx * sn - fy * cs, cs, sn]
        };
        integrate_through(rhs, from.0, to, &self.stops, from.1, &self.ode, step, |_, _| {})
    }

    /// The states at `points` (increasing, within $[0, L]$): each
    /// integrated from the last point or the node before it, whichever is nearer.
    fn states(&self, points: &[f64]) -> Result<Vec<[f64; 4]>> {
        let l = self.flexure.length();
        let mut out = Vec::with_capacity(points.len());
        let mut last = self.nodes[0];
        let mut step = 0.0;
        for (i, &s) in points.iter().enumerate() {
            if !(s.is_finite() && (0.0..=l).contains(&s)) || (i > 0 && s < points[i - 1]) {
                return Err(Error::invalid("s", s, "must increase within the flexure, from 0 to its length"));
            }
            let j = self.nodes.partition_point(|n| n.0 <= s).max(1) - 1;
            if last.0 < self.nodes[j].0 || last.0 > s {
                last = self.nodes[j];
            }
            last = (s, self.advance(last, s, &mut step)?);
            out.push(last.1);
        }
        Ok(out)
    }

    /// The cross-section at `s` from its state.
    fn point(&self, s: f64, y: &[f64; 4]) -> Point {
        cross_section(self.flexure, s, y)
    }

    /// The cross-section at arc length `s` (m).
    pub fn at(&self, s: f64) -> Result<Point> {
        Ok(self.point(s, &self.states(&[s])?[0]))
    }

    /// The cross-sections at `points` (m, increasing within $[0, L]$).
    pub fn sample(&self, points: &[f64]) -> Result<Vec<Point>> {
        let states = self.states(points)?;
        Ok(points.iter().zip(&states).map(|(&s, y)| self.point(s, y)).collect())
    }

    /// The deformed flexure at `count` points evenly spaced in arc length,
    /// ends included (2 to 100 000 points).
    ///
    /// # Example
    /// ```
    /// use flexure::{reference::elastica::Trace, Flexure};
    /// let f = Flexure::new(1.0, 1.0, 3).unwrap();
    /// let shape = Trace::shot(&f, 0.0, 0.0, 0.0, &Default::default()).unwrap().shape(5).unwrap();
    /// assert_eq!(shape.len(), 5);
    /// assert!((shape[2].x - 0.5).abs() < 1e-15 && shape[4].s == 1.0);
    /// ```
    pub fn shape(&self, count: usize) -> Result<Vec<Point>> {
        if !(2..=100_000).contains(&count) {
            return Err(Error::invalid("count", count, "must be from 2 to 100000 points"));
        }
        let l = self.flexure.length();
        let points: Vec<f64> =
            (0..count).map(|i| if i + 1 == count { l } else { l * i as f64 / (count - 1) as f64 }).collect();
        self.sample(&points)
    }

    /// The peak bending stress along the flexure, $\max_s E^{\prime}\frac{h}{2}\frac{|m|}{EI}$;
    /// `None` for a section without thickness.
    pub fn peak_stress(&self) -> Result<Option<Peak>> {
        if self.flexure.section().modulus().is_none() {
            return Ok(None);
        }
        self.peak(|p| p.stress.unwrap_or(0.0)).map(Some)
    }

    /// The largest change of curvature from rest, $\max_s |m|/EI$ (1/m).
    pub fn peak_curvature(&self) -> Result<Peak> {
        self.peak(|p| p.curvature_change.abs())
    }

    /// The maximum of `g` along the flexure: a scan of evenly spaced
    /// points, the breakpoints and the nodes, then golden-section
    /// refinement between the best point's neighbours (bounded steps).
    fn peak(&self, g: impl Fn(&Point) -> f64) -> Result<Peak> {
        let l = self.flexure.length();
        let mut points: Vec<f64> = (0..=PEAK_SAMPLES).map(|k| l * k as f64 / PEAK_SAMPLES as f64).collect();
        points.extend(&self.stops);
        points.extend(self.nodes.iter().map(|n| n.0));
        points.retain(|s| (0.0..=l).contains(s));
        points.sort_by(f64::total_cmp);
        points.dedup();
        let states = self.states(&points)?;
        let values: Vec<f64> = points.iter().zip(&states).map(|(&s, y)| g(&self.point(s, y))).collect();
        let best = (0..points.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
        let top = Peak { value: values[best], at: points[best] };
        let from = best.saturating_sub(1);
        let base = (points[from], states[from]);
        let bracket = (points[from], points[(best + 1).min(points.len() - 1)]);
        crate::stress::refine(bracket, top, l, PEAK_REFINEMENTS, |s| {
            Ok(g(&self.point(s, &self.advance(base, s, &mut 0.0)?)))
        })
    }
}

/// The cross-section of `flexure` at `s` from its state $(\phi, m, x, y)$.
pub(super) fn cross_section(flexure: &Flexure, s: f64, y: &[f64; 4]) -> Point {
    let (f, l) = (flexure, flexure.length());
    let change = y[1] / f.ei_at(s);
    let section = f.section();
    let stress = section.modulus().zip(section.thickness(s / l, l)).map(|(e, h)| e * 0.5 * h * change.abs());
    Point {
        s,
        phi: y[0],
        x: y[2],
        y: y[3],
        moment: y[1],
        curvature: f.curvature(f.rest(), s) + change,
        curvature_change: change,
        stress,
    }
}
