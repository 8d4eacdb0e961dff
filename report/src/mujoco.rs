//! MuJoCo 4.0's measured points on the same scenes and machine (RK4; the single bodies measured by the team and
//! recorded here; the mechanisms from the reference set's scripts, with the date below): orientation
//! error at T (rad; the circle scene: m, reduced coordinates) for dt = 1e-2, 1e-3, 1e-4, and the CPU time per
//! step. Drawn as reference markers on the work-precision
//! plots: CPU per simulated second = time per step / dt.
//!
//! These are constants, the fallback wherever `--anchors` did not measure a figure beside the run
//! ([`crate::anchors`]; the single bodies have no shared MuJoCo script and are always these): wherever the report
//! shows them it says when and where they were measured ([`SINGLE_BODY_MEASURED`], [`MECHANISMS_MEASURED`]). MuJoCo's errors are at each scene's full T, so a
//! run of another length (`--duration`) is not compared with them ([`length_mismatch`]).

use reference::SceneId;

use crate::anchors::{Anchors, Key, Time};
use crate::measure::Measurements;

/// (dt, error) points and the time per step (s).
#[derive(Clone, Copy)]
pub(crate) struct Anchor {
    pub(crate) points: [(f64, f64); 3],
    pub(crate) time_per_step: f64,
}

impl Anchor {
    /// MuJoCo's error at dt = 1e-3, the accuracy at which the report compares costs.
    pub(crate) fn reference_error(&self) -> f64 {
        self.points[1].1
    }

    /// MuJoCo's CPU per simulated second at dt = 1e-3 (s/s).
    pub(crate) fn reference_cost(&self) -> f64 {
        self.time_per_step / self.points[1].0
    }
}

/// The error measure of the anchors: end orientation (rad), except the circle scene's end position (m).
pub(crate) fn anchored_error(scene: SceneId, measurements: &Measurements) -> f64 {
    match scene {
        SceneId::RodOnCircle | SceneId::RodOnSphere => measurements.position_end,
        _ => measurements.orientation_end,
    }
}

/// The CPU per simulated second at which a work-precision series first reaches `target` error: interpolated
/// linearly in log–log between the two runs that bracket it (a fixed-step method's error is a power of its
/// cost), the cheapest run's cost if that already reaches it, None if no run does. `points` are
/// (CPU per simulated second, error).
pub(crate) fn cost_at_error(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let mut sorted: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(cost, error)| *cost > 0.0 && error.is_finite())
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let first = *sorted.first()?;
    if first.1 <= target {
        return Some(first.0);
    }
    sorted.windows(2).find_map(|pair| {
        let ((cheap, coarse), (dear, fine)) = (pair[0], pair[1]);
        (coarse > target && fine <= target).then(|| {
            if fine <= 0.0 {
                return dear;
            }
            let fraction = (coarse / target).ln() / (coarse / fine).ln();
            (cheap.ln() + fraction * (dear / cheap).ln()).exp()
        })
    })
}

/// The day the single-body figures below entered the code (commit b6f0a06): the day they were measured is not
/// recorded; docs/benchmarks.md calls it an earlier day than the mechanisms' 2026-11-25.
pub(crate) const SINGLE_BODY_RECORDED: &str = "2026-11-22";

/// Where the single-body scenes' MuJoCo figures come from, as far as the repository records it; printed beside
/// them in the report.
pub(crate) const SINGLE_BODY_MEASURED: &str = "MuJoCo 4.0 (RK4) figures measured by the \
     team on the project's 2-core machine and recorded in this code on 2026-11-22 (the day of the measurement is \
     not recorded); constants, not measured by this run";

/// The legend of the single-body MuJoCo points on the plots.
pub(crate) fn single_body_legend() -> String {
    // No-break space: the legend wraps before "(recorded", not inside it.
    format!("MuJoCo 4.0 RK4 (recorded\u{a0}{SINGLE_BODY_RECORDED})")
}

/// The day the mechanisms' MuJoCo and Pinocchio figures were measured ([`MECHANISMS_MEASURED`]).
pub(crate) const MECHANISMS_DATE: &str = "2026-11-25";

