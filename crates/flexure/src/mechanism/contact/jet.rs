//! A contact's gap as a function of the coordinates $q$ and of the arc
//! length $s$ where it sits on a flexure, with its first and second
//! derivatives: the row a touching contact adds to the equilibrium
//! equations, and its stiffness.
//!
//! The toucher's point $x(q, s)$ is a flexure's centreline point (its root
//! frame's placement times [`Touch::section_jet`]) or a corner's centre
//! (a ball of radius $r \ge 0$ between two geoms, [`super::corners`]), and
//! the gap is $g = d(y) - h$, $y = T_G^{-1}x$ in the frame of the geom's
//! shape, $d$ its signed distance. With $\Delta_c = \partial_c x - \partial_c x_G$
//! the point's velocity relative to the geom's body (the body's material
//! point at $x$) per unit $q_c$, and $n$ the world normal,
//! $$\partial_c g = n\cdot\Delta_c,\qquad
//!   \partial_b\partial_c g = n\cdot\big(\partial_{bc}x - \partial_{bc}x_G -
//!   \omega^G_c\times\Delta_b - \omega^G_b\times\Delta_c\big) + \Delta_b^T\nabla^2d\thinspace\Delta_c,$$
//! $\omega^G$ the geom body's angular velocity per coordinate and $\nabla^2 d$
//! the shape's curvature ([`super::GeomShape::curvature`], turned to the world). In
//! $s$, $\partial_s x = t$ (the unit tangent), so $\partial_s g = n\cdot t - h^{\prime}$.

use super::{Pair, Touch, Toucher, Turn, dot, named};
use crate::error::{Error, Result};
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::{Attached, FrameChain, Frames, add_attached_hessian, attach_into};
use nalgebra::DMatrix;
use std::borrow::Cow;

/// A pair's gap at $(q, s)$ with its derivatives ([`gap_jet`]); $n$ the mechanism's coordinates.
#[derive(Debug, Clone)]
pub struct GapJet<D: Touch> {
    /// $g$ (m): positive apart, negative overlapping.
    pub gap: f64,
    /// The toucher's surface point nearest the geom (world frame).
    pub point: D::Point,
    /// The geom's outward unit normal there (world frame).
    pub normal: D::Vector,
    /// $\partial g/\partial q$ ($n$ entries).
    pub gradient: Vec<f64>,
    /// $\partial^2 g/\partial q^2$ ($n\times n$).
    pub hessian: DMatrix<f64>,
    /// $\partial g/\partial s$ (0 for two geoms).
    pub ds: f64,
    /// $\partial^2 g/\partial q\thinspace\partial s$ ($n$ entries; 0 for two geoms).
    pub dqs: Vec<f64>,
    /// $\partial^2 g/\partial s^2$ (1/m; 0 for two geoms).
    pub dss: f64,
    /// $\partial n/\partial q_c = \nabla^2d\thinspace\Delta_c + \omega^G_c\times n$, one per coordinate (world).
    pub normal_jacobian: Vec<D::Vector>,
    /// $\partial n/\partial s = \nabla^2d\thinspace t$ (world, 1/m; 0 for two geoms).
    pub normal_ds: D::Vector,
    /// The flexure's unit tangent there (world; 0 for two geoms).
    pub tangent: D::Vector,
    /// The flexure's section axes there (world, tangent first; empty for two geoms).
    pub frame: Vec<D::Vector>,
    /// The half thickness it touches with (m): the point is $h$ off its centreline (a ball's radius).
    pub half: f64,
}

/// The flexure side of a pair: its joint, first coordinate, root frame and jet at $s$.
struct Own<'a, D: Touch> {
    offset: usize,
    root: &'a D::Pose,
    jet: super::SectionJet<D>,
}

