//! What is not an error but must not pass without a word, in a spatial
//! mechanism, as the planar [`crate::mechanism::findings`] tells it: closures
//! open at rest ([`open_closures`]) and parts that cross in a solved shape
//! ([`crossings`]).
//!
//! **Crossings.** In the plane a flexure is its backbone; in space two
//! backbones almost never meet, so each part is a solid with the thickness
//! its file gives it:
//! - a spatial flexure is its section swept along its centreline, as
//!   convex pieces between the sections at the ends of each of its chords
//!   ([`chords`](crate::mechanism::findings::chords), the planar count:
//!   each chord turns by at most
//!   [`CHORD_TURN`](crate::mechanism::findings::CHORD_TURN)): a rectangle's
//!   piece is the hull of its eight corners, a circle's the hull of its two
//!   discs (of the larger diameter, where it tapers); a flexure given by its
//!   stiffnesses alone has no section, and is its centreline;
//! - a rigid body, the ground included, is the edges of the hull of its
//!   attachment points ([`SpatialMechanism::attachments`], what `flexure
//!   draw` fills as the link; the ground's without its tendon anchors,
//!   separate points of the world), with no thickness: for flat points the sides
//!   of their polygon, as the planar links' outline, otherwise the edges of
//!   their polytope.
//!
//! Two pieces touch when they come within
//! [`TOUCH_TOLERANCE`](crate::mechanism::findings::TOUCH_TOLERANCE) × the
//! mechanism's size of each other (the size held to 10⁴ of its shortest
//! flexure's length; [`within`](crate::mechanism::findings::within),
//! the Gilbert–Johnson–Keerthi distance test). A part so far from the
//! origin that rounding there exceeds that tolerance (an origin of 1e30 m)
//! cannot be told touching from apart, and is not tested. Touching pieces that are
//! neighbours on both parts are one contact. Parts that a joint or a
//! closure connects (a flexure and the bodies at its ends, two flexures on
//! one body, bodies on either side of a hinge, slider, ball or weld) meet
//! where they are joined, and with thickness that contact runs on from the
//! joint as far as the two solids overlap: a contact that holds a piece of
//! each whose centreline passes through a point that is an end of both
//! (a flexure's root or tip, a link's attachment point, the origin of a
//! body it carries by a rigid joint) is that joint, not a crossing. A
//! flexure is tested against itself for pieces farther apart along it than
//! twice its section's half-diagonal (nearer ones could only meet in a
//! bend tighter than the section, a strain above one).
//!
//! [`SpatialMechanism::attachments`]: crate::mechanism::spatial::SpatialMechanism::attachments

mod closures;
mod crossing;

pub use crate::mechanism::findings::closure_name;
pub use closures::{open_closures, rest_gaps};
pub use crossing::{SpatialCrossing, crossings, crossings_along, describe};
