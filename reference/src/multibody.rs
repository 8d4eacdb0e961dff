//! The multi-body reference scenes of `docs/scenes.md`: M1, the 3D double pendulum (two hinges, an open chain);
//! M2, the four-bar linkage (a closed loop); M3, the N-link chain of ball joints (scaling). Their parameters,
//! exact initial states from joint coordinates (forward kinematics, plain vectors and quaternions), the
//! embedded reference trajectories, published values, and the violation of each joint computed from the
//! bodies' poses alone.
//!
//! Every link is a solid cuboid of extents (a, b, c) along its body axes with its body frame at the centre of
//! mass on the principal axes. Gravity is 9.81 m/s² along −z, potential energy zero at z = 0.

use std::f64::consts::FRAC_PI_2;

use nalgebra::{UnitQuaternion, Vector3};

use crate::scenes::GRAVITY;
use crate::trajectory::TrajectoryError;

/// A cuboid link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    /// Mass (kg).
    pub mass: f64,
    /// Side lengths along body x, y, z (m).
    pub extents: Vector3<f64>,
}

impl Link {
    /// `m/12 (b² + c², a² + c², a² + b²)`.
    pub fn principal_moments(&self) -> Vector3<f64> {
        let s = self.extents.component_mul(&self.extents);
        self.mass / 12.0 * Vector3::new(s.y + s.z, s.x + s.z, s.x + s.y)
    }
}

/// One body's state in classical terms (world frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// Centre of mass (m).
    pub position: Vector3<f64>,
    /// Body → world.
    pub orientation: UnitQuaternion<f64>,
    /// Centre-of-mass velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Angular velocity, world axes (rad/s).
    pub angular_velocity: Vector3<f64>,
}

impl BodyState {
    /// World position of a body point (body coordinates from the centre of mass).
    pub fn world_point(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.orientation * body_point
    }

    /// World velocity of a body point.
    pub fn point_velocity(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.velocity + self.angular_velocity.cross(&(self.orientation * body_point))
    }

    /// Kinetic plus potential energy of a link in this state.
    pub fn energy(&self, link: &Link) -> f64 {
        let body_omega = self.orientation.inverse_transform_vector(&self.angular_velocity);
        let rotational = body_omega.component_mul(&link.principal_moments()).dot(&body_omega);
        0.5 * (link.mass * self.velocity.norm_squared() + rotational) + link.mass * GRAVITY * self.position.z
    }
}

/// A body's pose: centre of mass and orientation (body → world).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Centre of mass in the world frame (m).
    pub position: Vector3<f64>,
    /// Rotation body → world.
    pub orientation: UnitQuaternion<f64>,
}

impl Pose {
    /// World position of a body point (body coordinates from the centre of mass, m).
    pub fn world_point(&self, body_point: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.orientation * body_point
    }
}

/// One sample of a mechanism's reference: every body's pose and the energy.
#[derive(Clone, Debug, PartialEq)]
pub struct MechanismSample {
    /// Time (s).
    pub t: f64,
    /// Every body's pose, in the mechanism's link order.
    pub bodies: Vec<Pose>,
    /// Total mechanical energy of the mechanism (J).
    pub energy: f64,
}