/// The gap of `pair` of `m` at coordinates `q`, frames `f` (at them, with
/// their Jacobian level) and, for a flexure, arc length `s` (m), with its
/// derivatives in $q$ and $s$ (see the module docs). Two geoms at their
/// corner, as [`super::gap()`] takes it; two geoms without corners are refused by name.
///
/// # Example
/// ```
/// use flexure::mechanism::contact::{gap_jet, pairs};
/// use flexure::mechanism::kinematics::frames;
/// // A strip 0.1 m long along x, and a floor 5 mm below it.
/// let m = flexure::mechanism::file::from_toml(r#"
/// [[joint]]
/// name = "strip"
/// kind = "flexure"
/// parent = "ground"
/// child = "tip"
/// length = 0.1
/// ei = 1e-3
/// [[geom]]
/// body = "ground"
/// shape = "plane"
/// origin = [0.0, -0.005]
/// normal = [0.0, 1.0]
/// "#).unwrap();
/// let q = m.rest();
/// let g = gap_jet(&m, &frames(&m, &q), &q, &pairs(&m)[0], Some(0.1)).unwrap();
/// // The tip's height moves by L/2 per unit of the first coordinate (Eq. 11).
/// assert!((g.gap - 0.005).abs() < 1e-15 && (g.gradient[0] - 0.05).abs() < 1e-15);
/// ```
pub fn gap_jet<D: Touch + FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    q: &[f64],
    pair: &Pair,
    s: Option<f64>,
) -> Result<GapJet<D>> {
    let n = m.dof();
    let p = point_jet(m, f, q, pair, s, None)?;
    let (slope, curvature) = first_order(f, &p);
    let GapSlope { gap, point, normal, gradient, ds, dss } = slope;
    let delta = &p.delta;
    let mut hessian = p.hessian_along(m, f, &normal);
    let bilinear = |a: &D::Vector, b: &D::Vector| quadratic::<D>(&curvature, a, b);
    for b in 0..n {
        for c in 0..n {
            hessian[(b, c)] += bilinear(&delta[b], &delta[c]);
        }
    }
    // The geom's turning turns its normal: −n·(ω^G_c × Δ_b) − n·(ω^G_b × Δ_c).
    for &c in &p.geom_columns {
        for b in 0..n {
            let v = D::triple(&normal, &f.omega[c], &delta[b]);
            hessian[(b, c)] -= v;
            hessian[(c, b)] -= v;
        }
    }
    let mut dqs = vec![0.0; n];
    let (mut normal_ds, tangent) = (D::Vector::default(), p.tangent().unwrap_or_default());
    if let Some(own) = &p.own {
        let t = D::rotate(own.root, &own.jet.tangent);
        normal_ds = product::<D>(&curvature, &t);
        for c in 0..n {
            dqs[c] = bilinear(&delta[c], &t);
        }
        for (a, dt) in own.jet.tangent_jacobian.iter().enumerate() {
            dqs[own.offset + a] += dot::<D>(&normal, &D::rotate(own.root, dt));
        }
        for &b in &columns(m, &p.att) {
            dqs[b] += dot::<D>(&normal, &D::spin(&f.omega[b], &t));
        }
        for &c in &p.geom_columns {
            dqs[c] -= D::triple(&normal, &f.omega[c], &t);
        }
    }
    let mut normal_jacobian: Vec<D::Vector> = delta.iter().map(|v| product::<D>(&curvature, v)).collect();
    for &c in &p.geom_columns {
        normal_jacobian[c] = normal_jacobian[c] + D::spin(&f.omega[c], &normal);
    }
    if let Some(turn) = &p.turn {
        normal_jacobian = turned(m, f, &p, turn, &mut hessian);
    }
    Ok(GapJet {
        gap,
        point,
        normal,
        gradient,
        hessian,
        ds,
        dqs,
        dss,
        normal_jacobian,
        normal_ds,
        tangent,
        frame: p.frame(),
        half: p.half[0],
    })
}

