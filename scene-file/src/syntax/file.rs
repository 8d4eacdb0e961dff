//! A whole scene file ([`SceneFile`]) with its defaults: its text read (at most [`MAX_FILE_BYTES`]) and parsed, toml's
//! errors placed at the offending key.

use std::io::Read as _;
use std::path::Path;

use dynamics::simulate::SAMPLE_INTERVAL;
use serde::Deserialize;

use super::bodies::{Bodies, ForceSpec, InitialSpec};
use super::contacts::{CollisionSpec, ContactSpec, PlaneSpec};
use super::elements::{CoupleSpec, JointDampingSpec, JointTorqueSpec, PdSpec, SpringSpec};
use super::joints::{ConstraintSpec, JointSpec};
use super::robot::RobotSpec;
use crate::error::{invalid, SceneFileError};
use crate::names::{AlgebraChoice, IntegratorName, StabilisationName};

/// A whole scene file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// A title for the summary and the plots.
    #[serde(default)]
    pub title: Option<String>,
    /// Which algebras run the scene.
    #[serde(default)]
    pub algebra: AlgebraChoice,
    /// The integrator, if the file names one (the default depends on the scene: `CheckedScene::integrator`).
    #[serde(default)]
    pub integrator: Option<IntegratorName>,
    /// The fixed step (s); it must divide the sample interval. A file gives this or `tolerance`.
    #[serde(default)]
    pub dt: Option<f64>,
    /// The accuracy an adaptive run chooses its steps by, in place of `dt` (relative and absolute alike, in rad,
    /// m, rad/s and m/s: `dynamics::integrate::step_control`); the integrator then defaults to `"dop853-body"`, the pair of
    /// order 8 (`"dp5-body"`, of order 5, is the other integrator with an error estimate).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Simulated time (s); the last sample interval may be shorter.
    pub duration: f64,
    /// Time between recorded samples (s).
    #[serde(default = "default_sample_interval")]
    pub sample_interval: f64,
    /// How the joints are held: `"projection"` (the default), `"baumgarte"` or `"none"`.
    #[serde(default = "default_stabilisation")]
    pub stabilisation: StabilisationName,
    /// How far the start may be moved onto its joints (m and rad) before it is refused as breaking them: its
    /// rounding passes, a body placed off its joint does not.
    #[serde(default = "default_max_start_correction")]
    pub max_start_correction: f64,
    /// Gains for `stabilisation = "baumgarte"` (default α = β = 10, as on the command line).
    #[serde(default)]
    pub baumgarte: Option<BaumgarteGains>,
    /// `[body]`, one body, or `[[body]]`, named bodies; none with a `[robot]` alone.
    #[serde(default)]
    pub body: Option<Bodies>,
    /// The single body's initial state.
    #[serde(default)]
    pub initial: Option<InitialSpec>,
    /// The single body's forces.
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    /// The single body's constraints to the world.
    #[serde(default)]
    pub constraints: Vec<ConstraintSpec>,
    /// Joints between named bodies, or a named body and the world or a robot link.
    #[serde(default)]
    pub joint: Vec<JointSpec>,
    /// A URDF robot.
    #[serde(default)]
    pub robot: Option<RobotSpec>,
    /// Spring-dampers between two bodies.
    #[serde(default)]
    pub spring: Vec<SpringSpec>,
    /// Constant couples between two bodies.
    #[serde(default)]
    pub couple: Vec<CoupleSpec>,
    /// Torques on joints by name.
    #[serde(default)]
    pub joint_torque: Vec<JointTorqueSpec>,
    /// Viscous damping on joints by name.
    #[serde(default)]
    pub joint_damping: Vec<JointDampingSpec>,
    /// PD controllers on joints by name.
    #[serde(default)]
    pub pd: Vec<PdSpec>,
    /// Body points kept above world planes.
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    /// World planes every collision shape stays above.
    #[serde(default)]
    pub plane: Vec<PlaneSpec>,
    /// Pairs of bodies whose collision shapes stay apart.
    #[serde(default)]
    pub collision: Vec<CollisionSpec>,
}

impl SceneFile {
    /// Parses a scene file's text: its syntax only (nothing is checked but what toml and the structs' types check).
    pub fn parse(text: &str) -> Result<SceneFile, SceneFileError> {
        toml::from_str(text).map_err(|error| at_unknown_key(text, error))
    }
}