/// The rows of a reference CSV with a header, as numbers.
fn parse_rows(text: &str, columns: usize) -> Result<Vec<Vec<f64>>, TrajectoryError> {
    let mut lines = text.lines().enumerate();
    lines.next().ok_or(TrajectoryError::MissingHeader)?;
    lines
        .filter(|(_, line)| !line.trim().is_empty())
        .map(|(index, line)| {
            let fields: Vec<&str> = line.split(',').collect();
            if fields.len() != columns {
                return Err(TrajectoryError::FieldCount {
                    line: index + 1,
                    found: fields.len(),
                });
            }
            fields
                .iter()
                .map(|field| {
                    field
                        .trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| TrajectoryError::InvalidNumber {
                            line: index + 1,
                            column: "a numeric column",
                            text: field.to_string(),
                        })
                })
                .collect()
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------------------------
// M1: the 3D double pendulum.

/// M1 (`docs/scenes.md`): link 1 hinged to the world about world x at its top end; link 2 hinged to link 1's
/// bottom end about link 1's body y. Joint angles q1 (link 1 about world x) and q2 (link 2 relative to link 1,
/// about link 1's y), zero hanging straight down with all frames aligned with the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DoublePendulum {
    /// Link 1 (upper) and link 2 (lower).
    pub links: [Link; 2],
    /// Hinge 1's world point and its body point on link 1; its axis is world x, link 1's body x.
    pub pivot: Vector3<f64>,
    /// Hinge 1's point on link 1, in link 1's body coordinates from its centre of mass (m).
    pub hinge_1_on_link_1: Vector3<f64>,
    /// Hinge 2's body points on link 1 and link 2; its axis is link 1's body y (= link 2's).
    pub hinge_2_on_link_1: Vector3<f64>,
    /// Hinge 2's point on link 2, in link 2's body coordinates from its centre of mass (m).
    pub hinge_2_on_link_2: Vector3<f64>,
    /// Initial joint angles q1, q2 (rad).
    pub initial_angles: [f64; 2],
    /// Initial joint rates q̇1, q̇2 (rad/s).
    pub initial_rates: [f64; 2],
    /// Simulated time T (s).
    pub duration: f64,
}

/// M1's parameters as `docs/scenes.md` gives them.
pub const DOUBLE_PENDULUM: DoublePendulum = DoublePendulum {
    links: [
        Link {
            mass: 1.0,
            extents: Vector3::new(0.1, 0.1, 1.0),
        },
        Link {
            mass: 0.5,
            extents: Vector3::new(0.08, 0.08, 0.8),
        },
    ],
    pivot: Vector3::new(0.0, 0.0, 0.0),
    hinge_1_on_link_1: Vector3::new(0.0, 0.0, 0.5),
    hinge_2_on_link_1: Vector3::new(0.0, 0.0, -0.5),
    hinge_2_on_link_2: Vector3::new(0.0, 0.0, 0.4),
    initial_angles: [1.0, 0.6],
    initial_rates: [1.0, -0.5],
    duration: 10.0,
};

/// M1's published end state at T = 10 s (`docs/scenes.md`): per link the centre of mass and the quaternion
/// (w, x, y, z), then the energy (J).
pub const DOUBLE_PENDULUM_END: ([[f64; 7]; 2], f64) = (
    [
        [
            0.0,
            -0.323964111512135,
            -0.380850698374249,
            0.938536466193109,
            -0.345180100274844,
            0.0,
            0.0,
        ],
        [
            0.0608014516879924,
            -0.904087925111243,
            -1.06284154767385,
            0.935806030844964,
            -0.344175885754454,
            -0.0715385980324072,
            0.0263108588018009,
        ],
    ],
    -5.54325921838849,
);

impl DoublePendulum {
    /// Both links' states at joint angles `q` and rates `rates` (forward kinematics).
    pub fn state(&self, q: [f64; 2], rates: [f64; 2]) -> [BodyState; 2] {
        let first = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), q[0]);
        let second = first * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), q[1]);
        let omega_1 = rates[0] * Vector3::x();
        let omega_2 = omega_1 + rates[1] * (first * Vector3::y());
        let centre_1 = self.pivot - first * self.hinge_1_on_link_1;
        let hinge_2 = centre_1 + first * self.hinge_2_on_link_1;
        let centre_2 = hinge_2 - second * self.hinge_2_on_link_2;
        let hinge_2_velocity = omega_1.cross(&(hinge_2 - self.pivot));
        [
            BodyState {
                position: centre_1,
                orientation: first,
                velocity: omega_1.cross(&(centre_1 - self.pivot)),
                angular_velocity: omega_1,
            },
            BodyState {
                position: centre_2,
                orientation: second,
                velocity: hinge_2_velocity + omega_2.cross(&(centre_2 - hinge_2)),
                angular_velocity: omega_2,
            },
        ]
    }

    /// Both links' states at the initial joint angles and rates of `docs/scenes.md`.
    pub fn initial_state(&self) -> [BodyState; 2] {
        self.state(self.initial_angles, self.initial_rates)
    }

    /// The reference trajectory (`data/ref_m1_double_pendulum.csv`), one sample every 0.01 s.
    pub fn reference(&self) -> Result<Vec<MechanismSample>, TrajectoryError> {
        let rows = parse_rows(include_str!("../data/ref_m1_double_pendulum.csv"), 16)?;
        Ok(rows
            .iter()
            .map(|row| MechanismSample {
                t: row[0],
                bodies: (0..2)
                    .map(|k| {
                        let c = &row[1 + 7 * k..8 + 7 * k];
                        Pose {
                            position: Vector3::new(c[0], c[1], c[2]),
                            orientation: UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                                c[3], c[4], c[5], c[6],
                            )),
                        }
                    })
                    .collect(),
                energy: row[15],
            })
            .collect())
    }

    /// The largest violation of the two hinges (m) at these poses: each hinge point's distance between its two
    /// bodies, and each axis's misalignment measured as the distance between the two bodies' points 1 m along
    /// it.
    pub fn violation(&self, poses: &[Pose]) -> f64 {
        let (link_1, link_2) = (&poses[0], &poses[1]);
        let along = |pose: &Pose, point: Vector3<f64>, axis: Vector3<f64>| pose.world_point(&(point + axis));
        let hinge_1 = (link_1.world_point(&self.hinge_1_on_link_1) - self.pivot)
            .norm()
            .max((along(link_1, self.hinge_1_on_link_1, Vector3::x()) - (self.pivot + Vector3::x())).norm());
        let hinge_2 = (link_1.world_point(&self.hinge_2_on_link_1) - link_2.world_point(&self.hinge_2_on_link_2))
            .norm()
            .max(
                (along(link_1, self.hinge_2_on_link_1, Vector3::y())
                    - along(link_2, self.hinge_2_on_link_2, Vector3::y()))
                .norm(),
            );
        hinge_1.max(hinge_2)
    }
}

