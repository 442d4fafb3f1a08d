//! Exact Euler–Bernoulli references, kept apart from the model so that
//! users (and our tests) can measure the model's error against them.
//!
//! - [`elastica`]: the large-deflection elastica (Eq. 3) solved by shooting;
//! - [`compliance`]: the compliance ODE (Eq. 34);
//! - [`euler`]: Euler's closed-form buckling loads.
//! - [`vibration`]: linear vibration of the straight beam by shooting on the frequency.

pub mod compliance;
pub mod elastica;
pub mod euler;
pub mod vibration;
