//! The exact planar elastica touching rigid obstacles: point contacts,
//! frictionless or with Coulomb friction at the tip, found along the load
//! path by shooting with contact unknowns.
//!
//! One concept a file:
//!
//! - `obstacle.rs`: half-planes and circles, their gap and normal ([`Obstacle`]);
//! - `shooting.rs`: the elastica with a fixed set of contacts by multiple shooting;
//! - `path.rs`: the continuation in the load that opens, closes, sticks
//!   and slips contacts as it goes ([`contact`](fn@contact));
//! - `solution.rs`: what it returns ([`ContactSolution`]).

mod obstacle;
mod path;
mod shooting;
mod solution;

pub use obstacle::{Obstacle, ObstacleShape};
pub use path::contact;
pub use solution::{ContactEvent, ContactPoint, ContactSolution, ContactState, ContactStop, EventKind};
