//! The six reference scenes of `docs/scenes.md`: their parameters, embedded reference trajectories, published end
//! states and published analytic values. Numbers are written as published, to the digits given (the end states
//! only here, the other values also in `docs/scenes.md`); where a scene defines a quantity by geometry instead of
//! by value (e.g. the pendulum's initial CoM from θ₀ = π/2), it is built from that definition.
//!
//! Units are SI. Quaternions map body → world; the body frame is the principal-axis frame at the CoM.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_6};

use nalgebra::{UnitQuaternion, Vector3};

use crate::trajectory::{Sample, Trajectory, TrajectoryError};

/// Gravitational acceleration (m/s²), along −z in the world frame where a scene has gravity.
pub const GRAVITY: f64 = 9.81;

/// Interval of the reference samples and of the error metrics (s).
pub const SAMPLE_INTERVAL: f64 = 0.01;

/// One of the reference scenes of `docs/scenes.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SceneId {
    /// Scene 1: free cuboid spinning near its intermediate axis (Dzhanibekov flips), gravity off.
    Cuboid,
    /// Scene 2: thin rod on a hinge released horizontally (physical pendulum).
    Pendulum,
    /// Scene 3a: heavy symmetric top (cone, tip pinned) started with pure spin: cusped nutation.
    TopCusp,
    /// Scene 3b: the same top started on its slow steady precession.
    TopSteady,
    /// Scene 4, sphere: a rod whose end point slides on a sphere.
    RodOnSphere,
    /// Scene 4, circle: a rod whose end point slides on a horizontal circle.
    RodOnCircle,
}

/// How a scene's body is constrained. `body_anchor` is the constrained body point, as an offset from the CoM in the
/// body frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneConstraint {
    /// No constraint: the body moves freely.
    Free,
    /// Revolute joint: `body_anchor` stays at `pivot`, rotation only about the world `axis`.
    Hinge {
        /// World point the anchor stays at (m).
        pivot: Vector3<f64>,
        /// Unit rotation axis in the world frame.
        axis: Vector3<f64>,
        /// Constrained body point, offset from the CoM in the body frame (m).
        body_anchor: Vector3<f64>,
    },
    /// Spherical joint: `body_anchor` stays at `pivot`.
    BallJoint {
        /// World point the anchor stays at (m).
        pivot: Vector3<f64>,
        /// Constrained body point, offset from the CoM in the body frame (m).
        body_anchor: Vector3<f64>,
    },
    /// |P − centre| = radius for the body point P at `body_anchor`.
    PointOnSphere {
        /// Constrained body point P, offset from the CoM in the body frame (m).
        body_anchor: Vector3<f64>,
        /// Sphere centre in the world frame (m).
        centre: Vector3<f64>,
        /// Sphere radius (m).
        radius: f64,
    },
    /// |P − centre| = radius and (P − centre)·normal = 0.
    PointOnCircle {
        /// Constrained body point P, offset from the CoM in the body frame (m).
        body_anchor: Vector3<f64>,
        /// Circle centre in the world frame (m).
        centre: Vector3<f64>,
        /// Circle radius (m).
        radius: f64,
        /// Unit normal of the circle's plane, world frame.
        normal: Vector3<f64>,
    },
}

/// Everything a simulator needs to set a scene up, and the energy conventions of the drift metric.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneParameters {
    /// Mass of the body (kg).
    pub mass: f64,
    /// Principal moments of inertia about the CoM, along body x, y, z.
    pub principal_moments: Vector3<f64>,
    /// Gravitational acceleration along −z (0 when the scene has no gravity).
    pub gravity: f64,
    /// Initial CoM position in the world frame (m).
    pub initial_com: Vector3<f64>,
    /// Initial orientation, body → world.
    pub initial_orientation: UnitQuaternion<f64>,
    /// Initial angular velocity in the body frame (rad/s).
    pub initial_body_angular_velocity: Vector3<f64>,
    /// Initial CoM velocity in the world frame (m/s).
    pub initial_com_velocity: Vector3<f64>,
    /// Simulated time T (s).
    pub duration: f64,
    /// How the body is constrained.
    pub constraint: SceneConstraint,
    /// CoM height at which the potential energy m g (z − z₀) is zero.
    pub potential_zero_height: f64,
    /// Total energy E₀ as printed in `docs/scenes.md`.
    pub initial_energy: f64,
    /// Normaliser of the energy drift metric |E(T) − E₀| / E_scale (`docs/scenes.md` "Error metrics").
    pub energy_scale: f64,
}

