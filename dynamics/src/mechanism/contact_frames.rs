//! A contact's frame at one configuration (docs/contacts.md "Between bodies", "Rims", "Edges"): its gap, normal,
//! touching point and their rates, for a point or sphere, a disk's rim, and an edge on an edge.

use nalgebra::{Matrix3, Vector3};

use crate::contacts::PARALLEL_EDGES;
use crate::mechanism::parts::EdgeFeature;

/// A body's pose and velocity (world): its centre of mass, its rotation, the centre's velocity and the angular one.
#[derive(Clone, Copy, Debug)]
pub(super) struct BodyMotion {
    pub position: Vector3<f64>,
    pub rotation: Matrix3<f64>,
    pub linear: Vector3<f64>,
    pub angular: Vector3<f64>,
}

impl BodyMotion {
    /// The velocity of the body's material point at `point` (world).
    pub fn velocity_at(&self, point: &Vector3<f64>) -> Vector3<f64> {
        self.linear + self.angular.cross(&(point - self.position))
    }
}

/// A contact at one configuration (world): its gap (m, negative where the shapes overlap), the unit normal from the
/// other body (or the world) towards the contact's own, the touching point p, the relative velocity `w = v(p) −
/// v_other(p)` of the two bodies' material points at p, and the rates ṅ of the normal and ṗ of the touching point.
/// The gap changes at `n · w` (docs/contacts.md "Between bodies").
#[derive(Clone, Copy, Debug)]
pub(super) struct ContactFrame {
    pub gap: f64,
    pub normal: Vector3<f64>,
    pub touching: Vector3<f64>,
    pub relative: Vector3<f64>,
    pub normal_rate: Vector3<f64>,
    pub touching_rate: Vector3<f64>,
    /// For a disk's rim, the sine of the angle between its axis and the normal (zero: flat on the plane); 1 else.
    pub tilt: f64,
    /// How far (m) the touching point is outside the contact's face, or for an edge contact outside where its edges
    /// meet (docs/contacts.md "Edges"); negative inside, −∞ for a contact with neither.
    pub outside: f64,
    /// The rate of `outside` (m/s) across the bound it is measured to (zero where that is not a plane or an edge's
    /// end).
    pub outside_rate: f64,
    /// Whether the normal is defined by the configuration: false for edges within [`PARALLEL_EDGES`] of parallel,
    /// whose common normal turns over at round-off.
    pub defined: bool,
}

/// Where a disk's rim touches a plane, from its centre: `ρ û`, û the normal n projected on the disk (normal to its
/// axis a) and made unit, the rim's point farthest along n, which the touching point `c − ρ û` is; its rate; and the
/// disk's tilt `|n − (n · a) a|` (docs/contacts.md "Rims").
#[derive(Clone, Copy, Debug)]
pub(super) struct RimPoint {
    pub offset: Vector3<f64>,
    pub rate: Vector3<f64>,
    pub tilt: f64,
}

impl Default for RimPoint {
    /// No rim: a point or a sphere.
    fn default() -> Self {
        RimPoint {
            offset: Vector3::zeros(),
            rate: Vector3::zeros(),
            tilt: 1.0,
        }
    }
}

impl RimPoint {
    /// The rim of radius `radius` about the world axis `axis` of a body turning at `angular`, against the normal
    /// `normal` turning at `normal_rate`. With `u = n − (n · a) a`, `u̇ = ṅ − (ṅ · a + n · ȧ) a − (n · a) ȧ` (ȧ = ω ×
    /// a) and `d û/dt = (u̇ − û (û · u̇)) / |u|`. A disk exactly flat has no farthest point: any rim point serves
    /// (the gap is the same), moving with the body.
    pub(super) fn towards(
        radius: f64,
        axis: &Vector3<f64>,
        angular: &Vector3<f64>,
        normal: &Vector3<f64>,
        normal_rate: &Vector3<f64>,
    ) -> Self {
        let along = normal.dot(axis);
        let projected = normal - axis * along;
        let tilt = projected.norm();
        if tilt == 0.0 {
            let any = axis.cross(&Vector3::x());
            let any = if any.norm() > 0.5 {
                any
            } else {
                axis.cross(&Vector3::y())
            }
            .normalize();
            return RimPoint {
                offset: any * radius,
                rate: angular.cross(&any) * radius,
                tilt,
            };
        }
        let unit = projected / tilt;
        let axis_rate = angular.cross(axis);
        let projected_rate = normal_rate - axis * (normal_rate.dot(axis) + normal.dot(&axis_rate)) - axis_rate * along;
        let unit_rate = (projected_rate - unit * unit.dot(&projected_rate)) / tilt;
        RimPoint {
            offset: unit * radius,
            rate: unit_rate * radius,
            tilt,
        }
    }
}

