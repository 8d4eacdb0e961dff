//! The harness shared by the benchmarks: deterministic inputs, batch timing and a correctness check
//! run before timing.

use std::hint::black_box;

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion};

/// Every benchmark maps a batch of this many inputs; criterion reports time per batch.
pub const BATCH: usize = 1024;

/// SplitMix64: a tiny deterministic generator, so that every run times the same inputs.
pub struct Random(pub u64);

impl Random {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [−1, 1).
    pub fn signed_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    pub fn array<const N: usize>(&mut self) -> [f64; N] {
        std::array::from_fn(|_| self.signed_unit())
    }

    /// A rotation about a random axis and a translation within [−10, 10)³.
    pub fn isometry(&mut self) -> Isometry3<f64> {
        let [w, x, y, z] = self.array();
        let rotation = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
        let [tx, ty, tz] = self.array::<3>().map(|t| 10.0 * t);
        Isometry3::from_parts(Translation3::new(tx, ty, tz), rotation)
    }

    /// A point within [−10, 10)³.
    pub fn point(&mut self) -> Point3<f64> {
        Point3::from(self.array::<3>().map(|x| 10.0 * x))
    }
}

/// Fails the benchmark if two results differ: what is timed must compute the same thing.
pub fn assert_close(got: &[f64], expected: &[f64], what: &str) {
    let error = got.iter().zip(expected).map(|(g, e)| (g - e).abs()).fold(0.0, f64::max);
    assert!(error < 1e-9, "{what}: got {got:?}, expected {expected:?}");
}

/// Times `operation` over every input of the batch, writing into a reused output buffer.
pub fn time_batch<In: Copy, Out: Copy>(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    inputs: &[In],
    operation: impl Fn(In) -> Out,
) {
    let mut outputs = vec![operation(inputs[0]); inputs.len()];
    group.bench_function(name, |bencher| {
        bencher.iter(|| {
            for (output, &input) in outputs.iter_mut().zip(black_box(inputs)) {
                *output = operation(input);
            }
            black_box(&mut outputs);
        })
    });
}