impl SceneParameters {
    /// The initial state as a sample at t = 0 (world-frame angular velocity R₀ ω_body).
    pub fn initial_state(&self) -> Sample {
        Sample {
            t: 0.0,
            position: self.initial_com,
            orientation: self.initial_orientation,
            velocity: self.initial_com_velocity,
            angular_velocity: self.initial_orientation * self.initial_body_angular_velocity,
        }
    }

    /// Kinetic plus potential energy: ½ m |v|² + ½ ω_bᵀ I ω_b + m g (z − z₀).
    pub fn mechanical_energy(&self, sample: &Sample) -> f64 {
        let body_omega = sample.body_angular_velocity();
        let rotational = 0.5 * body_omega.dot(&self.principal_moments.component_mul(&body_omega));
        let translational = 0.5 * self.mass * sample.velocity.norm_squared();
        let potential = self.mass * self.gravity * (sample.position.z - self.potential_zero_height);
        translational + rotational + potential
    }
}

/// Inertia of the thin rod of scenes 2 and 4 (m = 1, L = 1, rod axis = body z), including the axial value 1e-3.
fn rod_principal_moments() -> Vector3<f64> {
    Vector3::new(1.0 / 12.0, 1.0 / 12.0, 1e-3)
}

/// Scene 2: θ₀ = π/2 (horizontal), hinge axis world y through the rod end at the origin.
pub const PENDULUM_INITIAL_ANGLE: f64 = FRAC_PI_2;
/// Scene 3: the symmetry axis starts tilted by θ₀ = π/6 (rotation about world x).
pub const TOP_INITIAL_TILT: f64 = FRAC_PI_6;
/// Scene 3: spin ω₃ about the symmetry axis (rad/s).
pub const TOP_SPIN: f64 = 20.0;
/// Scene 3b: slow steady precession rate at θ₀, ω₃ = 20 (rad/s).
const TOP_SLOW_PRECESSION_RATE: f64 = 1.45562004496984;

impl SceneId {
    /// Every scene, in `docs/scenes.md` order.
    pub const ALL: [SceneId; 6] = [
        SceneId::Cuboid,
        SceneId::Pendulum,
        SceneId::TopCusp,
        SceneId::TopSteady,
        SceneId::RodOnSphere,
        SceneId::RodOnCircle,
    ];