impl ContactFrame {
    /// The gap's rate `n · w` (m/s).
    pub fn normal_speed(&self) -> f64 {
        self.normal.dot(&self.relative)
    }

    /// The slip: the relative velocity's part along the tangent plane (m/s).
    pub fn slip(&self) -> Vector3<f64> {
        self.relative - self.normal * self.normal_speed()
    }
}

/// An edge contact's frame (docs/contacts.md "Edges"): the own edge from `start` (world) of the body moving as `own`,
/// the other's from `other_start` (principal coordinates) of the body moving as `other`. With unit directions a, b,
/// `u = a × b` of length sin θ, the normal `n = ±u/|u|` points out of the other solid (between its faces' normals).
/// The nearest points `p = p_a + s a`, `q = p_b + t b` solve `(p − q) · a = (p − q) · b = 0`: with `d = p_a − p_b`,
/// `c = a · b`, `s = (c (d · b) − d · a)/sin²θ`, `t = (d · b − c (d · a))/sin²θ`. The gap is `n · d`, and p the
/// touching point; `ġ = n · (v_A(p) − v_B(p))` as an identity (p − q lies along n, and ṅ ⊥ n), so the rows are those
/// of every contact. The rates: `ȧ = ω_A × a`, `ḃ = ω_B × b`, `u̇ = ȧ × b + a × ḃ`, `ṅ = ±(u̇ − n0 (n0 · u̇))/|u|`,
/// and `ṗ = v_A(p) + ṡ a` with ṡ the quotient rule on s.
pub(super) fn edge_frame(
    (own, start, own_edge): (&BodyMotion, Vector3<f64>, &EdgeFeature),
    (other, other_start, other_edge): (&BodyMotion, Vector3<f64>, &EdgeFeature),
) -> ContactFrame {
    let a = own.rotation * own_edge.direction;
    let b = other.rotation * other_edge.direction;
    let start_b = other.position + other.rotation * other_start;
    let [fa1, fa2] = own_edge.faces.map(|f| own.rotation * f);
    let [fb1, fb2] = other_edge.faces.map(|f| other.rotation * f);
    let u = a.cross(&b);
    let sine = u.norm();
    let length = own_edge.length.max(other_edge.length);
    // Nearly parallel edges leave their contact to the vertices at their ends: outside by up to the longer edge.
    let parallel = length * (1.0 - sine / PARALLEL_EDGES);
    let direction = if sine > 0.0 { u / sine } else { (fb1 + fb2).normalize() };
    let sign = if direction.dot(&(fb1 + fb2)) >= 0.0 { 1.0 } else { -1.0 };
    let normal = direction * sign;
    let d = start - start_b;
    let c = a.dot(&b);
    // Nearer parallel than half the bound, where the pair is outside by half the longer edge at least, the nearest
    // points and the rates are those of edges at that angle: finite, for a trial stage that goes there.
    let kept = sine.max(PARALLEL_EDGES / 2.0);
    let squared = kept * kept;
    let (along_b, along_a) = (d.dot(&b), d.dot(&a));
    let numerator = c * along_b - along_a;
    let (s, t) = (numerator / squared, (along_b - c * along_a) / squared);
    let touching = start + a * s;
    // Inside: the nearest points on both edges, n between the other's faces' normals, −n between the own's.
    let between = |n: &Vector3<f64>, f1: &Vector3<f64>, f2: &Vector3<f64>| {
        let axis = f1.cross(f2).normalize();
        f1.cross(n).dot(&axis).min(n.cross(f2).dot(&axis))
    };
    let terms = [
        -s,
        s - own_edge.length,
        -t,
        t - other_edge.length,
        -length * between(&normal, &fb1, &fb2),
        -length * between(&-normal, &fa1, &fa2),
        parallel,
    ];
    let (farthest, outside) =
        (terms.into_iter().enumerate()).fold((0, f64::NEG_INFINITY), |m, (k, x)| if x > m.1 { (k, x) } else { m });
    let (a_rate, b_rate) = (own.angular.cross(&a), other.angular.cross(&b));
    let u_rate = a_rate.cross(&b) + a.cross(&b_rate);
    let normal_rate = (u_rate - direction * direction.dot(&u_rate)) * (sign / kept);
    let d_rate = own.velocity_at(&start) - other.velocity_at(&start_b);
    let c_rate = a_rate.dot(&b) + a.dot(&b_rate);
    let along_b_rate = d_rate.dot(&b) + d.dot(&b_rate);
    let along_a_rate = d_rate.dot(&a) + d.dot(&a_rate);
    let numerator_rate = c_rate * along_b + c * along_b_rate - along_a_rate;
    let quotient_rate = |top: f64, top_rate: f64| (top_rate * squared + top * 2.0 * c * c_rate) / (squared * squared);
    let s_rate = quotient_rate(numerator, numerator_rate);
    let t_rate = quotient_rate(
        along_b - c * along_a,
        along_b_rate - c_rate * along_a - c * along_a_rate,
    );
    // How fast the nearest points leave their edges (the cones and parallels are guards, not watched for a rate).
    let outside_rate = [-s_rate, s_rate, -t_rate, t_rate].get(farthest).copied().unwrap_or(0.0);
    let own_velocity = own.velocity_at(&touching);
    ContactFrame {
        gap: normal.dot(&d),
        normal,
        touching,
        relative: own_velocity - other.velocity_at(&touching),
        normal_rate,
        touching_rate: own_velocity + a * s_rate,
        tilt: 1.0,
        outside,
        outside_rate,
        defined: sine > PARALLEL_EDGES,
    }
}

