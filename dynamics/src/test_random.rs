//! The unit tests' pseudo-random numbers: xorshift64, reproducible from a seed, no dependency.

/// Numbers uniform in [0, 1) from `seed` (nonzero).
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
