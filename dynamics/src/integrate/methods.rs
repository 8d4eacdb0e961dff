//! The integration methods by name: general methods for any system, splittings of a free body, and the methods
//! that step in joint coordinates, with their orders and costs.

/// A general integration method: valid for any [`Dynamics`](crate::Dynamics).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classic RK4 on (R, Ω) treated as vectors, then renormalisation of R (the paper's method, theory §10).
    Rk4,
    /// Runge–Kutta–Munthe-Kaas of order 4: R is advanced as `R₀ exp(σ)` with σ from the RK4 tableau,
    /// corrected by the commutators that truncate `dexp⁻¹` at order 4. R stays an exact motor; the world
    /// momentum Ω (a vector) follows classic RK4, so a free body keeps Ω exactly.
    Rkmk4,
    /// RKMK4 with the momentum carried in the body frame during the step, `Ω_b = ~RΩR` with
    /// `dΩ_b/dt = Ḃ × Ω_b + ~R W R` (theory §5). For a free body the body momentum then obeys Euler's equations
    /// on their own, and the error of R no longer feeds back into `Ḃ = M⁻¹[Ω_b]`; with world Ω (the other two
    /// methods) `Ḃ = M⁻¹[~RΩR]` inherits R's error, which the Dzhanibekov flips amplify: on scene 1 at
    /// dt = 1e-3 this method's orientation error is about 100× smaller than RK4's or RKMK4's (see
    /// `scenarios/examples/free_body_accuracy.rs`). A system without forces and joints keeps each body's world
    /// momentum exactly: the step ends with a projection onto it (see `end_of_body_step`).
    /// A force-free body skips the stages' motors ([`Dynamics::rates_depend_on_motors`](crate::Dynamics::rates_depend_on_motors)).
    Rkmk4Body,
    /// The body-momentum scheme of [`Method::Rkmk4Body`] on Butcher's 7-stage explicit Runge–Kutta method of
    /// order 6 (J. C. Butcher, 1964), with `dexp⁻¹` truncated after its `ad⁴` term: 7 evaluations per step
    /// instead of 4, for an error that falls as dt⁶. At the accuracy of RK4 at dt = 1e-3 it takes steps
    /// 5–10× longer (measured on the reference scenes, see docs/dynamics.md).
    Rkmk6Body,
    /// The same scheme on Cooper and Verner's 11-stage explicit method of order 8 (1972), with `dexp⁻¹` truncated
    /// after its `ad⁶` term: 11 evaluations per step for an error that falls as dt⁸, so at tight tolerances
    /// (MuJoCo's accuracy on the double pendulum, 2.2e-10 rad) it takes steps about three times as long as
    /// RKMK6-body's and needs fewer evaluations per simulated second.
    Rkmk8Body,
    /// The same scheme on Dormand and Prince's 7-stage pair of orders 5 and 4 (J. R. Dormand and P. J. Prince,
    /// "A family of embedded Runge–Kutta formulae", J. Comp. Appl. Math. 6(1), 1980), with `dexp⁻¹` truncated after
    /// its `ad⁴` term. The 5th-order solution is kept; the difference from the embedded 4th-order one, taken in the
    /// Lie algebra, estimates the step's error, which an adaptive [`crate::Schedule`] turns into step sizes
    /// ([`crate::integrate::step_control`]). Its continuous extension of order 4 (Shampine's, in Hairer, Nørsett & Wanner,
    /// *Solving ODEs I*, §II.6) gives the state anywhere inside a step without another evaluation, so samples and
    /// events never shorten a step.
    Dopri5Body,
    /// The same scheme on Dormand and Prince's 12-stage pair of order 8 with embedded solutions of orders 5 and 3
    /// (DOP853: P. J. Prince and J. R. Dormand, J. Comp. Appl. Math. 7(1), 1981, as published with Hairer's code),
    /// with `dexp⁻¹` truncated after its `ad⁶` term: the 8th-order solution is kept, and Hairer's combination of
    /// the two embedded differences, `e₅²/√(e₅² + 0.01 e₃²)`, estimates the error with a step-size law of order 8.
    /// Its continuous extension of order 7 costs four more evaluations, made only in steps that hold a sample or
    /// an event. For tight tolerances: 12 evaluations per step for an error that falls as dt⁸.
    Dop853Body,
}

impl Method {
    /// Every general method, in the order of the enum.
    pub const ALL: [Method; 7] = [
        Method::Rk4,
        Method::Rkmk4,
        Method::Rkmk4Body,
        Method::Rkmk6Body,
        Method::Rkmk8Body,
        Method::Dopri5Body,
        Method::Dop853Body,
    ];

    /// The method's name in reports and tables ("RK4", "RKMK4", "RKMK4-body", "RKMK6-body", "RKMK8-body",
    /// "DP5(4)-body", "DOP853-body").
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "RK4",
            Method::Rkmk4 => "RKMK4",
            Method::Rkmk4Body => "RKMK4-body",
            Method::Rkmk6Body => "RKMK6-body",
            Method::Rkmk8Body => "RKMK8-body",
            Method::Dopri5Body => "DP5(4)-body",
            Method::Dop853Body => "DOP853-body",
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            Method::Rk4 | Method::Rkmk4 | Method::Rkmk4Body => 4,
            Method::Dopri5Body => 5,
            Method::Rkmk6Body => 6,
            Method::Rkmk8Body | Method::Dop853Body => 8,
        }
    }

    /// For an embedded pair, the order `k` of its error estimate's step-size law (the estimate of a step of
    /// length h falls as h^k, so the controller scales steps by `(1/err)^(1/k)`); `None` for a method without an
    /// estimate, which an adaptive schedule refuses.
    pub fn estimate_order(self) -> Option<u32> {
        match self {
            Method::Dopri5Body => Some(5),
            Method::Dop853Body => Some(8),
            Method::Rk4 | Method::Rkmk4 | Method::Rkmk4Body | Method::Rkmk6Body | Method::Rkmk8Body => None,
        }
    }
}

