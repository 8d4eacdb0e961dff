//! Trajectories as CSV, in the reference files' columns plus the energy.

use std::fmt::Write as _;
use std::path::Path;

use dynamics::simulate::Sample;

/// The header: the reference files' columns (SCENES.md "Files") and the energy.
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
