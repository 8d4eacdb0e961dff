//! Joint limits: one-sided constraints on a joint coordinate (docs/limits.md). A revolute or prismatic joint model
//! may carry a [`JointLimit`] ([`crate::JointModel::with_limit`]); a mechanism enforces it exactly:
//!
//! * while the coordinate is inside its range the joint is free, and [`crate::simulate()`] watches the gap to the
//!   nearer bound as an event;
//! * where the gap closes (located to round-off) the joint meets its bound in an **impact**: an impulse through the
//!   kinetic metric (the joint-space mass matrix) reverses the joint's rate times the restitution, Newton's law,
//!   changing no other held relation (couplings, drives, other held limits);
//! * a joint that does not bounce away is **held** at the bound by a joint-space row `q̈ = 0` of the articulated
//!   solve, whose multiplier is the limit's reaction; it is released where that reaction would pull (located as
//!   an event), never by a spring or a penetration.
//!
//! The transitions are recorded in [`crate::Simulation::transitions`].

use crate::constraints::ConstraintError;

/// A limited joint this close to a bound (rad or m) at the start is on it; further beyond it is an error.
pub const AT_BOUND: f64 = 1e-12;

/// Bounces slower than this (rad/s or m/s) end at rest at the bound: a restitution below 1 would otherwise bounce
/// ever more often (Zeno), each flight shorter than the last, and a flight must rise well above the
/// [`AT_BOUND`] to which its return is located (from 1e-3 under 10 rad/s² or m/s², it rises 5e-8).
pub const REST_SPEED: f64 = 1e-3;

/// A joint coordinate's range `[lower, upper]` (rad or m) and the restitution of its bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimit {
    lower: f64,
    upper: f64,
    restitution: f64,
}

impl JointLimit {
    /// The range `[lower, upper]`, inelastic (restitution 0): a joint reaching a bound stops there. One bound may be
    /// infinite (a one-sided limit); `lower < upper`, no NaN, and not both infinite (that limits nothing).
    ///
    /// ```
    /// use dynamics::limits::JointLimit;
    ///
    /// let elbow = JointLimit::new(-2.0, 2.5)?.with_restitution(0.5)?; // rad
    /// assert_eq!((elbow.lower(), elbow.upper(), elbow.restitution()), (-2.0, 2.5, 0.5));
    /// assert!(JointLimit::new(1.0, -1.0).is_err()); // the bounds inverted
    /// assert!(JointLimit::new(f64::NEG_INFINITY, 0.3).is_ok()); // a stop on one side only
    /// # Ok::<(), dynamics::ConstraintError>(())
    /// ```
    pub fn new(lower: f64, upper: f64) -> Result<Self, ConstraintError> {
        if lower.is_nan() || upper.is_nan() || lower >= upper || (lower.is_infinite() && upper.is_infinite()) {
            return Err(ConstraintError::InvalidParameter {
                name: "joint limit".to_owned(),
                reason: format!(
                    "a limit needs lower < upper, neither NaN and at least one finite, got [{lower}, {upper}]"
                ),
            });
        }
        Ok(JointLimit {
            lower,
            upper,
            restitution: 0.0,
        })
    }

    /// The same range with Newton's restitution coefficient `restitution` in [0, 1]: the joint leaves a bound at
    /// `restitution` times the rate it met it with (1: elastic, no energy lost; 0: it stops).
    pub fn with_restitution(self, restitution: f64) -> Result<Self, ConstraintError> {
        if !(0.0..=1.0).contains(&restitution) {
            return Err(ConstraintError::InvalidParameter {
                name: "joint limit".to_owned(),
                reason: format!("a restitution coefficient is in [0, 1], got {restitution}"),
            });
        }
        Ok(JointLimit { restitution, ..self })
    }

    /// The lower bound (rad or m).
    pub fn lower(&self) -> f64 {
        self.lower
    }

    /// The upper bound (rad or m).
    pub fn upper(&self) -> f64 {
        self.upper
    }

    /// The restitution coefficient.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The signed distance (rad or m) from `q` to the nearer bound: positive inside the range.
    pub fn gap(&self, q: f64) -> f64 {
        (q - self.lower).min(self.upper - q)
    }

    /// The bound nearer to `q`.
    pub fn nearer(&self, q: f64) -> Bound {
        if q - self.lower <= self.upper - q {
            Bound::Lower
        } else {
            Bound::Upper
        }
    }

    /// The value of `bound`.
    pub fn at(&self, bound: Bound) -> f64 {
        match bound {
            Bound::Lower => self.lower,
            Bound::Upper => self.upper,
        }
    }
}

/// One of a limit's two bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// The lower bound: the coordinate is kept from decreasing past it.
    Lower,
    /// The upper bound: the coordinate is kept from increasing past it.
    Upper,
}

impl Bound {
    /// The direction (+1 or −1) in which the bound pushes the coordinate.
    pub fn inward(self) -> f64 {
        match self {
            Bound::Lower => 1.0,
            Bound::Upper => -1.0,
        }
    }
}

/// What happened to a limited joint, or a contact point ([`crate::contacts`], whose plane is its lower bound), at a
/// transition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LimitChange {
    /// The joint met `bound` at `speed_before` (rad/s or m/s, toward the bound) and left it at `speed_after` (away
    /// from it): an impact that bounced.
    Bounced {
        /// The bound met.
        bound: Bound,
        /// The joint's rate toward the bound before the impact.
        speed_before: f64,
        /// The joint's rate away from the bound after it.
        speed_after: f64,
    },
    /// The joint met `bound` at `speed_before` (zero for a joint at rest on it) and is held there.
    Held {
        /// The bound met.
        bound: Bound,
        /// The joint's rate toward the bound before the impact.
        speed_before: f64,
    },
    /// The bound stopped pushing: the joint is free again, at rest on the bound.
    Released {
        /// The bound left.
        bound: Bound,
    },
    /// A held contact's slide stopped and its friction holds it: it sticks (docs/contacts.md "Friction").
    Stuck {
        /// The slip left at the located stop (m/s), removed as the contact sticks.
        slip_before: f64,
    },
    /// A held contact starts to slide (or a slide that stopped slides on), its slip along `direction` (world, unit):
    /// the friction force it needed left the cone.
    Slipped {
        /// The direction of the slip, by maximal dissipation.
        direction: nalgebra::Vector3<f64>,
    },
}

/// What `transitions` changed the energy by up to and including time `t` (J): the sum of their
/// [`LimitTransition::energy_change`]s, so that `E(t) − E₀` less it is the energy change of the motion between them
/// (zero for a conservative system, up to the integration error).
pub fn energy_changed_by(transitions: &[LimitTransition], t: f64) -> f64 {
    (transitions.iter())
        .filter(|transition| transition.t <= t)
        .map(|transition| transition.energy_change)
        .sum()
}

/// A located change of a joint limit's or a contact's state, in [`crate::Simulation::transitions`].
#[derive(Clone, Debug, PartialEq)]
pub struct LimitTransition {
    /// The time (s): the first time found at or after the crossing, within a few ulps.
    pub t: f64,
    /// The name of the limited joint or of the contact ([`crate::contacts`]).
    pub constraint: String,
    /// What happened.
    pub change: LimitChange,
    /// The system's energy after the transition less before it (J): what an impact took (zero for restitution 1, up to
    /// round-off), zero for a release.
    pub energy_change: f64,
}
