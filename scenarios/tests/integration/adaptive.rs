//! Adaptive steps (`dynamics::step_control`) on scene 1, the free Dzhanibekov cuboid, against its reference
//! trajectory: the error achieved follows the tolerance asked for.
//!
//! Measured (`cargo test --release -p scenarios --test integration adaptive:: -- --nocapture`, PGA and CGA alike),
//! largest orientation error over the 10 s against the tolerance (relative = absolute): 1e-4: 1.96e-3 rad (19.6×
//! the tolerance, 170 steps); 1e-6: 3.34e-5 (33.4×, 422); 1e-8: 3.64e-7 (36.4×, 1056); 1e-10: 3.70e-9 (37.0×,
//! 2649); 1e-12: 1.86e-10 (186×, 6650). The tolerance bounds each step's error; the four flips amplify what the
//! steps leave, so the run's error is a steady ~30× the tolerance down to 1e-10, and then meets the 4th-order
//! estimate's floor. No step was refused.

use dynamics::{simulate, Algebra, Method, Schedule, Tolerance};
use reference::{trajectory_errors, SceneId};

use crate::common::{cuboid, trajectory};

fn tolerance_is_followed<A: Algebra>() {
    let scene = cuboid::<A>();
    let reference = SceneId::Cuboid
        .reference_trajectory()
        .expect("embedded reference parses");
    for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let schedule = Schedule::adaptive(
            Tolerance::new(tolerance, tolerance).unwrap(),
            scene.scene.duration,
            0.01,
        )
        .expect("a valid schedule");
        let run = simulate(&scene.system, &[scene.initial], Method::Dopri5Body, &schedule).expect("scene 1 runs");
        let errors = trajectory_errors(&reference, &trajectory(&run)).expect("same 0.01 s grid");
        let s = run.statistics;
        let ratio = errors.max_orientation / tolerance;
        println!(
            "{} tol {tolerance:.0e}: orientation {:.2e} rad ({:.2}× tol), position {:.2e} m, steps {} + {} refused, \
             {} evaluations, h {:.2e}..{:.2e}",
            A::NAME,
            errors.max_orientation,
            ratio,
            errors.max_position,
            s.accepted,
            s.rejected,
            s.evaluations,
            s.smallest_step,
            s.largest_step
        );
        // Proportional: the same factor (within 2×) at every tolerance down to 1e-10; below, the floor.
        if tolerance >= 1e-10 {
            assert!(
                (10.0..60.0).contains(&ratio),
                "tolerance {tolerance:e}: {ratio:.1}× the tolerance"
            );
        } else {
            assert!(
                errors.max_orientation < 3e-10,
                "tolerance {tolerance:e}: {:.2e}",
                errors.max_orientation
            );
        }
        assert!(errors.max_position < 10.0 * tolerance, "{:.2e}", errors.max_position);
    }
}

for_both_algebras!(tolerance_is_followed);
