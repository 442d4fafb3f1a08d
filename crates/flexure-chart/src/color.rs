//! Colours: the categorical ones that tell curves and shapes apart, and
//! the sequential map of a quantity (stress) from 0 to 1.

/// An opaque colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    pub(crate) fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// This colour mixed toward white by `t` (0: unchanged, 1: white).
    pub fn tint(self, t: f64) -> Color {
        let mix = |c: u8| (f64::from(c) + t.clamp(0.0, 1.0) * (255.0 - f64::from(c))).round() as u8;
        Color(mix(self.0), mix(self.1), mix(self.2))
    }
}

pub const BLACK: Color = Color(0, 0, 0);
pub const GRAY: Color = Color(140, 140, 140);

/// Categorical colours (Tableau 10), then black.
pub const COLORS: [Color; 6] =
    [Color(31, 119, 180), Color(214, 39, 40), Color(44, 160, 44), Color(148, 103, 189), Color(255, 127, 14), BLACK];

/// A sequential colour map for a quantity from 0 to 1: the dark four
/// fifths of matplotlib's *plasma* (blue, purple, red, orange), each end
/// visible on white and its lightness rising with the value.
pub(crate) const RAMP: [Color; 5] =
    [Color(13, 8, 135), Color(106, 0, 168), Color(177, 42, 144), Color(225, 100, 98), Color(252, 166, 54)];

/// The colour of `t` in [0, 1] (clamped) on the sequential map.
pub fn ramp(t: f64) -> Color {
    let x = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 } * (RAMP.len() - 1) as f64;
    let k = (x.floor() as usize).min(RAMP.len() - 2);
    let f = x - k as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    Color(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}