    /// Short name with the `docs/scenes.md` scene number.
    pub fn label(self) -> &'static str {
        match self {
            SceneId::Cuboid => "1 cuboid (Dzhanibekov)",
            SceneId::Pendulum => "2 pendulum",
            SceneId::TopCusp => "3a top, cusp start",
            SceneId::TopSteady => "3b top, steady precession",
            SceneId::RodOnSphere => "4 rod end on sphere",
            SceneId::RodOnCircle => "4 rod end on circle",
        }
    }

    /// The scene's physical parameters, initial state and constraint as `docs/scenes.md` defines them.
    pub fn parameters(self) -> SceneParameters {
        match self {
            SceneId::Cuboid => {
                // Cuboid a, b, c = 1, 2, 3 along x, y, z: I = m/12 (b²+c², a²+c², a²+b²).
                let initial_energy = 42.2970833333333;
                SceneParameters {
                    mass: 1.0,
                    principal_moments: Vector3::new(13.0 / 12.0, 10.0 / 12.0, 5.0 / 12.0),
                    gravity: 0.0,
                    initial_com: Vector3::zeros(),
                    initial_orientation: UnitQuaternion::identity(),
                    initial_body_angular_velocity: Vector3::new(0.1, 10.0, 0.0),
                    initial_com_velocity: Vector3::new(1.0, 0.5, 0.0),
                    duration: 10.0,
                    constraint: SceneConstraint::Free,
                    potential_zero_height: 0.0,
                    initial_energy,
                    energy_scale: initial_energy,
                }
            }
            SceneId::Pendulum => {
                // θ is a rotation about world y; the hinge is the rod end at body offset (0, 0, d), d = 0.5,
                // so the rod hangs straight down at θ = 0 and the CoM starts at −R₀ (0, 0, d) = (−0.5, 0, 0).
                let hinge_anchor = Vector3::new(0.0, 0.0, 0.5);
                let initial_orientation = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), PENDULUM_INITIAL_ANGLE);
                let energy_scale = 4.905; // m g d
                SceneParameters {
                    mass: 1.0,
                    principal_moments: rod_principal_moments(),
                    gravity: GRAVITY,
                    initial_com: -(initial_orientation * hinge_anchor),
                    initial_orientation,
                    initial_body_angular_velocity: Vector3::zeros(),
                    initial_com_velocity: Vector3::zeros(),
                    duration: 10.0,
                    constraint: SceneConstraint::Hinge {
                        pivot: Vector3::zeros(),
                        axis: Vector3::y(),
                        body_anchor: hinge_anchor,
                    },
                    // Potential zero at the hanging equilibrium, CoM height −d.
                    potential_zero_height: -0.5,
                    initial_energy: 4.905,
                    energy_scale,
                }
            }
            SceneId::TopCusp | SceneId::TopSteady => {
                // Solid cone M = 1, h = 1, R = 1, tip pinned at the origin, CoM on the axis at l = 3h/4 from the
                // tip; transverse moment about the CoM 3/80 h² + 3/20 R² = 0.1875, axial 3/10 R² = 0.3.
                let tip_anchor = Vector3::new(0.0, 0.0, -0.75);
                let initial_orientation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), TOP_INITIAL_TILT);
                let (initial_body_angular_velocity, initial_energy) = if self == SceneId::TopCusp {
                    (Vector3::new(0.0, 0.0, TOP_SPIN), 66.371781908344)
                } else {
                    // Euler angles z-x-z at ψ = 0: body ω = (θ̇, φ̇ sin θ, ω₃).
                    let precession = TOP_SLOW_PRECESSION_RATE * TOP_INITIAL_TILT.sin();
                    (Vector3::new(0.0, precession, TOP_SPIN), 66.5704221941551)
                };
                let initial_com = -(initial_orientation * tip_anchor);
                // The tip is at rest: v = ω × (CoM − tip).
                let initial_com_velocity = (initial_orientation * initial_body_angular_velocity).cross(&initial_com);
                SceneParameters {
                    mass: 1.0,
                    principal_moments: Vector3::new(0.1875, 0.1875, 0.3),
                    gravity: GRAVITY,
                    initial_com,
                    initial_orientation,
                    initial_body_angular_velocity,
                    initial_com_velocity,
                    duration: 10.0,
                    constraint: SceneConstraint::BallJoint {
                        pivot: Vector3::zeros(),
                        body_anchor: tip_anchor,
                    },
                    potential_zero_height: 0.0,
                    initial_energy,
                    energy_scale: initial_energy,
                }
            }
            SceneId::RodOnSphere | SceneId::RodOnCircle => {
                let body_anchor = Vector3::new(0.0, 0.0, 0.5);
                let (centre, radius) = (Vector3::zeros(), 0.5);
                SceneParameters {
                    mass: 1.0,
                    principal_moments: rod_principal_moments(),
                    gravity: GRAVITY,
                    initial_com: Vector3::new(0.5, 0.0, -0.5),
                    initial_orientation: UnitQuaternion::identity(),
                    initial_body_angular_velocity: Vector3::new(1.0, 0.0, 0.0),
                    initial_com_velocity: Vector3::new(0.0, 0.5, 0.0),
                    duration: 5.0,
                    constraint: if self == SceneId::RodOnSphere {
                        SceneConstraint::PointOnSphere {
                            body_anchor,
                            centre,
                            radius,
                        }
                    } else {
                        SceneConstraint::PointOnCircle {
                            body_anchor,
                            centre,
                            radius,
                            normal: Vector3::z(),
                        }
                    },
                    potential_zero_height: 0.0,
                    initial_energy: -4.73833333333333,
                    energy_scale: 9.81, // m g L
                }
            }
        }
    }

    /// The reference CSV, embedded at compile time (format: [`crate::trajectory`]).
    pub fn reference_csv(self) -> &'static str {
        match self {
            SceneId::Cuboid => include_str!("../data/ref_scene1_cuboid.csv"),
            SceneId::Pendulum => include_str!("../data/ref_scene2_pendulum.csv"),
            SceneId::TopCusp => include_str!("../data/ref_scene3a_top_cusp.csv"),
            SceneId::TopSteady => include_str!("../data/ref_scene3b_top_steady.csv"),
            SceneId::RodOnSphere => include_str!("../data/ref_scene4_rod_end_on_sphere.csv"),
            SceneId::RodOnCircle => include_str!("../data/ref_scene4_rod_end_on_circle.csv"),
        }
    }

    /// The reference trajectory (DOP853, rtol = atol = 1e-13, sampled every 0.01 s), parsed from
    /// [`Self::reference_csv`].
    pub fn reference_trajectory(self) -> Result<Trajectory, TrajectoryError> {
        Trajectory::from_csv(self.reference_csv())
    }

    /// The published end state at t = T (`docs/scenes.md`; checked against the reference file's last row).
    pub fn published_end_state(self) -> Sample {
        let (t, position, orientation, velocity, angular_velocity) = match self {
            SceneId::Cuboid => (
                10.0,
                [10.0, 5.0, 0.0],
                [
                    -0.463228090409878,
                    -0.0507369839007738,
                    -0.882937049497386,
                    -0.0571634616229237,
                ],
                [1.0, 0.5, 0.0],
                [0.839063006458838, 9.99039218091608, -0.11139944828783],
            ),
            SceneId::Pendulum => (
                10.0,
                [-0.348411203396954, 0.0, -0.358621852858253],
                [0.926618504487285, 0.0, 0.376002855230845, 0.0],
                [1.64765110502265, 0.0, -1.60073932947461],
                [0.0, -4.59439683301701, 0.0],
            ),
            SceneId::TopCusp => (
                10.0,
                [0.474423643780064, -0.125181657484673, 0.567231662420071],
                [
                    0.405864586892671,
                    0.342785003302251,
                    0.0659090274370247,
                    0.844646895880056,
                ],
                [0.582394593267269, 0.887011487583568, -0.291352207186243],
                [11.8216633035033, -2.50515170344886, 16.0039098289965],
            ),
            SceneId::TopSteady => (
                10.0,
                [0.342555979044154, 0.152579163784302, 0.649519052838317],
                [
                    0.872222326844184,
                    0.00649104851317581,
                    0.258737636220532,
                    0.415019173589277,
                ],
                [-0.222097289249157, 0.498631349620936, -3.5527136788005e-15],
                [8.55905621998406, 3.81232184144614, 17.6844130869309],
            ),
            SceneId::RodOnSphere => (
                5.0,
                [-0.21145470800258, -0.490125973478692, -0.571172237973089],
                [
                    0.575769924250724,
                    -0.364716188781198,
                    0.537254101706334,
                    0.496819007455386,
                ],
                [-0.264821842742178, -1.11321479751041, 0.390699380434321],
                [-0.425219166993032, -0.170394617141798, 1.73281864224853],
            ),
            SceneId::RodOnCircle => (
                5.0,
                [-0.0378483058571736, -0.515245148069653, -0.497396343982359],
                [
                    0.998693080277072,
                    -0.0224585353037675,
                    -0.0458177935922082,
                    0.00291125214415449,
                ],
                [0.47319266156998, -0.159902762552223, 0.0314587764998987],
                [-0.255587256020488, -0.562165041212586, 0.00165274031301047],
            ),
        };
        let [w, x, y, z] = orientation;
        Sample {
            t,
            position: position.into(),
            // Printed to 15 digits, so normalising changes it by ~1e-15 only.
            orientation: UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
            velocity: velocity.into(),
            angular_velocity: angular_velocity.into(),
        }
    }
}

