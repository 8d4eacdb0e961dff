//! CPU time of whole runs with adaptive steps against the best fixed step at equal error
//! ([`scenarios::equal_error::EQUAL_ERROR`]: scene 1, M1, the 64-link chain M3 and the near-toggle four-bar, in
//! PGA): DOP853-body at a
//! tolerance beside RKMK8-body at the fixed step whose error is at least as large, so their ratio, measured in one
//! run, is a ratio at equal or better error for the adaptive run. Only the stepping is timed
//! (`Simulation::stepping_time`): building the scene and recording samples are left out of both.
//!
//! `cargo bench -p scenarios --bench adaptive [-- FILTER]`, e.g. `-- M1`.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics::{Method, Pga};
use scenarios::equal_error::EQUAL_ERROR;

fn equal_error(c: &mut Criterion) {
    for pair in EQUAL_ERROR {
        let scene = pair.scene;
        let prepared = scene.prepare::<Pga>().expect("the scene builds");
        let mut group = c.benchmark_group(format!("adaptive/{}", scene.label()));
        let runs = [
            (
                format!("{} tol {:e}", Method::Dop853Body.name(), pair.tolerance),
                Method::Dop853Body,
                scene.adaptive(pair.tolerance).expect("a valid tolerance"),
            ),
            (
                format!("{} dt {:e}", pair.fixed.name(), pair.dt),
                pair.fixed,
                scene.fixed(pair.dt).expect("a valid step"),
            ),
        ];
        // A run of the chain takes seconds: ten of each are enough for a minimum.
        let long = prepared
            .run(pair.fixed, &runs[1].2)
            .expect("the run succeeds")
            .stepping_time
            > Duration::from_secs(1);
        if long {
            group.sample_size(10);
        }
        for (name, method, schedule) in &runs {
            group.bench_function(name.as_str(), |b| {
                b.iter_custom(|iterations| {
                    (0..iterations)
                        .map(|_| prepared.run(*method, schedule).expect("the run succeeds").stepping_time)
                        .sum()
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(2));
    targets = equal_error
}
criterion_main!(benches);