// ---------------------------------------------------------------------------------------------------------------
// M2: the four-bar linkage.

/// M2 (`docs/scenes.md`): planar in the x–z plane, every hinge axis world y; ground pivots A = (0, 0, 0) and
/// D = (L0, 0, 0); crank AB, coupler BC, rocker DC, each a cuboid (w, w, L) with body z along the link from its
/// first joint to its second (A→B, B→C, D→C) and body y = world y. The crank angle φ is AB's angle from +x
/// towards +z; C is on the left of B→D.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBar {
    /// Ground length A–D and the link lengths L1 (crank), L2 (coupler), L3 (rocker) (m).
    pub ground: f64,
    /// Link lengths L1 (crank), L2 (coupler), L3 (rocker) (m).
    pub lengths: [f64; 3],
    /// Cross-section side w of every link (m).
    pub width: f64,
    /// Masses of the crank, coupler and rocker (kg).
    pub masses: [f64; 3],
    /// Initial crank angle φ₀ (rad).
    pub initial_angle: f64,
    /// Initial crank rate φ̇₀ (rad/s).
    pub initial_rate: f64,
    /// Simulated time T (s).
    pub duration: f64,
    /// The crank returns to φ₀ + 2πk every this many seconds (`docs/scenes.md`).
    pub revolution_period: f64,
}

/// M2's parameters as `docs/scenes.md` gives them.
pub const FOUR_BAR: FourBar = FourBar {
    ground: 1.0,
    lengths: [0.3, 1.0, 0.8],
    width: 0.05,
    masses: [0.5, 1.0, 0.8],
    initial_angle: 1.0,
    initial_rate: 6.0,
    duration: 5.0,
    revolution_period: 0.7906242901366745,
};

/// M2's published end state at T = 5 s: φ (unwrapped), α2, α3 (rad) and the energy (J).
pub const FOUR_BAR_END: ([f64; 3], f64) = (
    [39.87082445943846, 0.516787824385687, 1.95547463448371],
    10.1849020920329,
);

/// The four-bar's configuration at one crank angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarConfiguration {
    /// Joint B (crank–coupler) and C (coupler–rocker), in the x–z plane as (x, z).
    pub b: [f64; 2],
    /// Joint C (coupler–rocker) as (x, z) (m).
    pub c: [f64; 2],
    /// Link direction angles: φ (crank), α2 (B→C), α3 (D→C).
    pub angles: [f64; 3],
    /// dα2/dφ, dα3/dφ.
    pub ratios: [f64; 2],
}

/// The orientation of a link whose body z points along `angle` from +x towards +z in the x–z plane, body y
/// along world y: a rotation about y by π/2 − angle.
pub fn link_orientation(angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::y_axis(), FRAC_PI_2 - angle)
}

impl FourBar {
    /// The links, crank first.
    pub fn links(&self) -> [Link; 3] {
        std::array::from_fn(|k| Link {
            mass: self.masses[k],
            extents: Vector3::new(self.width, self.width, self.lengths[k]),
        })
    }

