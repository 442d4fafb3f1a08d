//! What is not an error but must not pass without a word: closures open at
//! rest, whose closing preloads the mechanism, and parts that cross each
//! other in a solved shape (self-intersection; parts touch only geoms, not each other).
//!
//! The library prints nothing: each finding has a [`Severity`] and a
//! message, and the callers (the command line, Python) report them.
//!
//! Both are written once over the dimension ([`Findings`], implemented for
//! the plane and space side by side): what differs is the frames, a
//! closure's angle, and the parts' geometry.
//!
//! **Open closures** ([`open_closures`]). A weld, pin or ball *meets at
//! rest* when, with every joint at its rest coordinates, its two points are
//! at most [`GAP_TOLERANCE`] × [`Mechanism::size`](crate::mechanism::Mechanism::size) apart and the angle it
//! holds ([`rest_gaps`]: a weld's between its frames, in the plane taken to
//! $(-\pi, \pi]$ as the closure equation takes it; in space also a pin's
//! between its axes) is at most [`GAP_TOLERANCE`] rad. One that does not
//! meet is closed by force before any load acts: the finding gives the gap
//! and the preload, the closure's multiplier (force in N, and moment in
//! N·m where it holds a turn) in the unloaded, assembled configuration,
//! that is, the force it carries with no external load. It is a warning,
//! or a note when the closure says `preload = true`.
//!
//! **Crossings** ([`crossings`]). Each flexure is drawn along its
//! centreline as chords: the backbone ([`crate::kinematics::backbone`]) in
//! the plane, the sections' centres ([`crate::spatial::shape`]) in space.
//! The centreline's curvature is at most $V/L$ everywhere, with
//! $V = \sum_i\lvert\alpha_i\rvert$ (each angle shape's slope is a shifted
//! Legendre polynomial, at most 1 in magnitude), so with
//! $\lceil V/\theta\rceil$ chords or more each chord turns by at most
//! $\theta$ = [`CHORD_TURN`] and stays within $h\theta/2$ of its arc, $h$ its
//! length (at least [`MIN_CHORDS`] chords, at most [`MAX_CHORDS`]): only a
//! crossing shallower than that is missed. Each body, the ground included,
//! is the edges of the hull of its attachment points
//! ([`Mechanism::attachments`](crate::mechanism::Mechanism::attachments): what `flexure draw` fills as the link),
//! the ground's without its tendon anchors, which are separate points of
//! the world rather than corners of one part. Parts that a joint or a
//! closure connects meet where they are joined (a flexure's root on its
//! parent link, its tip on its child, two legs on a stage welded to one of
//! them, links on either side of a hinge, slider, ball or weld): a contact
//! there, at a point that is an end of both parts (a link's attachment
//! points or the origin of a body it carries by a rigid joint; a flexure's
//! root and tip), is not a crossing.
//!
//! *In the plane* a part is its segments, with no thickness. Two segments
//! cross when they share a point (within [`TOUCH_TOLERANCE`] × the
//! mechanism's size), a collinear overlap included; a contact at a joint
//! is a crossing only if it is a collinear overlap that runs on from
//! there; separate points of contact are counted. A flexure's
//! non-consecutive chords are tested against each other too (a loop).
//!
//! *In space* two backbones almost never meet, so each part is a solid
//! with the thickness its file gives it: a flexure is its section swept
//! along its centreline, as convex pieces between the sections at the ends
//! of each chord (a rectangle's piece is the hull of its eight corners, a
//! circle's the hull of its two discs, of the larger diameter where it
//! tapers; a flexure given by its stiffnesses alone has no section, and is
//! its centreline); a link is its hull's edges with no thickness (for flat
//! points the sides of their polygon, otherwise the edges of their
//! polytope). Two pieces touch when they come within [`TOUCH_TOLERANCE`] ×
//! the mechanism's size of each other (the size held to 10⁴ of its
//! shortest flexure's length; [`within`], the Gilbert–Johnson–Keerthi
//! distance test). A part so far from the origin that rounding there
//! exceeds that tolerance (an origin of 1e30 m) cannot be told touching
//! from apart, and is not tested. Touching pieces that are neighbours on
//! both parts are one contact. With thickness the contact at a joint runs
//! on from it as far as the two solids overlap: a contact that holds a
//! piece of each whose centreline passes through a point that is an end of
//! both is that joint, not a crossing. A flexure is tested against itself
//! for pieces farther apart along it than twice its section's
//! half-diagonal (nearer ones could only meet in a bend tighter than the
//! section, a strain above one).

mod closures;
mod convex;
mod crossing;
mod dimension;
mod geometry;

pub use closures::{GAP_TOLERANCE, OpenClosure, closure_name, open_closures, rest_gaps};
pub use convex::{Convex, MAX_ITERATIONS, within};

pub use crossing::{
    CHORD_TURN, Crossing, CrossingAt, MAX_CHORDS, MIN_CHORDS, Part, PartGeometry, Piece, PlacedPart, TOUCH_TOLERANCE,
    chords, crossings, crossings_along,
};
pub use dimension::Findings;
pub use geometry::{Meeting, hull, segments_meet};

/// How much a finding matters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Something is likely wrong with the answer or the file.
    Warning,
    /// Something the file says is meant (a closure with `preload = true`).
    Note,
}
