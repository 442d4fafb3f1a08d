//! The three-stage Radau IIA method (order 5): its Butcher matrix, nodes,
//! and the weights of RADAU5's embedded error estimate (Hairer & Wanner,
//! *Solving ODEs II*, IV.5 and IV.8).

/// The three-stage Radau IIA tableau and its error estimate's weights.
pub(super) struct Radau {
    pub(super) a: [[f64; 3]; 3],
    /// $A^2$.
    pub(super) a2: [[f64; 3]; 3],
    pub(super) c: [f64; 3],
    /// $d_i$ of the embedded estimate.
    pub(super) d: [f64; 3],
    /// $\gamma_0$, the real eigenvalue of $A$.
    pub(super) gamma: f64,
}

impl Radau {
    pub(super) fn new() -> Self {
        let s6 = 6f64.sqrt();
        let a = [
            [(88.0 - 7.0 * s6) / 360.0, (296.0 - 169.0 * s6) / 1800.0, (-2.0 + 3.0 * s6) / 225.0],
            [(296.0 + 169.0 * s6) / 1800.0, (88.0 + 7.0 * s6) / 360.0, (-2.0 - 3.0 * s6) / 225.0],
            [(16.0 - s6) / 36.0, (16.0 + s6) / 36.0, 1.0 / 9.0],
        ];
        let mut a2 = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                a2[i][j] = (0..3).map(|k| a[i][k] * a[k][j]).sum();
            }
        }
        let c = [(4.0 - s6) / 10.0, (4.0 + s6) / 10.0, 1.0];
        let d = [-(13.0 + 7.0 * s6) / 3.0, (-13.0 + 7.0 * s6) / 3.0, -1.0 / 3.0];
        let gamma = (6.0 + 81f64.cbrt() - 9f64.cbrt()) / 30.0;
        Self { a, a2, c, d, gamma }
    }
}