/// Why runs of `duration` (s) cannot be compared with MuJoCo's error at the full length `full` (s), if they
/// cannot: "n/a: shortened run (2 s of T = 10 s)". Errors grow with time, so a shorter run's error at its end is
/// not comparable with MuJoCo's at T.
pub(crate) fn length_mismatch(duration: f64, full: f64) -> Option<String> {
    if (duration - full).abs() <= 1e-9 * full.abs() {
        None
    } else if duration < full {
        Some(format!("n/a: shortened run ({duration} s of T = {full} s)"))
    } else {
        Some(format!("n/a: run of {duration} s, not T = {full} s"))
    }
}

pub(crate) fn anchor(scene: SceneId) -> Option<Anchor> {
    let points = |errors: [f64; 3]| [(1e-2, errors[0]), (1e-3, errors[1]), (1e-4, errors[2])];
    match scene {
        SceneId::Cuboid => Some(Anchor {
            points: points([3e-6, 2e-10, 4e-12]),
            time_per_step: 4.3e-6,
        }),
        SceneId::Pendulum => Some(Anchor {
            points: points([2e-7, 4e-11, 2e-15]),
            time_per_step: 3.9e-6,
        }),
        SceneId::TopCusp => Some(Anchor {
            points: points([2e-4, 2e-8, 1e-12]),
            time_per_step: 4.3e-6,
        }),
        SceneId::RodOnCircle => Some(Anchor {
            points: points([8e-7, 8e-11, 8e-14]),
            time_per_step: 4.8e-6,
        }),
        SceneId::TopSteady | SceneId::RodOnSphere => None,
    }
}

/// The anchor as (CPU per simulated second, error) points.
pub(crate) fn work_precision_points(scene: SceneId) -> Option<Vec<(f64, f64)>> {
    anchor(scene).map(|a| {
        a.points
            .iter()
            .map(|&(dt, error)| (a.time_per_step / dt, error))
            .collect()
    })
}

/// Where the mechanisms' MuJoCo and Pinocchio figures below come from ([`MECHANISMS_DATE`]), printed beside them in
/// the report. (The
/// M1 and M2 times are those measured beside the benchmark run docs/benchmarks.md quotes; other runs the same day gave
/// 5.2–6.8 µs and 11.0–15.6 µs per step: the shared machine varies by a third from hour to hour.)
pub(crate) const MECHANISMS_MEASURED: &str =
    "MuJoCo 4.0 (RK4) and Pinocchio 4.1 measured 2026-11-25 with the reference set's \
     scripts on this project's machine type (2 cores, thread CPU time), beside `cargo bench -p scenarios --bench \
     mechanisms`";

/// M1, the double pendulum: MuJoCo's end orientation error (rad) at dt = 1e-2, 1e-3, 1e-4 and its time per step.
pub(crate) const DOUBLE_PENDULUM: Anchor = Anchor {
    points: [(1e-2, 2.06e-6), (1e-3, 2.22e-10), (1e-4, 2.58e-13)],
    time_per_step: 5.19e-6,
};

/// M2, the four-bar, its loop closed by MuJoCo's soft equality `connect`: coupler centre-of-mass error at T (m),
/// the largest loop violation (m) and the time per step (s), at dt = 1e-3 (the error does not fall with dt).
pub(crate) const FOUR_BAR_COUPLER_ERROR: f64 = 4.45e-2;
pub(crate) const FOUR_BAR_VIOLATION: f64 = 4.43e-4;
pub(crate) const FOUR_BAR_TIME_PER_STEP: f64 = 11.0e-6;

/// M3: MuJoCo's time per RK4 step (s) at dt = 1e-3 for the chain of N links, ball joints and (about x) hinges.
pub(crate) const CHAIN_BALL_TIME_PER_STEP: [(usize, f64); 7] = [
    (1, 5.1e-6),
    (2, 6.7e-6),
    (4, 9.5e-6),
    (8, 18.3e-6),
    (16, 53.4e-6),
    (32, 228.0e-6),
    (64, 1239.1e-6),
];
pub(crate) const CHAIN_HINGE_TIME_PER_STEP: [(usize, f64); 7] = [
    (1, 6.0e-6),
    (2, 6.8e-6),
    (4, 6.7e-6),
    (8, 9.6e-6),
    (16, 16.1e-6),
    (32, 36.1e-6),
    (64, 115.3e-6),
];

