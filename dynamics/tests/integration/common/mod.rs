//! Shared by the integration tests (of `dynamics`, and of `scenarios`, which includes this file): a macro that
//! instantiates generic tests for both algebras, and a deterministic random source.

/// Instantiates generic test functions `fn name<A: Algebra>()` as `pga::name` and `cga::name`.
#[macro_export]
macro_rules! for_both_algebras {
    ($($test:ident),* $(,)?) => {
        mod pga { $( #[test] fn $test() { super::$test::<dynamics::Pga>(); } )* }
        mod cga { $( #[test] fn $test() { super::$test::<dynamics::Cga>(); } )* }
    };
}

/// A deterministic xorshift source of numbers in [−1, 1).
pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Self {
        Random(seed.max(1))
    }

    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    pub fn vector(&mut self, scale: f64) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.next(), self.next(), self.next()) * scale
    }

    pub fn rotation(&mut self) -> nalgebra::UnitQuaternion<f64> {
        // A uniformly spread axis-angle up to π.
        nalgebra::UnitQuaternion::from_scaled_axis(self.vector(std::f64::consts::PI / 3f64.sqrt()))
    }
}
