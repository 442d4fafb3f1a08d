//! What is not an error but must not pass without a word: closures open at
//! rest, whose closing preloads the mechanism, and parts that cross each
//! other in a solved shape (self-intersection; the model has no contact).
//!
//! The library prints nothing: each finding has a [`Severity`] and a
//! message, and the callers (the command line, Python) report them.
//!
//! **Open closures** ([`open_closures`]). A weld or pin *meets at rest*
//! when, with every joint at its rest coordinates, its two points are at
//! most [`GAP_TOLERANCE`] × [`Mechanism::size`](crate::mechanism::Mechanism::size) apart and (a weld) its two
//! frames' angles differ by at most [`GAP_TOLERANCE`] rad, the angle taken
//! to $(-\pi, \pi]$ as the closure equation takes it. One that does not
//! meet is closed by force before any load acts: the finding gives the gap
//! and the preload, the closure's multiplier (force in N, and moment in
//! N·m for a weld) in the unloaded, assembled configuration, that is, the
//! force the weld or pin carries with no external load. It is a warning,
//! or a note when the closure says `preload = true`.
//!
//! **Crossings** ([`crossings`]). Each flexure is its backbone
//! ([`crate::kinematics::backbone`]) as a polyline of chords; each body,
//! the ground included, the edges of the hull of its attachment points
//! ([`Mechanism::attachments`](crate::mechanism::Mechanism::attachments): what `flexure draw` fills as the link),
//! the ground's without its tendon anchors, which are separate points of
//! the world rather than corners of one part.
//! The backbone's curvature is at most $V/L$ everywhere, with
//! $V = \sum_i\lvert\alpha_i\rvert$ (each angle shape's slope is a shifted
//! Legendre polynomial, at most 1 in magnitude), so with
//! $\lceil V/\theta\rceil$ chords or more each chord turns by at most
//! $\theta$ = [`CHORD_TURN`] and stays within $h\theta/2$ of its arc, $h$ its
//! length (at least [`MIN_CHORDS`] chords, at most [`MAX_CHORDS`]): only a
//! crossing shallower than that is missed. Two segments cross when they
//! share a point (within [`TOUCH_TOLERANCE`] × the mechanism's size), a
//! collinear overlap included. Parts that a joint or a closure connects
//! meet at their ends (a flexure's root on its parent link, its tip on its
//! child, two legs on a stage welded to one of them, links on either side
//! of a revolute joint, a slider's carriage on its rail): a contact there,
//! at a point that is an end of both parts (a link's attachment points or
//! the origin of a body it carries by a revolute, prismatic or fixed joint;
//! a flexure's root and tip), is not a crossing, unless it is a collinear
//! overlap that runs on from there. A flexure's
//! non-consecutive chords are tested against each other too (a loop).

pub(in crate::mechanism) mod closures;
mod convex;
mod crossing;
mod geometry;

pub use closures::{GAP_TOLERANCE, OpenClosure, closure_name, open_closures, rest_gaps};
pub use convex::{Convex, MAX_ITERATIONS, within};
pub(crate) use crossing::hull_points;
pub use crossing::{
    CHORD_TURN, Crossing, MAX_CHORDS, MIN_CHORDS, Part, TOUCH_TOLERANCE, chords, crossings, crossings_along,
};
pub use geometry::{Contact, hull, segments_meet};

/// How much a finding matters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Something is likely wrong with the answer or the file.
    Warning,
    /// Something the file says is meant (a closure with `preload = true`).
    Note,
}