/// Pinocchio 4.1's articulated-body algorithm on the ball chain, s per dynamics evaluation (Python's call
/// overhead of about 0.15 µs included), measured beside MuJoCo by `pinocchio/chain.py`.
pub(crate) const PINOCCHIO_CHAIN_EVALUATION: [(usize, f64); 7] = [
    (1, 0.68e-6),
    (2, 1.12e-6),
    (4, 1.95e-6),
    (8, 3.81e-6),
    (16, 7.41e-6),
    (32, 12.35e-6),
    (64, 25.04e-6),
];

/// M1's MuJoCo time per step at dt = 1e-3: measured in this run if `anchors` has it, else [`DOUBLE_PENDULUM`]'s.
pub(crate) fn double_pendulum_time(anchors: &Anchors) -> Time<'_> {
    anchors.time(Key::DoublePendulum, DOUBLE_PENDULUM.time_per_step, MECHANISMS_DATE)
}

/// M2's MuJoCo time per step at dt = 1e-3: measured in this run if `anchors` has it, else [`FOUR_BAR_TIME_PER_STEP`].
pub(crate) fn four_bar_time(anchors: &Anchors) -> Time<'_> {
    anchors.time(Key::FourBar, FOUR_BAR_TIME_PER_STEP, MECHANISMS_DATE)
}

/// M3's MuJoCo times per step by chain length, ball joints or hinges: measured where `anchors` has them.
pub(crate) fn chain_times(anchors: &Anchors, ball: bool) -> Vec<(usize, Time<'_>)> {
    let recorded = if ball {
        &CHAIN_BALL_TIME_PER_STEP
    } else {
        &CHAIN_HINGE_TIME_PER_STEP
    };
    recorded
        .iter()
        .map(|&(links, seconds)| {
            (
                links,
                anchors.time(Key::Chain { ball, links }, seconds, MECHANISMS_DATE),
            )
        })
        .collect()
}

/// M3's Pinocchio times per evaluation by chain length: measured where `anchors` has them.
pub(crate) fn pinocchio_chain_times(anchors: &Anchors) -> Vec<(usize, Time<'_>)> {
    PINOCCHIO_CHAIN_EVALUATION
        .iter()
        .map(|&(links, seconds)| {
            (
                links,
                anchors.time(Key::PinocchioChain(links), seconds, MECHANISMS_DATE),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cost_at_error_interpolates_log_log() {
        // error = cost⁻⁴: 1e-4 at cost 10, 1e-8 at cost 100; 1e-6 lies halfway in log, at cost √1000.
        let points = [(100.0, 1e-8), (10.0, 1e-4)];
        let cost = cost_at_error(&points, 1e-6).unwrap();
        assert!((cost - 1000f64.sqrt()).abs() < 1e-9, "{cost}");
        assert_eq!(cost_at_error(&points, 1e-3), Some(10.0));
        assert_eq!(cost_at_error(&points, 1e-9), None);
        // The first crossing from the cheap end counts, not a later one past a round-off floor.
        let floored = [(10.0, 1e-4), (100.0, 1e-8), (1000.0, 2e-8)];
        assert!((cost_at_error(&floored, 1e-6).unwrap() - 1000f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn runs_of_another_length_are_not_compared() {
        assert_eq!(length_mismatch(10.0, 10.0), None);
        assert_eq!(
            length_mismatch(2.0, 10.0).as_deref(),
            Some("n/a: shortened run (2 s of T = 10 s)")
        );
        assert!(length_mismatch(20.0, 10.0).unwrap().starts_with("n/a"));
        assert!(MECHANISMS_MEASURED.contains(MECHANISMS_DATE));
        assert!(SINGLE_BODY_MEASURED.contains(SINGLE_BODY_RECORDED));
    }
}
