//! What the families share about measuring runs: two runs' agreement, the energy drift net of impacts, the cost at
//! which a series of runs reaches an error (interpolated), and whether a run's length compares with an error
//! recorded at a scene's full length.

use dynamics::limits::{energy_changed_by, LimitTransition};
use dynamics::simulate::Sample;

/// The largest orientation (rad) and position (m) difference over the samples of two runs.
pub fn agreement(first: &[Sample], second: &[Sample]) -> (f64, f64) {
    first
        .iter()
        .zip(second)
        .fold((0.0f64, 0.0f64), |(angle, distance), (a, b)| {
            (
                angle.max(a.orientation.angle_to(&b.orientation)),
                distance.max((a.position - b.position).norm()),
            )
        })
}

/// The largest |E(t) − E₀ − L(t)| (J) over `(t, E)` samples, L(t) what the `transitions` changed the energy by up to t.
pub(crate) fn drift_net_of_impacts(samples: impl Iterator<Item = (f64, f64)>, transitions: &[LimitTransition]) -> f64 {
    let mut start = None;
    samples
        .map(|(t, energy)| {
            let start = *start.get_or_insert(energy);
            (energy - start - energy_changed_by(transitions, t)).abs()
        })
        .fold(0.0, f64::max)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recorded_anchors::{MECHANISMS_DATE, MECHANISMS_MEASURED, SINGLE_BODY_MEASURED, SINGLE_BODY_RECORDED};

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
