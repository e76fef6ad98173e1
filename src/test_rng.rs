//! A seeded pseudo-random sequence for unit tests that scatter their
//! input (Knuth's MMIX linear congruential generator): the same numbers
//! on every run and machine, no dependency.

pub(crate) struct Lcg(u64);

impl Lcg {
    pub(crate) fn new(seed: u64) -> Lcg {
        Lcg(seed)
    }

    fn step(&mut self) -> u64 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        self.0
    }

    /// Uniform in [0, 1), from the top 53 bits.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.step() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// In 0..m, from the top 31 bits.
    pub(crate) fn below(&mut self, m: usize) -> usize {
        (self.step() >> 33) as usize % m
    }
}