/// A pair's gap at $(q, s)$ to first order in $q$ ([`gap_slope`]): what
/// motion needs of a touching contact at each stage.
#[derive(Debug, Clone)]
pub struct GapSlope<D: Touch> {
    /// $g$ (m): positive apart, negative overlapping.
    pub gap: f64,
    /// The toucher's surface point nearest the geom (world frame).
    pub point: D::Point,
    /// The geom's outward unit normal there (world frame).
    pub normal: D::Vector,
    /// $\partial g/\partial q$ ($n$ entries).
    pub gradient: Vec<f64>,
    /// $\partial g/\partial s$ (0 for two geoms).
    pub ds: f64,
    /// $\partial^2 g/\partial s^2$ (1/m; 0 for two geoms).
    pub dss: f64,
}

/// [`gap_jet`] without its second derivatives in $q$: the gap of `pair`
/// at `q` (frames `f` at Jacobian level) and `s`, its gradient
/// $\partial_cg = n\cdot\Delta_c$, and its first two derivatives in $s$.
///
/// # Example
/// ```
/// use flexure::kinematics::Level;
/// use flexure::mechanism::contact::{gap_jet, gap_slope, pairs};
/// use flexure::mechanism::kinematics::{frames, frames_level_into, Frames};
/// let m = flexure::mechanism::file::from_toml("[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nei = 1e-3\n\
///     [[geom]]\nbody = \"ground\"\nshape = \"circle\"\norigin = [0.05, -0.01]\nradius = 0.005\n").unwrap();
/// let q = [0.1, -0.05, 0.02];
/// let mut f = Frames::new(&m);
/// frames_level_into(&m, &q, Level::Jacobian, &mut f);
/// let (slope, jet) = (gap_slope(&m, &f, &q, &pairs(&m)[0], Some(0.04)).unwrap(), gap_jet(&m, &frames(&m, &q), &q, &pairs(&m)[0], Some(0.04)).unwrap());
/// assert_eq!((slope.gap, slope.gradient, slope.ds, slope.dss), (jet.gap, jet.gradient, jet.ds, jet.dss));
/// ```
pub fn gap_slope<D: Touch + FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    q: &[f64],
    pair: &Pair,
    s: Option<f64>,
) -> Result<GapSlope<D>> {
    Ok(first_order(f, &point_jet(m, f, q, pair, s, None)?).0)
}

/// [`gap_slope`] of a pair of two geoms against `surface` (a plane fixed in
/// the body of the geom touched) in place of that geom: a corner held on a
/// face keeps the face's plane past its edges, so its gap stays smooth up
/// to where it is let go.
pub(crate) fn gap_slope_on<D: Touch + FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    q: &[f64],
    pair: &Pair,
    surface: super::Geom<D>,
) -> Result<GapSlope<D>> {
    let mut p = point_jet(m, f, q, pair, None, None)?;
    p.shape = Cow::Owned(surface);
    Ok(first_order(f, &p).0)
}

/// The gap's value, normal, gradient and derivatives in $s$ from its point's
/// jet, with the shape's curvature turned to the world.
fn first_order<D: Touch + FrameChain>(f: &Frames<D>, p: &PointJet<D>) -> (GapSlope<D>, super::DistanceHessian) {
    let shape = &p.shape;
    let frame = D::compose(&f.bodies[shape.body], &shape.frame);
    let (d, normal) = shape.gap(&f.bodies[shape.body], &p.x, 0.0);
    let y = D::position(&D::act(&D::inverse(&frame), &p.x));
    let curvature = world_curvature::<D>(&frame, &shape.shape.curvature(&y));
    let gradient: Vec<f64> = p.delta.iter().map(|v| dot::<D>(&normal, v)).collect();
    let (mut ds, mut dss) = (0.0, 0.0);
    if let Some(own) = &p.own {
        let t = D::rotate(own.root, &own.jet.tangent);
        ds = dot::<D>(&normal, &t) - p.half[1];
        dss = dot::<D>(&normal, &D::rotate(own.root, &own.jet.bend)) + quadratic::<D>(&curvature, &t, &t) - p.half[2];
    }
    let point = D::moved(&p.x, &normal, -p.half[0]);
    (GapSlope { gap: d - p.half[0], point, normal, gradient, ds, dss }, curvature)
}