    /// The loop closed at crank angle φ: C is the intersection of the circles about B (radius L2) and D
    /// (radius L3) on the left of B→D (as `four_bar.py` builds it).
    pub fn configuration(&self, phi: f64) -> FourBarConfiguration {
        let [l1, l2, l3] = self.lengths;
        let b = [l1 * phi.cos(), l1 * phi.sin()];
        let (dx, dz) = (self.ground - b[0], -b[1]);
        let d = (dx * dx + dz * dz).sqrt();
        let a = (l2 * l2 - l3 * l3 + d * d) / (2.0 * d);
        let h = (l2 * l2 - a * a).sqrt();
        let p = [b[0] + a * dx / d, b[1] + a * dz / d];
        let c = [p[0] - h * dz / d, p[1] + h * dx / d];
        let alpha_2 = (c[1] - b[1]).atan2(c[0] - b[0]);
        let alpha_3 = c[1].atan2(c[0] - self.ground);
        let denominator = (alpha_2 - alpha_3).sin();
        FourBarConfiguration {
            b,
            c,
            angles: [phi, alpha_2, alpha_3],
            ratios: [
                l1 * (alpha_3 - phi).sin() / (l2 * denominator),
                l1 * (alpha_2 - phi).sin() / (l3 * denominator),
            ],
        }
    }

    /// The three links' states at crank angle φ turning at φ̇ (the others at the rates the loop implies).
    pub fn state(&self, phi: f64, rate: f64) -> [BodyState; 3] {
        let configuration = self.configuration(phi);
        let [l1, l2, l3] = self.lengths;
        let rates = [rate, configuration.ratios[0] * rate, configuration.ratios[1] * rate];
        let direction = |angle: f64| Vector3::new(angle.cos(), 0.0, angle.sin());
        // d/dt of the direction at angle α is α̇ (−sin α, 0, cos α): a rotation of −α̇ about y.
        let turning = |angle: f64| Vector3::new(-angle.sin(), 0.0, angle.cos());
        let [phi, alpha_2, alpha_3] = configuration.angles;
        let b = Vector3::new(configuration.b[0], 0.0, configuration.b[1]);
        let d = Vector3::new(self.ground, 0.0, 0.0);
        let centres = [
            0.5 * l1 * direction(phi),
            b + 0.5 * l2 * direction(alpha_2),
            d + 0.5 * l3 * direction(alpha_3),
        ];
        let b_velocity = l1 * rates[0] * turning(phi);
        let velocities = [
            0.5 * l1 * rates[0] * turning(phi),
            b_velocity + 0.5 * l2 * rates[1] * turning(alpha_2),
            0.5 * l3 * rates[2] * turning(alpha_3),
        ];
        std::array::from_fn(|k| BodyState {
            position: centres[k],
            orientation: link_orientation(configuration.angles[k]),
            velocity: velocities[k],
            angular_velocity: Vector3::new(0.0, -rates[k], 0.0),
        })
    }

    /// The three links' states at the initial crank angle and rate of `docs/scenes.md`.
    pub fn initial_state(&self) -> [BodyState; 3] {
        self.state(self.initial_angle, self.initial_rate)
    }

    /// The reference trajectory (`data/ref_m2_four_bar.csv`): poses from the centres of mass and the link
    /// angles; the crank angle φ (unwrapped) per sample is [`FourBar::reference_angles`].
    pub fn reference(&self) -> Result<Vec<MechanismSample>, TrajectoryError> {
        let rows = parse_rows(include_str!("../data/ref_m2_four_bar.csv"), 11)?;
        Ok(rows
            .iter()
            .map(|row| MechanismSample {
                t: row[0],
                bodies: (0..3)
                    .map(|k| Pose {
                        position: Vector3::new(row[1 + 2 * k], 0.0, row[2 + 2 * k]),
                        orientation: link_orientation(row[7 + k]),
                    })
                    .collect(),
                energy: row[10],
            })
            .collect())
    }

    /// The reference link angles per sample: φ (unwrapped), α2, α3.
    pub fn reference_angles(&self) -> Result<Vec<[f64; 3]>, TrajectoryError> {
        let rows = parse_rows(include_str!("../data/ref_m2_four_bar.csv"), 11)?;
        Ok(rows.iter().map(|row| [row[7], row[8], row[9]]).collect())
    }

