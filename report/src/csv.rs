//! Trajectories as CSV: one body in the reference files' columns plus the energy; several bodies as every
//! body's centre of mass and orientation, then the system's energy.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::simulate::Sample;

/// The header: the reference files' columns (docs/scenes.md "Files") and the energy.
pub const HEADER: &str = "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy";

/// Writes the samples to `path`.
pub fn write(path: &Path, samples: &[Sample]) -> std::io::Result<()> {
    let mut text = String::with_capacity(samples.len() * 300 + HEADER.len() + 1);
    text.push_str(HEADER);
    text.push('\n');
    for s in samples {
        let q = s.orientation.quaternion();
        let values = [
            s.t,
            s.position.x,
            s.position.y,
            s.position.z,
            q.w,
            q.i,
            q.j,
            q.k,
            s.velocity.x,
            s.velocity.y,
            s.velocity.z,
            s.angular_velocity.x,
            s.angular_velocity.y,
            s.angular_velocity.z,
            s.energy,
        ];
        let line: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
        let _ = writeln!(text, "{}", line.join(","));
    }
    std::fs::write(path, text)
}

/// Writes several bodies' samples (`bodies[i][k]`) to `path`: `t`, then per body `NAME.x`, `NAME.y`, `NAME.z`
/// (centre of mass, world, m), `NAME.qw`, `NAME.qx`, `NAME.qy`, `NAME.qz` (orientation body → world), then
/// `energy` (the whole system's, J).
pub(crate) fn write_bodies(path: &Path, names: &[&str], bodies: &[Vec<Sample>]) -> std::io::Result<()> {
    let mut text = String::from("t");
    for name in names {
        for column in ["x", "y", "z", "qw", "qx", "qy", "qz"] {
            let _ = write!(text, ",{name}.{column}");
        }
    }
    text.push_str(",energy\n");
    let samples = bodies.first().map_or(0, Vec::len);
    for k in 0..samples {
        let first = &bodies[0][k];
        let _ = write!(text, "{:e}", first.t);
        for body in bodies {
            let s = &body[k];
            let q = s.orientation.quaternion();
            for v in [s.position.x, s.position.y, s.position.z, q.w, q.i, q.j, q.k] {
                let _ = write!(text, ",{v:e}");
            }
        }
        let _ = writeln!(text, ",{:e}", first.energy);
    }
    std::fs::write(path, text)
}