/// The text of the file at `path`, refused unread past [`MAX_FILE_BYTES`] (a typo naming /dev/zero must not hang).
pub fn read_text(path: &Path) -> Result<String, SceneFileError> {
    let file = std::fs::File::open(path).map_err(SceneFileError::Read)?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(SceneFileError::Read)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(invalid("the file", format!("is larger than {MAX_FILE_BYTES} bytes")));
    }
    String::from_utf8(bytes).map_err(|e| invalid("the file", format!("is not UTF-8: {e}")))
}

fn default_sample_interval() -> f64 {
    SAMPLE_INTERVAL
}

/// A millimetre or a milliradian: far above a start written to six digits, far below a body off its joint.
fn default_max_start_correction() -> f64 {
    1e-3
}

fn default_stabilisation() -> StabilisationName {
    StabilisationName::Projection
}

/// `baumgarte = { alpha = …, beta = … }` (1/s). Read as a table only: serde's derived struct would also take an
/// array and drop any numbers past the second (`baumgarte = [1, 2, 3]`).
#[derive(Clone, Copy, Debug)]
pub struct BaumgarteGains {
    /// 1/s.
    pub alpha: f64,
    /// 1/s.
    pub beta: f64,
}

impl<'de> Deserialize<'de> for BaumgarteGains {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Gains;
        const FIELDS: &[&str] = &["alpha", "beta"];
        impl<'de> serde::de::Visitor<'de> for Gains {
            type Value = BaumgarteGains;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table { alpha = …, beta = … }")
            }
            fn visit_map<M: serde::de::MapAccess<'de>>(self, mut map: M) -> Result<BaumgarteGains, M::Error> {
                let (mut alpha, mut beta) = (None, None);
                while let Some(key) = map.next_key::<String>()? {
                    let slot = match key.as_str() {
                        "alpha" => &mut alpha,
                        "beta" => &mut beta,
                        other => return Err(serde::de::Error::unknown_field(other, FIELDS)),
                    };
                    if slot.replace(map.next_value::<f64>()?).is_some() {
                        return Err(serde::de::Error::custom(format!("duplicate field `{key}`")));
                    }
                }
                Ok(BaumgarteGains {
                    alpha: alpha.ok_or_else(|| serde::de::Error::missing_field("alpha"))?,
                    beta: beta.ok_or_else(|| serde::de::Error::missing_field("beta"))?,
                })
            }
        }
        deserializer.deserialize_struct("BaumgarteGains", FIELDS, Gains)
    }
}

/// Scene files larger than this are refused before they are read to the end (the largest shipped one is 5 KiB).
pub const MAX_FILE_BYTES: u64 = 4 << 20;

/// The reader's error, or, for an unknown key it can only place at its table's header (tables read through a `kind`
/// tag), the same message at the key's own line: the first `key =` between the header and the next one.
fn at_unknown_key(text: &str, error: toml::de::Error) -> SceneFileError {
    let message = error.message().trim().to_owned();
    let key = message
        .strip_prefix("unknown field `")
        .and_then(|rest| rest.split('`').next());
    let (Some(key), Some(span)) = (key, error.span()) else {
        return error.into();
    };
    let line_of = |offset: usize| text[..offset].matches('\n').count() + 1;
    // The span is the table's header; its keys run to the next header.
    let after_header = text[span.end..].find('\n').map_or(text.len(), |end| span.end + end);
    let end = text[after_header..]
        .match_indices("\n[")
        .next()
        .map_or(text.len(), |(at, _)| after_header + at);
    let table = &text[span.start..end];
    let assigned = table.match_indices(key).find(|&(at, _)| {
        let before = table[..at].chars().next_back();
        let after = table[at + key.len()..].trim_start();
        before.is_none_or(|c| c.is_whitespace() || c == '{' || c == ',') && after.starts_with('=')
    });
    match assigned {
        Some((at, _)) if line_of(span.start + at) != line_of(span.start) => SceneFileError::UnknownKey {
            line: line_of(span.start + at),
            table_line: line_of(span.start),
            message,
        },
        _ => error.into(),
    }
}