/// A toucher's point $x$ (a flexure's centreline point at $s$, or a
/// ball's centre) and its motion relative to a material point $a$ of the
/// geom's body: $\Delta_c = \partial_c x - \partial_c a$
/// ([`point_jet`]); $a$ is where $x$ is unless anchored elsewhere.
pub(crate) struct PointJet<'a, D: Touch + FrameChain> {
    /// $x$ (world).
    pub x: D::Point,
    /// $\Delta_c$ for each coordinate (world).
    pub delta: Vec<D::Vector>,
    /// The toucher's half thickness and its first two derivatives in $s$.
    pub half: [f64; 3],
    /// A material point's offset from the centreline (world; 0 unless asked for).
    pub offset: D::Vector,
    /// The geom touched (of two edges crossing, the plane across them, [`super::crossing`]).
    pub shape: Cow<'a, super::Geom<D>>,
    /// The coordinates that move the geom's body.
    pub geom_columns: Vec<usize>,
    att: Attached<D>,
    attg: Attached<D>,
    moving: bool,
    own: Option<Own<'a, D>>,
    /// Of two edges crossing, how their normal turns.
    turn: Option<Turn>,
}

/// The point of `pair`'s toucher at `q` (frames `f`, Jacobian level) and
/// $s$, with its motion relative to the geom body's material point at
/// `anchor` (in the body's frame), or at the point itself when `None`.
pub(crate) fn point_jet<'a, D: Touch + FrameChain>(
    m: &'a Mechanism<D>,
    f: &'a Frames<D>,
    q: &[f64],
    pair: &Pair,
    s: Option<f64>,
    anchor: Option<D::Vector>,
) -> Result<PointJet<'a, D>> {
    jet_at(m, f, q, pair, (s, [0.0; 3]), None, anchor)
}

/// Where on a toucher a material point is: a flexure's arc length (m) and
/// the point's offset from its centreline in the section's axes (m,
/// tangent first; [`super::offset_jet`]), or the point in a ball's body
/// frame (its first three entries).
pub(crate) type Material = [f64; 4];

/// A ball's material point `p` (its body's frame) as a [`Material`].
pub(crate) fn on_ball(p: [f64; 3]) -> Material {
    [p[0], p[1], p[2], 0.0]
}

/// [`point_jet`] of a material point of the toucher ([`Material`]): a
/// flexure's section at `on[0]` (its arc length), the point off the
/// centreline by `on[1..]` in the section's axes (on a strip's surface), or
/// the point `on[..3]` of a ball's body (its frame),
/// relative to the geom body's material point `anchor` (its frame). A
/// stuck contact that rolls pins these two.
pub(crate) fn material_jet<'a, D: Touch + FrameChain>(
    m: &'a Mechanism<D>,
    f: &'a Frames<D>,
    q: &[f64],
    pair: &Pair,
    on: &Material,
    anchor: D::Vector,
) -> Result<PointJet<'a, D>> {
    match pair.part {
        Toucher::Flexure(_) => jet_at(m, f, q, pair, (Some(on[0]), [on[1], on[2], on[3]]), None, Some(anchor)),
        Toucher::Geom(_) => {
            let ball = super::vector::<D>(&[on[0], on[1], on[2]]);
            jet_at(m, f, q, pair, (None, [0.0; 3]), Some(ball), Some(anchor))
        }
    }
}

