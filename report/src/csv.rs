//! Trajectories as CSV, all written by one writer (the `csv` crate, RFC 4180): a header of column names, then a line
//! per sample of numbers in Rust's `{:e}` (exact when read back), comma-separated. One body in the reference files' columns plus the energy
//! ([`write()`]); several bodies' centres of mass and orientations, then the system's energy (`write_bodies`); a
//! robot's joint coordinates between the time and the energy (`write_joints`).

use std::path::Path;

use dynamics::simulate::Sample;

/// The header: the reference files' columns (docs/scenes.md "Files") and the energy.
pub const HEADER: &str = "t,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy";

/// Writes the samples to `path`.
pub fn write(path: &Path, samples: &[Sample]) -> std::io::Result<()> {
    let rows = samples.iter().map(|s| {
        let q = s.orientation.quaternion();
        vec![
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
        ]
    });
    write_table(path, HEADER.split(','), rows)
}

/// Writes several bodies' samples (`bodies[i][k]`) to `path`: `t`, then per body `NAME.x`, `NAME.y`, `NAME.z`
/// (centre of mass, world, m), `NAME.qw`, `NAME.qx`, `NAME.qy`, `NAME.qz` (orientation body → world), then
/// `energy` (the whole system's, J).
pub(crate) fn write_bodies(path: &Path, names: &[&str], bodies: &[Vec<Sample>]) -> std::io::Result<()> {
    let pose = ["x", "y", "z", "qw", "qx", "qy", "qz"];
    let per_body = names
        .iter()
        .flat_map(|name| pose.map(|column| format!("{name}.{column}")));
    let columns = std::iter::once("t".to_owned())
        .chain(per_body)
        .chain(["energy".to_owned()]);
    let samples = bodies.first().map_or(0, Vec::len);
    let rows = (0..samples).map(|k| {
        let first = &bodies[0][k];
        let mut row = vec![first.t];
        for body in bodies {
            let s = &body[k];
            let q = s.orientation.quaternion();
            row.extend([s.position.x, s.position.y, s.position.z, q.w, q.i, q.j, q.k]);
        }
        row.push(first.energy);
        row
    });
    write_table(path, columns, rows)
}

/// Writes a robot's joints CSV to `path`: `t`, the `headers` with each sample's `rows`, then `energy` (the whole
/// system's, J), the time and energy from `samples`.
pub(crate) fn write_joints(
    path: &Path,
    headers: &[String],
    rows: &[Vec<f64>],
    samples: &[Sample],
) -> std::io::Result<()> {
    let columns = std::iter::once("t")
        .chain(headers.iter().map(String::as_str))
        .chain(["energy"]);
    let rows = rows.iter().zip(samples).map(|(row, sample)| {
        let mut values = Vec::with_capacity(row.len() + 2);
        values.push(sample.t);
        values.extend(row);
        values.push(sample.energy);
        values
    });
    write_table(path, columns, rows)
}

/// Writes the header of `columns` and the `rows` to `path`, a name quoted where RFC 4180 says (a comma, a quote or a
/// line break in it).
fn write_table(
    path: &Path,
    columns: impl IntoIterator<Item = impl AsRef<str>>,
    rows: impl ExactSizeIterator<Item = Vec<f64>>,
) -> std::io::Result<()> {
    let mut writer = ::csv::Writer::from_path(path)?;
    writer.write_record(columns.into_iter().map(|c| c.as_ref().to_owned()))?;
    for row in rows {
        writer.write_record(row.iter().map(|value| format!("{value:e}")))?;
    }
    writer.flush()
}
