//! Moving screws from a body's frame to the world, three ways, in each algebra: the hand-written
//! `motor::ScrewFrame` (a 3×3 rotation and the position from the motor's coordinates, then `(Ql, Qt + c⨯Ql)`), the
//! fused sandwich `m * s * ~m` emitted by `algebra!`, and the emitted 6×6 linear map of that sandwich
//! (`moved_line_map` / `moved_screw_map`, then `apply`). Each is timed for one screw (the frame or map built for
//! it) and for eight screws sharing one motor (built once), the counts a joint evaluation sees.
//!
//! `cargo bench -p dynamics --bench screw_frames`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::motor::{from_pose, ScrewFrame};
use dynamics::{cga, pga, Algebra, Cga, Pga, ScrewCoordinates};
use nalgebra::{UnitQuaternion, Vector3};

/// A motor of a generic pose, and eight body screws.
fn inputs<A: Algebra>() -> (A::Motor, [ScrewCoordinates; 8]) {
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -1.1, 0.7));
    let motor = from_pose::<A>(Vector3::new(1.5, -2.0, 0.25), &turn);
    let screws = std::array::from_fn(|k| {
        let k = k as f64;
        ScrewCoordinates {
            l: Vector3::new(1.0 + k, -0.5 * k, 0.25),
            t: Vector3::new(0.1, k, -2.0 + 0.3 * k),
        }
    });
    (motor, screws)
}

/// The three ways for one algebra: the fused function and the map's builder and `apply` are the algebra's own.
fn bench_algebra<A: Algebra, Map>(
    c: &mut Criterion,
    fused: impl Fn(A::Motor, A::Screw) -> A::Screw,
    build: impl Fn(A::Motor) -> Map,
    apply: impl Fn(&Map, A::Screw) -> A::Screw,
) {
    let (motor, coordinates) = inputs::<A>();
    let screws = coordinates.map(A::screw);
    let mut group = c.benchmark_group(format!("screw frames/{}", A::NAME));
    group.bench_function("ScrewFrame, 1 screw", |b| {
        b.iter(|| A::screw(ScrewFrame::of::<A>(black_box(motor)).to_world(&black_box(coordinates[0]))))
    });
    group.bench_function("fused sandwich, 1 screw", |b| {
        b.iter(|| fused(black_box(motor), black_box(screws[0])))
    });
    group.bench_function("linear map, 1 screw", |b| {
        b.iter(|| apply(&build(black_box(motor)), black_box(screws[0])))
    });
    group.bench_function("ScrewFrame, 8 screws", |b| {
        b.iter(|| {
            let frame = ScrewFrame::of::<A>(black_box(motor));
            black_box(coordinates).map(|s| A::screw(frame.to_world(&s)))
        })
    });
    group.bench_function("fused sandwich, 8 screws", |b| {
        b.iter(|| {
            let motor = black_box(motor);
            black_box(screws).map(|s| fused(motor, s))
        })
    });
    group.bench_function("linear map, 8 screws", |b| {
        b.iter(|| {
            let map = build(black_box(motor));
            black_box(screws).map(|s| apply(&map, s))
        })
    });
    group.finish();
}

fn frames(c: &mut Criterion) {
    bench_algebra::<Pga, _>(
        c,
        pga::generated::moved_line,
        pga::generated::moved_line_map,
        pga::generated::MovedLineMap::apply,
    );
    bench_algebra::<Cga, _>(
        c,
        cga::generated::moved_screw,
        cga::generated::moved_screw_map,
        cga::generated::MovedScrewMap::apply,
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    targets = frames
}
criterion_main!(benches);