/// [`point_jet`], of a flexure's section's material point `offset` off
/// its centreline, or of the ball's material point `ball` (its body's
/// frame) rather than its centre.
fn jet_at<'a, D: Touch + FrameChain>(
    m: &'a Mechanism<D>,
    f: &'a Frames<D>,
    q: &[f64],
    pair: &Pair,
    (s, offset): (Option<f64>, [f64; 3]),
    ball: Option<D::Vector>,
    anchor: Option<D::Vector>,
) -> Result<PointJet<'a, D>> {
    let n = m.dof();
    let mut att = Attached::new(m);
    let mut turn = None;
    let (shape, x, half, own, moved) = match pair.part {
        Toucher::Flexure(j) => {
            let joint = &m.joints[j];
            let Some(flexure) = joint.kind.flexure() else {
                return Err(Error::invalid("pair", named(m, pair), "names a joint that is not a flexure"));
            };
            let s = s.ok_or_else(|| Error::invalid("s", "none", "is needed where a flexure touches"))?;
            let k = joint.kind.joint().dof();
            let centre = D::section_jet(flexure, &q[joint.offset..joint.offset + k], s)?;
            let jet = super::offset_jet(&centre, offset);
            let local = D::moved(&D::origin(&D::identity()), &jet.point, 1.0);
            attach_into(m, f, joint.parent, D::position(&D::act(&joint.origin, &local)), true, &mut att);
            let root = &f.roots[j];
            let (half, moved) = (jet.half, D::rotate(root, &(jet.point - centre.point)));
            let own = Some(Own { offset: joint.offset, root, jet });
            (Cow::Borrowed(&m.geoms[pair.geom]), D::act(root, &local), half, own, moved)
        }
        Toucher::Geom(_) => {
            let c = super::corner(m, pair)?;
            let (centre, shape) = match c.held(&f.bodies) {
                Some(k) => {
                    turn = k.turn;
                    (k.centre, Cow::Owned(k.surface))
                }
                None => (c.centre, c.against(&f.bodies)),
            };
            let centre = ball.unwrap_or(centre);
            attach_into(m, f, c.round.body, centre, true, &mut att);
            let x = D::act(&f.bodies[c.round.body], &D::moved(&D::origin(&D::identity()), &centre, 1.0));
            (shape, x, [c.radius, 0.0, 0.0], None, D::Vector::default())
        }
    };
    let moving = m.parent_joint(shape.body).is_some();
    let mut attg = Attached::new(m);
    if moving {
        let local = anchor.unwrap_or_else(|| D::position(&D::act(&D::inverse(&f.bodies[shape.body]), &x)));
        attach_into(m, f, shape.body, local, true, &mut attg);
    }
    let mut delta: Vec<D::Vector> = (0..n).map(|c| att.linear(c) - attg.linear(c)).collect();
    if let Some(own) = &own {
        for (a, p) in own.jet.jacobian.iter().enumerate() {
            delta[own.offset + a] = delta[own.offset + a] + D::rotate(own.root, p);
        }
    }
    let geom_columns = columns(m, &attg);
    Ok(PointJet { x, delta, half, offset: moved, shape, geom_columns, att, attg, moving, own, turn })
}

impl<D: Touch + FrameChain> PointJet<'_, D> {
    /// A flexure's unit tangent at the point (world); `None` for a ball.
    pub fn tangent(&self) -> Option<D::Vector> {
        self.own.as_ref().map(|o| D::rotate(o.root, &o.jet.tangent))
    }

    /// A flexure's section axes at the point (world, tangent first); empty for a ball.
    pub fn frame(&self) -> Vec<D::Vector> {
        self.own.as_ref().map_or(Vec::new(), |o| o.jet.frame.iter().map(|e| D::rotate(o.root, e)).collect())
    }

    /// $w\cdot\partial_b\partial_c(x - a)$ for a fixed world vector $w$,
    /// $a$ the material point of the geom's body where it is anchored.
    pub fn hessian_along(&self, m: &Mechanism<D>, f: &Frames<D>, w: &D::Vector) -> DMatrix<f64> {
        let n = m.dof();
        let mut hessian = DMatrix::zeros(n, n);
        add_attached_hessian(m, f, &self.att, w, &mut hessian);
        if self.moving {
            add_attached_hessian(m, f, &self.attg, &(D::Vector::default() - *w), &mut hessian);
        }
        if let Some(own) = &self.own {
            let k = own.jet.jacobian.len();
            // Within the flexure: w·R ∂²p/∂α², with w in its root frame.
            let local = normal_in::<D>(own.root, w);
            for a in 0..k {
                for b in 0..k {
                    let v: f64 = (0..D::POINT_DIM).map(|i| local[i] * own.jet.hessian[i][(a, b)]).sum();
                    hessian[(own.offset + a, own.offset + b)] += v;
                }
            }
            // With the joints below it: w·(ω_b × ∂_a x).
            for &b in &columns(m, &self.att) {
                for a in 0..k {
                    let v = D::triple(w, &f.omega[b], &D::rotate(own.root, &own.jet.jacobian[a]));
                    hessian[(own.offset + a, b)] += v;
                    hessian[(b, own.offset + a)] += v;
                }
            }
        }
        hessian
    }
}

