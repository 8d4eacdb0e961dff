//! How the report draws its runs: small multiples, one panel per integrator [`Family`] (and per constraint
//! formulation), so an axis carries at most four curves (two integrators in two algebras) and MuJoCo's points.
//! A colour means the same in every panel ([`slot`]): the hue is the integrator's place in its family, the dark
//! shade PGA (solid, circles), the light shade CGA (dashed, squares). Values too small for a log axis are drawn at
//! [`LOG_FLOOR`].

use dynamics::integrate::{Integrator, Method, SplittingMethod};
use scenarios::Formulation;
use scene_file::AlgebraKind;

use crate::plot::{Series, Shape};

/// The integrator families the plots put in panels of their own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Family {
    /// RK4 and RKMK4: the momentum integrated in the world frame.
    WorldFrame,
    /// RKMK4-body and RKMK6-body: the momentum carried in the body frame.
    BodyMomentum,
    /// RKMK8-body, the same scheme at order 8, in a panel of its own (a third pair of colours would pass the six
    /// an axis may carry with MuJoCo's points).
    EighthOrder,
    /// DP5(4)-body and DOP853-body, the embedded pairs of adaptive schedules, stepped at fixed sizes.
    Embedded,
    /// Strang and Yoshida-4 (free bodies only).
    Splitting,
    /// The methods stepping in joint coordinates (mechanisms of joint models only).
    JointCoordinates,
}

impl Family {
    /// An integrator's family and its place in it (0 or 1).
    pub(crate) fn of(integrator: Integrator) -> (Family, usize) {
        match integrator {
            Integrator::General(Method::Rk4) => (Family::WorldFrame, 0),
            Integrator::General(Method::Rkmk4) => (Family::WorldFrame, 1),
            Integrator::General(Method::Rkmk4Body) => (Family::BodyMomentum, 0),
            Integrator::General(Method::Rkmk6Body) => (Family::BodyMomentum, 1),
            Integrator::General(Method::Rkmk8Body) => (Family::EighthOrder, 0),
            Integrator::General(Method::Dopri5Body) => (Family::Embedded, 0),
            Integrator::General(Method::Dop853Body) => (Family::Embedded, 1),
            Integrator::Splitting(SplittingMethod::Strang) => (Family::Splitting, 0),
            Integrator::Splitting(SplittingMethod::Yoshida4) => (Family::Splitting, 1),
            Integrator::Joint(method) => (
                Family::JointCoordinates,
                usize::from(method != dynamics::JointMethod::Rkmk4),
            ),
        }
    }

    pub(crate) fn title(self) -> &'static str {
        match self {
            Family::WorldFrame => "RK4 and RKMK4 (momentum in the world frame)",
            Family::BodyMomentum => "RKMK4-body and RKMK6-body (momentum in the body frame)",
            Family::EighthOrder => "RKMK8-body (order 8, momentum in the body frame)",
            Family::Embedded => {
                "DP5(4)-body and DOP853-body (embedded pairs, orders 5 and 8, momentum in the body frame)"
            }
            Family::Splitting => "Strang and Yoshida-4 splittings",
            Family::JointCoordinates => "RKMK-joint (joint coordinates)",
        }
    }
}

/// The palette slot of a run: the hue pair (blue, vermilion) by the integrator's place in its family, the dark
/// shade for PGA and the light one for CGA, so a colour means the same in every panel and never repeats in one.
pub(crate) fn slot(algebra: AlgebraKind, member: usize) -> usize {
    2 * member
        + match algebra {
            AlgebraKind::Pga => 0,
            AlgebraKind::Cga => 1,
        }
}

/// A run's series in the style of its algebra: PGA solid with circles, CGA dashed with squares (so where the two
/// algebras give the same curve, the PGA one shows through the CGA dashes).
pub(crate) fn styled(series: Series, algebra: AlgebraKind, member: usize) -> Series {
    Series {
        slot: Some(slot(algebra, member)),
        dashed: algebra == AlgebraKind::Cga,
        shape: match algebra {
            AlgebraKind::Pga => Shape::Circle,
            AlgebraKind::Cga => Shape::Square,
        },
        ..series
    }
}

/// A panel's title: its formulation, if any, and its family.
pub(crate) fn panel_title(formulation: Option<Formulation>, family: Family) -> String {
    match formulation {
        Some(f) => format!("{}: {}", f.name(), family.title()),
        None => family.title().to_owned(),
    }
}

/// Values below this are drawn at it on the log plots of drift and violation (round-off is about 1e-16).
pub(crate) const LOG_FLOOR: f64 = 1e-17;

/// The running maximum of a sequence (the largest value up to each point).
pub(crate) fn running_max(values: &[f64]) -> Vec<f64> {
    values
        .iter()
        .scan(f64::NEG_INFINITY, |largest, &v| {
            *largest = largest.max(v);
            Some(*largest)
        })
        .collect()
}