    /// The body points of the four hinges as (body index, body point) pairs: A on the crank, B on crank and
    /// coupler, C on coupler and rocker, D on the rocker.
    pub fn joint_points(&self) -> [[(usize, Vector3<f64>); 2]; 2] {
        let [l1, l2, l3] = self.lengths;
        [
            [
                (0, Vector3::new(0.0, 0.0, l1 / 2.0)),
                (1, Vector3::new(0.0, 0.0, -l2 / 2.0)),
            ],
            [
                (1, Vector3::new(0.0, 0.0, l2 / 2.0)),
                (2, Vector3::new(0.0, 0.0, l3 / 2.0)),
            ],
        ]
    }

    /// The largest violation of the four hinges (m) at these poses: A and D against the ground pivots, B and C
    /// between their two links, and every link's tilt out of the x–z plane (its body y against world y, as
    /// the distance it moves a point 1 m along the axis).
    pub fn violation(&self, poses: &[Pose]) -> f64 {
        let [l1, _, l3] = self.lengths;
        let ground_a = (poses[0].world_point(&Vector3::new(0.0, 0.0, -l1 / 2.0))).norm();
        let ground_d =
            (poses[2].world_point(&Vector3::new(0.0, 0.0, -l3 / 2.0)) - Vector3::new(self.ground, 0.0, 0.0)).norm();
        let inner = self
            .joint_points()
            .iter()
            .map(|[(i, p), (j, q)]| (poses[*i].world_point(p) - poses[*j].world_point(q)).norm())
            .fold(0.0, f64::max);
        let tilt = poses
            .iter()
            .map(|pose| (pose.orientation * Vector3::y() - Vector3::y()).norm())
            .fold(0.0, f64::max);
        ground_a.max(ground_d).max(inner).max(tilt)
    }
}

/// The times at which the unwrapped crank angle `angle(t)` first reaches `start + 2πk` (k = 1, 2, …): each
/// crossing between two samples located by cubic Hermite interpolation of the angle and its rate, whose error
/// is O(h⁴) in the sample spacing h (with h = 1e-3 s and the crank's 8 rad/s, below 1e-12 s).
pub fn revolution_times(samples: &[(f64, f64, f64)], start: f64) -> Vec<f64> {
    let mut times = Vec::new();
    let mut k = 1;
    for pair in samples.windows(2) {
        let ((t0, a0, r0), (t1, a1, r1)) = (pair[0], pair[1]);
        let target = start + 2.0 * std::f64::consts::PI * k as f64;
        if a0 < target && a1 >= target {
            let h = t1 - t0;
            // Hermite basis on s ∈ [0, 1]; Newton from the linear guess.
            let value = |s: f64| {
                let (s2, s3) = (s * s, s * s * s);
                (2.0 * s3 - 3.0 * s2 + 1.0) * a0
                    + (s3 - 2.0 * s2 + s) * h * r0
                    + (-2.0 * s3 + 3.0 * s2) * a1
                    + (s3 - s2) * h * r1
            };
            let slope = |s: f64| {
                let s2 = s * s;
                (6.0 * s2 - 6.0 * s) * a0
                    + (3.0 * s2 - 4.0 * s + 1.0) * h * r0
                    + (-6.0 * s2 + 6.0 * s) * a1
                    + (3.0 * s2 - 2.0 * s) * h * r1
            };
            let mut s = (target - a0) / (a1 - a0);
            for _ in 0..20 {
                let step = (value(s) - target) / slope(s);
                s -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            times.push(t0 + s * h);
            k += 1;
        }
    }
    times
}

// ---------------------------------------------------------------------------------------------------------------
// M3: the N-link chain.

/// M3 (`docs/scenes.md`): N identical links joined end to end by ball joints (link k's body (0, 0, −L/2) to link
/// k+1's body (0, 0, +L/2)), the first link's top end at the world origin; initially straight and horizontal
/// along +y (every link turned +90° about world x), at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain {
    /// The link every joint connects (all links are identical).
    pub link: Link,
    /// Simulated time T (s).
    pub duration: f64,
}

/// M3's parameters as `docs/scenes.md` gives them; the number of links N is chosen by the caller.
pub const CHAIN: Chain = Chain {
    link: Link {
        mass: 0.5,
        extents: Vector3::new(0.05, 0.05, 0.5),
    },
    duration: 10.0,
};

/// The chain lengths of M3 in `docs/scenes.md`.
pub const CHAIN_LENGTHS: [usize; 7] = [1, 2, 4, 8, 16, 32, 64];

