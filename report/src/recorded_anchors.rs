//! MuJoCo's and Pinocchio's recorded figures, the constants the report compares our runs with wherever `--anchors`
//! did not measure a figure beside the run ([`crate::measured_anchors`]; the single bodies have no shared MuJoCo script
//! and are always these).
//!
//! MuJoCo 4.0's measured points on the same scenes and machine (RK4; the single bodies measured by the team and
//! recorded here; the mechanisms from the reference set's scripts, with the date below): orientation error at T (rad;
//! the circle scene: m, reduced coordinates) for dt = 1e-2, 1e-3, 1e-4, and the CPU time per step, drawn as reference
//! markers on the work-precision plots (CPU per simulated second = time per step / dt); Pinocchio 4.1's time per
//! evaluation on the chain. The robots' MuJoCo and Pinocchio figures are recorded with their references
//! (`reference::robots`); here is when and with which versions ([`RECORDED_WHEN`], [`MUJOCO`], [`PINOCCHIO`]).
//!
//! Wherever the report shows these it says when and where they were measured ([`SINGLE_BODY_MEASURED`],
//! [`MECHANISMS_MEASURED`]). MuJoCo's errors are at each scene's full T, so a run of another length (`--duration`) is
//! not compared with them ([`crate::measure::length_mismatch`]).

use reference::SceneId;

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

/// The day the single-body figures below entered the code (commit b6f0a06): the day they were measured is not
/// recorded; docs/benchmarks.md calls it an earlier day than the mechanisms' 2026-11-25.
pub(crate) const SINGLE_BODY_RECORDED: &str = "2026-11-22";

/// Where the single-body scenes' MuJoCo figures come from, as far as the repository records it; printed beside
/// them in the report.
pub(crate) const SINGLE_BODY_MEASURED: &str = "MuJoCo 4.0 (RK4) figures measured by the \
     team on the project's 2-core machine and recorded in this code on 2026-11-22 (the day of the measurement is \
     not recorded); constants, not measured by this run";

/// The legend of the single-body MuJoCo points on the plots, `when` being "recorded 2026-11-22" or "measured in this
/// run".
pub(crate) fn single_body_legend(when: &str) -> String {
    // No-break spaces: the legend wraps before the parenthesis, not inside it.
    format!("MuJoCo 4.0 RK4 ({})", when.replace(' ', "\u{a0}"))
}

/// The day the mechanisms' MuJoCo and Pinocchio figures were measured ([`MECHANISMS_MEASURED`]).
pub(crate) const MECHANISMS_DATE: &str = "2026-11-25";

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

impl Anchor {
    /// The anchor as (CPU per simulated second, error) points.
    pub(crate) fn work_precision_points(&self) -> Vec<(f64, f64)> {
        self.points
            .iter()
            .map(|&(dt, error)| (self.time_per_step / dt, error))
            .collect()
    }
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

/// When the reference's MuJoCo and Pinocchio figures were recorded; said wherever they are shown.
pub(crate) const RECORDED_WHEN: &str = "when the reference was made (see reference/data/robots/README.md)";

/// The versions of the reference's `versions` field.
pub(crate) const MUJOCO: &str = "MuJoCo 4.0 RK4";

pub(crate) const PINOCCHIO: &str = "Pinocchio 4.1";