/// Of two edges crossing ([`super::crossing`]), the gap's Hessian turned
/// from the plane's, fixed in the touched geom's body, to the lines':
/// their normal $\hat n = \sigma(a\times b)/\lvert a\times b\rvert$ turns
/// with both bodies, $\partial_c\hat n = \sigma(I - \hat n\hat n^T)\partial_c(a\times b)/\lvert a\times b\rvert$,
/// $\partial_c a = \omega^A_c\times a$, $\partial_c b = \omega^B_c\times b$, where the
/// plane's turns as $\partial_c n_p = \omega^B_c\times\hat n$. With $d$ the lines'
/// distance and $v_c = \Delta_c + d\thinspace\partial_c n_p$ the two nearest points'
/// relative velocity, $g = \hat n\cdot(x_A - x_B)$ for any two material points
/// of the lines gives
/// $$\partial_b\partial_c g - \partial_b\partial_c g_p =
/// (\partial_c\hat n - \partial_c n_p)\cdot v_b + (\partial_b\hat n - \partial_b n_p)\cdot v_c -
/// d(\partial_b\hat n\cdot\partial_c\hat n - \partial_b n_p\cdot\partial_c n_p).$$
/// Returns $\partial_c\hat n$ for each coordinate.
fn turned<D: Touch + FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    p: &PointJet<'_, D>,
    turn: &Turn,
    hessian: &mut DMatrix<f64>,
) -> Vec<D::Vector> {
    use super::crossing::{add, cross, dot as dot3, scale, sub};
    let n = m.dof();
    let (on_a, on_b) = (columns(m, &p.att), &p.geom_columns);
    let w = cross(turn.a, turn.b);
    let size = dot3(w, w).sqrt();
    let normal = scale(w, turn.sign / size);
    let spin = |c: usize, on: &[usize], v: [f64; 3]| match on.contains(&c) {
        true => super::array::<D>(&D::spin(&f.omega[c], &super::vector::<D>(&v))),
        false => [0.0; 3],
    };
    let dn: Vec<[f64; 3]> = (0..n)
        .map(|c| {
            let dw = add(cross(spin(c, &on_a, turn.a), turn.b), cross(turn.a, spin(c, on_b, turn.b)));
            scale(sub(dw, scale(normal, dot3(normal, dw))), turn.sign / size)
        })
        .collect();
    let dp: Vec<[f64; 3]> = (0..n).map(|c| spin(c, on_b, normal)).collect();
    let v: Vec<[f64; 3]> = (0..n).map(|c| add(super::array::<D>(&p.delta[c]), scale(dp[c], turn.distance))).collect();
    for b in 0..n {
        for c in 0..n {
            hessian[(b, c)] += dot3(sub(dn[c], dp[c]), v[b]) + dot3(sub(dn[b], dp[b]), v[c])
                - turn.distance * (dot3(dn[b], dn[c]) - dot3(dp[b], dp[c]));
        }
    }
    dn.iter().map(|d| super::vector::<D>(d)).collect()
}

/// The coordinates of the joints on `x`'s path.
fn columns<D: FrameChain>(m: &Mechanism<D>, x: &Attached<D>) -> Vec<usize> {
    x.path().iter().flat_map(|&j| m.joints[j].offset..m.joints[j].offset + m.joints[j].kind.joint().dof()).collect()
}

/// `v` (world) in the frame `pose`.
fn normal_in<D: Touch>(pose: &D::Pose, v: &D::Vector) -> D::Vector {
    D::rotate(&D::inverse(pose), v)
}

