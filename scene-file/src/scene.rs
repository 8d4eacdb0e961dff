//! Reading a scene file: its text (at most [`MAX_FILE_BYTES`]) parsed, checked, and built in every requested algebra,
//! so a bad file fails before anything runs.

use std::path::Path;
use std::sync::Arc;

use dynamics::integrate::Integrator;
use dynamics::{Cga, Pga};

use crate::build::constraints::FileAlgebra;
use crate::build::system::SceneSystem;
use crate::error::{invalid, SceneFileError};
use crate::names::{AlgebraKind, IntegratorName};
use crate::syntax::file::{at_unknown_key, SceneFile, MAX_FILE_BYTES};

impl SceneFile {
    /// Reads and checks a scene file (at most [`MAX_FILE_BYTES`]); a robot's URDF path is relative to the file's
    /// folder.
    ///
    /// ```
    /// use std::path::Path;
    /// use scene_file::SceneFile;
    ///
    /// // The heavy top shipped in the workspace's `scenes` folder: a cone on a ball joint at its tip.
    /// let scene = SceneFile::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/heavy_top.toml"))?;
    /// assert_eq!((scene.dt, scene.duration), (Some(1e-3), 10.0));
    /// assert_eq!(scene.constraints.len(), 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn load(path: &Path) -> Result<SceneFile, SceneFileError> {
        use std::io::Read as _;
        let file = std::fs::File::open(path).map_err(SceneFileError::Read)?;
        let mut bytes = Vec::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(SceneFileError::Read)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(invalid("the file", format!("is larger than {MAX_FILE_BYTES} bytes")));
        }
        let text = String::from_utf8(bytes).map_err(|e| invalid("the file", format!("is not UTF-8: {e}")))?;
        SceneFile::parse_in(&text, path.parent().unwrap_or(Path::new("")))
    }

    /// Parses a scene file and checks that it can run: the bodies, the timing, the integrator and, in every
    /// requested algebra, the forces, joints, stabilisation, the projection of the initial state onto the
    /// joints and the reaction solve there. A robot's URDF path is relative to the current folder
    /// ([`SceneFile::parse_in`] takes another).
    ///
    /// ```
    /// use scene_file::SceneFile;
    ///
    /// // A pendulum: a 1 m rod hung from the world by a ball joint at its top end.
    /// let pendulum = r#"
    ///     dt = 1e-3
    ///     duration = 0.5
    ///
    ///     [body]
    ///     mass = 1.0
    ///     shape = { kind = "rod", length = 1.0, axial_moment = 1e-3 }
    ///
    ///     [[forces]]
    ///     kind = "gravity"
    ///
    ///     [[constraints]]
    ///     kind = "ball_joint"
    ///     body_point = [0.0, 0.0, 0.5]
    ///     world_point = [0.0, 0.0, 0.0]
    /// "#;
    /// let scene = SceneFile::parse(pendulum)?;
    /// assert_eq!(scene.layout()?.bodies.len(), 1);
    /// assert_eq!(scene.schedule()?.step_count(), 500);
    ///
    /// // A bad value fails here, naming it, before anything runs.
    /// let error = SceneFile::parse(&pendulum.replace("mass = 1.0", "mass = -1.0")).unwrap_err();
    /// assert!(error.to_string().contains("mass"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse(text: &str) -> Result<SceneFile, SceneFileError> {
        SceneFile::parse_in(text, Path::new(""))
    }

    /// [`SceneFile::parse`], with a robot's URDF path relative to `folder` (the scene file's).
    ///
    /// ```
    /// use scene_file::SceneFile;
    ///
    /// let folder = std::env::temp_dir().join(format!("parse-in-{}", std::process::id()));
    /// std::fs::create_dir_all(&folder)?;
    /// std::fs::write(folder.join("wheel.urdf"), r#"<robot name="wheel">
    ///   <link name="base"/>
    ///   <link name="wheel"><inertial><mass value="1"/>
    ///     <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.2"/></inertial></link>
    ///   <joint name="axle" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 0 1"/></joint>
    /// </robot>"#)?;
    /// let text = "dt = 1e-3\nduration = 0.1\n[robot]\nurdf = \"wheel.urdf\"\nroot = \"fixed\"\n";
    /// let scene = SceneFile::parse_in(text, &folder)?;
    /// assert_eq!(scene.schedule()?.step_count(), 100);
    /// // Elsewhere the URDF is not found, and the error names it.
    /// let error = SceneFile::parse_in(text, &folder.join("elsewhere")).unwrap_err();
    /// assert!(error.to_string().contains("wheel.urdf"), "{error}");
    /// std::fs::remove_dir_all(&folder)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse_in(text: &str, folder: &Path) -> Result<SceneFile, SceneFileError> {
        let mut scene: SceneFile = toml::from_str(text).map_err(|error| at_unknown_key(text, error))?;
        if let Some(robot) = &scene.robot {
            scene.loaded_robot = Some(Arc::new(robot.load(folder)?));
        }
        scene.integrator = scene.integrator_written.unwrap_or(if scene.tolerance.is_some() {
            IntegratorName::Dop853Body
        } else if scene.robot.is_some() {
            IntegratorName::Rkmk8Body
        } else {
            IntegratorName::Rk4
        });
        scene.schedule()?;
        if scene.tolerance.is_some() && Integrator::from(scene.integrator).estimate_order().is_none() {
            return Err(invalid(
                "integrator",
                format!(
                    "{} has no error estimate to choose its steps by: with a tolerance, name \"dop853-body\" or \
                     \"dp5-body\" (or leave the integrator out), or give dt in place of the tolerance",
                    Integrator::from(scene.integrator).name()
                ),
            ));
        }
        let layout = scene.layout()?;
        let splitting = matches!(Integrator::from(scene.integrator), Integrator::Splitting(_));
        if splitting && !scene.free_body(&layout) {
            return Err(invalid(
                "integrator",
                format!(
                    "{} is a splitting method, which runs one body without constraints, a robot or force elements only",
                    Integrator::from(scene.integrator).name()
                ),
            ));
        }
        for algebra in scene.algebra.algebras() {
            match algebra {
                AlgebraKind::Pga => scene.check_integrator(&scene.system::<Pga>()?)?,
                AlgebraKind::Cga => scene.check_integrator(&scene.system::<Cga>()?)?,
            }
        }
        Ok(scene)
    }

    /// An integrator stepping in joint coordinates needs every joint a joint model, in a tree: refused here, naming
    /// the integrator, rather than when the run starts.
    fn check_integrator<A: FileAlgebra>(&self, system: &SceneSystem<A>) -> Result<(), SceneFileError> {
        let integrator = Integrator::from(self.integrator);
        if matches!(integrator, Integrator::Joint(_)) {
            dynamics::Stepper::new(&system.system, integrator).map_err(|e| invalid("integrator", e.to_string()))?;
        }
        Ok(())
    }
}