/// A splitting method for a free body ([`KineticSplitting`](crate::KineticSplitting)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SplittingMethod {
    /// Strang (symmetric, 2nd order): kick ½h, drift h, kick ½h, where the drift is the symmetric
    /// composition of the exact rotations about the body axes and the exact translation.
    Strang,
    /// Yoshida's 4th-order triple jump: three Strang steps of `w₁h, w₀h, w₁h`.
    Yoshida4,
}

impl SplittingMethod {
    /// Every splitting method, in the order of the enum.
    pub const ALL: [SplittingMethod; 2] = [SplittingMethod::Strang, SplittingMethod::Yoshida4];

    /// The method's name in reports and tables ("Strang", "Yoshida4").
    pub fn name(self) -> &'static str {
        match self {
            SplittingMethod::Strang => "Strang",
            SplittingMethod::Yoshida4 => "Yoshida4",
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            SplittingMethod::Strang => 2,
            SplittingMethod::Yoshida4 => 4,
        }
    }
}

/// A method that steps in joint coordinates (mechanisms of joint models in a tree; see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointMethod {
    /// The classic RK4 tableau (Munthe-Kaas on the rotations), 4 evaluations per step.
    Rkmk4,
    /// Butcher's 7-stage method of order 6, as [`crate::Method::Rkmk6Body`]'s.
    Rkmk6,
    /// Cooper and Verner's 11-stage method of order 8, as [`crate::Method::Rkmk8Body`]'s.
    Rkmk8,
    /// Dormand and Prince's embedded pair of order 8 (DOP853), as [`crate::Method::Dop853Body`]'s: the 8th-order
    /// solution kept, Hairer's combination of the embedded differences of orders 5 and 3 estimating each step's error
    /// in joint coordinates for an adaptive [`crate::Schedule`] (the largest over the coordinates, docs/dynamics.md
    /// "Adaptive steps in joint coordinates"), and its continuous extension of order 7 giving samples and events
    /// inside a step. The method of robots with a tolerance.
    Dop853,
}

impl JointMethod {
    /// Every joint-coordinate method.
    pub const ALL: [JointMethod; 4] = [
        JointMethod::Rkmk4,
        JointMethod::Rkmk6,
        JointMethod::Rkmk8,
        JointMethod::Dop853,
    ];

    /// "RKMK4-joint", "RKMK6-joint", "RKMK8-joint", "DOP853-joint".
    pub fn name(self) -> &'static str {
        match self {
            JointMethod::Rkmk4 => "RKMK4-joint",
            JointMethod::Rkmk6 => "RKMK6-joint",
            JointMethod::Rkmk8 => "RKMK8-joint",
            JointMethod::Dop853 => "DOP853-joint",
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            JointMethod::Rkmk4 => 4,
            JointMethod::Rkmk6 => 6,
            JointMethod::Rkmk8 | JointMethod::Dop853 => 8,
        }
    }

    /// For an embedded pair, the order of its error estimate's step-size law ([`Method::estimate_order`]); `None`
    /// for the others.
    pub fn estimate_order(self) -> Option<u32> {
        match self {
            JointMethod::Dop853 => Some(8),
            JointMethod::Rkmk4 | JointMethod::Rkmk6 | JointMethod::Rkmk8 => None,
        }
    }
}

/// Any integrator: a general [`Method`], a [`SplittingMethod`] (free bodies only) or a [`JointMethod`]
/// (mechanisms of joint models in a tree).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// A general method, for any system.
    General(Method),
    /// A splitting method, for a single free body whose forces depend on the configuration only.
    Splitting(SplittingMethod),
    /// A method that steps in joint coordinates, for a mechanism whose joints are joint models in a tree
    /// (`crate::integrate::joint_coordinates`).
    Joint(JointMethod),
}

impl Integrator {
    /// Every integrator: the general methods, then the splittings.
    pub const ALL: [Integrator; 9] = [
        Integrator::General(Method::Rk4),
        Integrator::General(Method::Rkmk4),
        Integrator::General(Method::Rkmk4Body),
        Integrator::General(Method::Rkmk6Body),
        Integrator::General(Method::Rkmk8Body),
        Integrator::General(Method::Dopri5Body),
        Integrator::General(Method::Dop853Body),
        Integrator::Splitting(SplittingMethod::Strang),
        Integrator::Splitting(SplittingMethod::Yoshida4),
    ];

    /// The name of the method.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::General(method) => method.name(),
            Integrator::Splitting(method) => method.name(),
            Integrator::Joint(method) => method.name(),
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            Integrator::General(method) => method.order(),
            Integrator::Splitting(method) => method.order(),
            Integrator::Joint(method) => method.order(),
        }
    }

    /// The order of the error estimate of an embedded pair ([`Method::estimate_order`]); `None` for the others.
    pub fn estimate_order(self) -> Option<u32> {
        match self {
            Integrator::General(method) => method.estimate_order(),
            Integrator::Joint(method) => method.estimate_order(),
            Integrator::Splitting(_) => None,
        }
    }
}

impl From<Method> for Integrator {
    fn from(method: Method) -> Self {
        Integrator::General(method)
    }
}

impl From<SplittingMethod> for Integrator {
    fn from(method: SplittingMethod) -> Self {
        Integrator::Splitting(method)
    }
}

impl From<JointMethod> for Integrator {
    fn from(method: JointMethod) -> Self {
        Integrator::Joint(method)
    }
}