impl Chain {
    /// Half a link: the joints sit at body (0, 0, ±L/2).
    pub fn half_length(&self) -> f64 {
        0.5 * self.link.extents.z
    }

    /// The initial state of an N-link chain.
    pub fn initial_state(&self, links: usize) -> Vec<BodyState> {
        let orientation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2);
        (0..links)
            .map(|k| BodyState {
                position: Vector3::new(0.0, self.half_length() * (2 * k + 1) as f64, 0.0),
                orientation,
                velocity: Vector3::zeros(),
                angular_velocity: Vector3::zeros(),
            })
            .collect()
    }

    /// The largest ball-joint violation (m): the first link's top against the origin, and each joint's two
    /// body points against each other.
    pub fn violation(&self, poses: &[Pose]) -> f64 {
        let (top, bottom) = (
            Vector3::new(0.0, 0.0, self.half_length()),
            Vector3::new(0.0, 0.0, -self.half_length()),
        );
        let first = poses.first().map_or(0.0, |p| p.world_point(&top).norm());
        poses
            .windows(2)
            .map(|pair| (pair[0].world_point(&bottom) - pair[1].world_point(&top)).norm())
            .fold(first, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The forward kinematics reproduce the reference files' first rows and energies, and the four-bar's
    /// loop closes.
    #[test]
    fn initial_states_match_the_reference_files() {
        let m1 = DOUBLE_PENDULUM;
        let reference = m1.reference().unwrap();
        let first = &reference[0];
        let state = m1.initial_state();
        for (s, pose) in state.iter().zip(&first.bodies) {
            assert!((s.position - pose.position).norm() < 1e-14);
            assert!(s.orientation.angle_to(&pose.orientation) < 1e-14);
        }
        let energy: f64 = state.iter().zip(&m1.links).map(|(s, l)| s.energy(l)).sum();
        assert!((energy - first.energy).abs() < 1e-13, "{energy} vs {}", first.energy);
        assert_eq!(reference.len(), 1001);
        let poses: Vec<Pose> = state
            .iter()
            .map(|s| Pose {
                position: s.position,
                orientation: s.orientation,
            })
            .collect();
        assert!(m1.violation(&poses) < 1e-15);

        let m2 = FOUR_BAR;
        let reference = m2.reference().unwrap();
        let state = m2.initial_state();
        for (s, pose) in state.iter().zip(&reference[0].bodies) {
            assert!((s.position - pose.position).norm() < 1e-14, "{s:?} vs {pose:?}");
            assert!(s.orientation.angle_to(&pose.orientation) < 1e-14);
        }
        let energy: f64 = state.iter().zip(&m2.links()).map(|(s, l)| s.energy(l)).sum();
        assert!(
            (energy - reference[0].energy).abs() < 1e-13,
            "{energy} vs {}",
            reference[0].energy
        );
        let poses: Vec<Pose> = state
            .iter()
            .map(|s| Pose {
                position: s.position,
                orientation: s.orientation,
            })
            .collect();
        assert!(m2.violation(&poses) < 1e-15);
        // The velocities close the loop too: B's and C's velocities agree from both links.
        let [(i, p), (j, q)] = m2.joint_points()[1];
        assert!((state[i].point_velocity(&p) - state[j].point_velocity(&q)).norm() < 1e-14);
        // The file's 15 significant digits against the end state printed in docs/scenes.md (M2); the file's energy at T
        // differs from the printed (initial) one by the reference integration's 4e-12 J.
        let (end, energy) = FOUR_BAR_END;
        let last = m2.reference_angles().unwrap()[500];
        assert!((last[0] - end[0]).abs() < 1e-12 && (reference[500].energy - energy).abs() < 1e-11);
    }

    #[test]
    fn revolution_times_of_a_uniform_rotation() {
        // φ = 1 + 8t: crossings of 1 + 2πk at t = 2πk/8.
        let samples: Vec<(f64, f64, f64)> = (0..300)
            .map(|i| {
                let t = i as f64 * 1e-2;
                (t, 1.0 + 8.0 * t, 8.0)
            })
            .collect();
        let times = revolution_times(&samples, 1.0);
        assert_eq!(times.len(), 3);
        for (k, t) in times.iter().enumerate() {
            assert!((t - 2.0 * std::f64::consts::PI * (k + 1) as f64 / 8.0).abs() < 1e-15);
        }
    }
}