/// Scene 1 analytic values printed in `docs/scenes.md` (Landau–Lifshitz §37 closed form).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DzhanibekovValues {
    /// 2 T_rot = ω·Iω.
    pub twice_rotational_energy: f64,
    /// |L|.
    pub angular_momentum_norm: f64,
    /// λ (1/s), the rate of the elliptic argument u = λt + K.
    pub lambda: f64,
    /// k², the elliptic parameter.
    pub parameter: f64,
    /// K(k²).
    pub quarter_period_integral: f64,
    /// Period of the body-frame angular velocity, 4K/λ (s).
    pub angular_velocity_period: f64,
    /// Interval between flips (sign changes of ω_y), 2K/λ (s).
    pub flip_interval: f64,
    /// The flip instants in [0, 10] s.
    pub flip_instants: [f64; 4],
}

/// Scene 1's published Dzhanibekov values.
pub const CUBOID_VALUES: DzhanibekovValues = DzhanibekovValues {
    twice_rotational_energy: 83.3441666666667,
    angular_momentum_norm: 8.33403747025147,
    lambda: 4.80434418801599,
    parameter: 0.999792043255003,
    quarter_period_integral: 5.62562508653737,
    angular_velocity_period: 4.68378189936515,
    flip_interval: 2.34189094968257,
    flip_instants: [1.170945474841, 3.512836424524, 5.854727374206, 8.196618323889],
};