/// A sphere's frame against an edge (docs/contacts.md "Spheres on polyhedra"): the sphere of radius `radius` about
/// `centre` (world) of the body moving as `own`, the edge from `start` (principal coordinates) of the body moving as
/// `other`. With b the edge's unit direction and `τ = (c − q₀) · b`, the nearest point of its line is `q = q₀ + τ b`;
/// `δ = c − q`, the normal `n = δ/|δ|`, the gap `|δ| − r` and the touching point `p = c − r n`. As for two balls,
/// `ġ = n · (v_A(p) − v_B(p))` (q moves along b, normal to n), with `q̇ = v_B(q) + τ̇ b`, `τ̇ = (ċ − v_B(q₀)) · b +
/// (c − q₀) · ḃ`, `ṅ = (δ̇ − n (n · δ̇))/|δ|` and `ṗ = ċ − r ṅ`. Inside: q on the edge, n between its faces' normals.
pub(super) fn sphere_edge_frame(
    (own, centre, radius): (&BodyMotion, Vector3<f64>, f64),
    (other, other_start, edge): (&BodyMotion, Vector3<f64>, &EdgeFeature),
) -> ContactFrame {
    let b = other.rotation * edge.direction;
    let start = other.position + other.rotation * other_start;
    let [f1, f2] = edge.faces.map(|f| other.rotation * f);
    let from_start = centre - start;
    let along = from_start.dot(&b);
    let nearest = start + b * along;
    let between = centre - nearest;
    let distance = between.norm();
    let defined = distance > 0.0;
    let normal = if defined {
        between / distance
    } else {
        (f1 + f2).normalize()
    };
    let centre_velocity = own.velocity_at(&centre);
    let b_rate = other.angular.cross(&b);
    let along_rate = (centre_velocity - other.velocity_at(&start)).dot(&b) + from_start.dot(&b_rate);
    let nearest_rate = other.velocity_at(&nearest) + b * along_rate;
    let between_rate = centre_velocity - nearest_rate;
    let normal_rate = if defined {
        (between_rate - normal * normal.dot(&between_rate)) / distance
    } else {
        Vector3::zeros()
    };
    let touching = centre - normal * radius;
    let axis = f1.cross(&f2).normalize();
    let cone = f1.cross(&normal).dot(&axis).min(normal.cross(&f2).dot(&axis));
    let terms = [-along, along - edge.length, -edge.length * cone];
    let (farthest, outside) =
        (terms.into_iter().enumerate()).fold((0, f64::NEG_INFINITY), |m, (k, x)| if x > m.1 { (k, x) } else { m });
    let outside_rate = [-along_rate, along_rate].get(farthest).copied().unwrap_or(0.0);
    ContactFrame {
        gap: distance - radius,
        normal,
        touching,
        relative: own.velocity_at(&touching) - other.velocity_at(&touching),
        normal_rate,
        touching_rate: centre_velocity - normal_rate * radius,
        tilt: 1.0,
        outside,
        outside_rate,
        defined,
    }
}