/// $a^TCb$.
fn quadratic<D: Touch>(c: &super::DistanceHessian, a: &D::Vector, b: &D::Vector) -> f64 {
    (0..D::POINT_DIM).map(|i| (0..D::POINT_DIM).map(|j| a[i] * c[i][j] * b[j]).sum::<f64>()).sum()
}

/// $Cv$.
fn product<D: Touch>(c: &super::DistanceHessian, v: &D::Vector) -> D::Vector {
    let mut out = D::Vector::default();
    for i in 0..D::POINT_DIM {
        out[i] = (0..D::POINT_DIM).map(|j| c[i][j] * v[j]).sum();
    }
    out
}

/// $RCR^T$: a shape's curvature in its frame turned to the world by `frame`'s rotation.
fn world_curvature<D: Touch>(frame: &D::Pose, c: &super::DistanceHessian) -> super::DistanceHessian {
    let axes: Vec<D::Vector> = (0..D::POINT_DIM)
        .map(|i| {
            let mut e = D::Vector::default();
            e[i] = 1.0;
            D::rotate(frame, &e)
        })
        .collect();
    let mut out = [[0.0; 3]; 3];
    for (a, ra) in axes.iter().enumerate() {
        for (b, rb) in axes.iter().enumerate() {
            for i in 0..D::POINT_DIM {
                for j in 0..D::POINT_DIM {
                    out[i][j] += ra[i] * c[a][b] * rb[j];
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Level;
    use crate::mechanism::contact::{Geom, GeomShape, corner, pairs};
    use crate::mechanism::kinematics::frames_level_into;
    use nalgebra::{Isometry3, Vector3};

    /// A corner held on a face's plane ([`gap_slope_on`]): the gradient of
    /// its gap against central differences of the gap (step 1e-6, to 1e-8),
    /// for a box's corner on a lid (prismatic carriage, revolute lid) against
    /// a plane fixed in the ground, and a rail's corner on the ground against
    /// a plane fixed in the turning lid.
    #[test]
    fn a_corner_held_on_a_planes_gap_gradient_matches_differences() {
        let m = crate::mechanism::file::spatial_from_toml(
            "dimension = 3\n[[joint]]\nname = \"carriage\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"cart\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 100.0\n\
             [[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"cart\"\nchild = \"lid\"\naxis = [1.0, 0.0, 0.0]\nstiffness = 0.5\n\
             [[geom]]\nname = \"block\"\nbody = \"lid\"\nshape = \"box\"\norigin = [0.0, 0.08, 0.0]\nrpy = [0.0, 0.7853981633974483, 0.0]\nhalf_extents = [0.01, 0.02, 0.005]\n\
             [[geom]]\nname = \"rail\"\nbody = \"ground\"\nshape = \"box\"\norigin = [0.0, 0.09, -0.04]\nhalf_extents = [0.1, 0.002, 0.01]\n",
        )
        .unwrap();
        let q = [0.05, -0.3];
        let normal = Vector3::new(0.3, -0.4, 1.0).normalize();
        for k in [0, 8] {
            let pair = pairs(&m).into_iter().find(|p| p.corner == k).unwrap();
            let body = corner(&m, &pair).unwrap().flat.body;
            let plane = Geom::new("", body, Isometry3::translation(0.01, 0.08, -0.03), GeomShape::Plane { normal });
            let slope = |q: &[f64]| {
                let mut f = Frames::new(&m);
                frames_level_into(&m, q, Level::Jacobian, &mut f);
                gap_slope_on(&m, &f, q, &pair, plane.clone()).unwrap()
            };
            let at = slope(&q);
            assert!(at.gradient.iter().all(|g| g.abs() > 1e-3), "corner {k}: {:?}", at.gradient);
            for c in 0..2 {
                let (mut up, mut down) = (q, q);
                (up[c], down[c]) = (q[c] + 1e-6, q[c] - 1e-6);
                let difference = (slope(&up).gap - slope(&down).gap) / 2e-6;
                assert!(
                    (at.gradient[c] - difference).abs() < 1e-8,
                    "corner {k}, coordinate {c}: {} against {difference}",
                    at.gradient[c]
                );
            }
        }
    }
}