/// Scene 2 analytic values printed in `docs/scenes.md`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumValues {
    /// ω₀ = √(m g d / I_p) (rad/s).
    pub small_amplitude_frequency: f64,
    /// 2π/ω₀ (s).
    pub small_amplitude_period: f64,
    /// k = sin(θ₀/2).
    pub modulus: f64,
    /// K(k²).
    pub quarter_period_integral: f64,
    /// 4K/ω₀ (s).
    pub exact_period: f64,
}

// k is kept as printed in docs/scenes.md (15 digits), not replaced by FRAC_1_SQRT_2.
#[allow(clippy::approx_constant)]
/// Scene 2's published pendulum values.
pub const PENDULUM_VALUES: PendulumValues = PendulumValues {
    small_amplitude_frequency: 3.83601355576333,
    small_amplitude_period: 1.63794658591328,
    modulus: 0.707106781186547,
    quarter_period_integral: 1.85407467730137,
    exact_period: 1.93333485437325,
};

/// Scene 3 analytic values printed in `docs/scenes.md` (Goldstein §5.7, u = cos θ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTopValues {
    /// a = I₃ω₃/I₁ (rad/s).
    pub a: f64,
    /// β = 2Mgl/I₁ (1/s²).
    pub beta: f64,
    /// Slow and fast steady precession rates at θ₀ = π/6, ω₃ = 20 (rad/s).
    pub slow_precession_rate: f64,
    /// Fast steady precession rate at θ₀ = π/6, ω₃ = 20 (rad/s).
    pub fast_precession_rate: f64,
    /// Mgl/(I₃ω₃) (rad/s).
    pub gyroscopic_precession_rate: f64,
    /// √(4 I₁ M g l)/I₃ (rad/s).
    pub minimum_stable_spin: f64,
    /// 3a: b = a cos θ₀ (rad/s).
    pub cusp_b: f64,
    /// 3a: α = β cos θ₀ (1/s²).
    pub cusp_alpha: f64,
    /// 3a: the roots u₁ < u₂ < u₃ of f(u).
    pub cusp_roots: [f64; 3],
    /// 3a nutation bounds (rad).
    pub theta_min: f64,
    /// 3a largest tilt θ_max (rad).
    pub theta_max: f64,
    /// 3a nutation period (s).
    pub nutation_period: f64,
    /// 3a precession angle per nutation period (rad).
    pub precession_per_nutation: f64,
    /// 3a mean precession rate (rad/s).
    pub mean_precession_rate: f64,
}

