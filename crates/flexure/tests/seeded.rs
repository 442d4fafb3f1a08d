//! Seeded random numbers for the tests (xorshift64*): random cases that
//! every run repeats, without a dependency.

/// A seeded generator of numbers in [−1, 1).
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// `n` numbers, the i-th within `scale`/(i + 1): coefficients that fall
    /// with their order, as a flexure's do.
    pub fn vec(&mut self, n: usize, scale: f64) -> Vec<f64> {
        (0..n).map(|i| scale * self.next() / (i + 1) as f64).collect()
    }
}