/// Scene 3's published heavy-top values.
pub const HEAVY_TOP_VALUES: HeavyTopValues = HeavyTopValues {
    a: 8.0,
    beta: 19.62,
    slow_precession_rate: TOP_SLOW_PRECESSION_RATE,
    fast_precession_rate: 7.78198426206417,
    gyroscopic_precession_rate: 1.22625,
    minimum_stable_spin: 15.6604597633658,
    cusp_b: 6.92820323027551,
    cusp_alpha: 16.9914184222507,
    cusp_roots: [0.717112987082496, 0.866025403784432, 2.54486458682169],
    theta_min: 0.523598775598312,
    theta_max: 0.771145196934738,
    nutation_period: 1.0716421634452,
    precession_per_nutation: 1.50504453792044,
    mean_precession_rate: 1.40442825903929,
};

#[cfg(test)]
mod tests {
    use super::*;

    /// Component-wise comparison |actual − expected| ≤ tolerance · max(1, |expected|) over t, position, quaternion
    /// (sign-aligned), velocity and angular velocity.
    fn assert_states_close(actual: &Sample, expected: &Sample, tolerance: f64, context: &str) {
        let components = |sample: &Sample, sign: f64| {
            let q = sample.orientation.quaternion();
            let mut values = vec![sample.t];
            values.extend(sample.position.iter());
            values.extend([q.w, q.i, q.j, q.k].map(|component| sign * component));
            values.extend(sample.velocity.iter());
            values.extend(sample.angular_velocity.iter());
            values
        };
        let sign = actual
            .orientation
            .quaternion()
            .dot(expected.orientation.quaternion())
            .signum();
        for (index, (a, e)) in components(actual, sign)
            .iter()
            .zip(components(expected, 1.0))
            .enumerate()
        {
            assert!(
                (a - e).abs() <= tolerance * e.abs().max(1.0),
                "{context}: component {index} (t, p, q, v, ω order): {a} vs {e}"
            );
        }
    }

    #[test]
    fn reference_trajectories_are_on_the_metric_grid() {
        for scene in SceneId::ALL {
            let trajectory = scene.reference_trajectory().unwrap();
            let duration = scene.parameters().duration;
            let expected_samples = (duration / SAMPLE_INTERVAL).round() as usize + 1;
            assert_eq!(trajectory.samples().len(), expected_samples, "{}", scene.label());
            for (index, sample) in trajectory.samples().iter().enumerate() {
                assert!(
                    (sample.t - index as f64 * SAMPLE_INTERVAL).abs() < 1e-12,
                    "{} sample {index}",
                    scene.label()
                );
            }
        }
    }

    #[test]
    fn reference_starts_at_the_scene_initial_state() {
        // The parameters are re-derived from the scenes' definitions (docs/scenes.md), the CSV is the integrator's
        // output: they agree to a few ulp.
        for scene in SceneId::ALL {
            let first = *scene.reference_trajectory().unwrap().first();
            assert_states_close(&first, &scene.parameters().initial_state(), 1e-15, scene.label());
        }
    }

    #[test]
    fn reference_ends_at_the_published_end_state() {
        // Published to 15 significant digits: rounding ≤ 5e-15 relative (absolute for components below 1).
        for scene in SceneId::ALL {
            let last = *scene.reference_trajectory().unwrap().last();
            assert_states_close(&last, &scene.published_end_state(), 5e-15, scene.label());
        }
    }

    #[test]
    fn initial_energy_matches_the_published_value() {
        for scene in SceneId::ALL {
            let parameters = scene.parameters();
            let energy = parameters.mechanical_energy(&parameters.initial_state());
            let relative = ((energy - parameters.initial_energy) / parameters.initial_energy).abs();
            assert!(
                relative < 1e-14,
                "{}: E0 = {energy} vs {}",
                scene.label(),
                parameters.initial_energy
            );
        }
    }
}
