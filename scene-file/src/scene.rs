//! A scene file read whole ([`Scene`]): its text (at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES)) parsed, checked
//! once, and its system built in every requested algebra, so a bad file fails before anything runs; and running it.

use std::path::Path;

use dynamics::integrate::Integrator;
use dynamics::simulate::Simulation;
use dynamics::{Cga, Pga};

use crate::build::constraints::RoundPins;
use crate::build::system::{build, SceneSystem};
use crate::check::scene::CheckedScene;
use crate::error::{invalid, SceneFileError};
use crate::names::AlgebraKind;
use crate::syntax::file::{read_text, SceneFile};

/// A scene ready to run: the file checked, and its system in every algebra it asks for.
pub struct Scene {
    checked: CheckedScene,
    pga: Option<SceneSystem<Pga>>,
    cga: Option<SceneSystem<Cga>>,
}

/// An algebra in which scene files run: PGA or CGA.
pub trait FileAlgebra: RoundPins {
    /// The system `scene` built in this algebra, if the scene asks for it.
    fn system_of(scene: &Scene) -> Option<&SceneSystem<Self>>;
}

impl FileAlgebra for Pga {
    fn system_of(scene: &Scene) -> Option<&SceneSystem<Self>> {
        scene.pga.as_ref()
    }
}

impl FileAlgebra for Cga {
    fn system_of(scene: &Scene) -> Option<&SceneSystem<Self>> {
        scene.cga.as_ref()
    }
}

impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The systems hold closures (drives, controllers); their algebras stand for them.
        let built: Vec<&str> = [("PGA", self.pga.is_some()), ("CGA", self.cga.is_some())]
            .into_iter()
            .filter_map(|(name, built)| built.then_some(name))
            .collect();
        f.debug_struct("Scene")
            .field("checked", &self.checked)
            .field("built in", &built)
            .finish()
    }
}

impl Scene {
    /// Reads the scene file at `path` (at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES)): parsed, checked and built
    /// ([`Scene::new`]), a robot's URDF path relative to the file's folder.
    ///
    /// ```
    /// use std::path::Path;
    /// use scene_file::{Scene, Stepping};
    ///
    /// // The heavy top shipped in the workspace's `scenes` folder: a cone on a ball joint at its tip.
    /// let scene = Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/heavy_top.toml"))?;
    /// assert_eq!(scene.checked().stepping, Stepping::Fixed { dt: 1e-3 });
    /// assert_eq!(scene.checked().duration, 10.0);
    /// assert_eq!(scene.checked().layout.joints.len(), 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn load(path: &Path) -> Result<Scene, SceneFileError> {
        let text = read_text(path)?;
        Scene::parse_in(&text, path.parent().unwrap_or(Path::new("")))
    }

    /// Parses a scene file and checks that it can run: the bodies, the timing, the integrator and, in every
    /// requested algebra, the forces, joints, stabilisation, the projection of the initial state onto the
    /// joints and the reaction solve there. A robot's URDF path is relative to the current folder
    /// ([`Scene::parse_in`] takes another).
    ///
    /// ```
    /// use scene_file::Scene;
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
    /// let scene = Scene::parse(pendulum)?;
    /// assert_eq!(scene.checked().layout.bodies.len(), 1);
    /// assert_eq!(scene.checked().schedule.step_count(), 500);
    ///
    /// // A bad value fails here, naming it, before anything runs.
    /// let error = Scene::parse(&pendulum.replace("mass = 1.0", "mass = -1.0")).unwrap_err();
    /// assert!(error.to_string().contains("mass"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse(text: &str) -> Result<Scene, SceneFileError> {
        Scene::parse_in(text, Path::new(""))
    }

    /// [`Scene::parse`], with a robot's URDF path relative to `folder` (the scene file's).
    ///
    /// ```
    /// use scene_file::Scene;
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
    /// let scene = Scene::parse_in(text, &folder)?;
    /// assert_eq!(scene.checked().schedule.step_count(), 100);
    /// // Elsewhere the URDF is not found, and the error names it.
    /// let error = Scene::parse_in(text, &folder.join("elsewhere")).unwrap_err();
    /// assert!(error.to_string().contains("wheel.urdf"), "{error}");
    /// std::fs::remove_dir_all(&folder)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse_in(text: &str, folder: &Path) -> Result<Scene, SceneFileError> {
        Scene::new(SceneFile::parse(text)?, folder)
    }

    /// The scene of `file`: checked ([`CheckedScene::new`], a robot's URDF path relative to `folder`), then built in
    /// every algebra it asks for.
    pub fn new(file: SceneFile, folder: &Path) -> Result<Scene, SceneFileError> {
        let checked = CheckedScene::new(file, folder)?;
        let (mut pga, mut cga) = (None, None);
        for algebra in checked.algebra.algebras() {
            match algebra {
                AlgebraKind::Pga => pga = Some(build::<Pga>(&checked)?),
                AlgebraKind::Cga => cga = Some(build::<Cga>(&checked)?),
            }
        }
        Ok(Scene { checked, pga, cga })
    }

    /// The scene as checked.
    pub fn checked(&self) -> &CheckedScene {
        &self.checked
    }

    /// The system in algebra `A`; an error if the scene does not run in it (`algebra` names the other).
    pub fn system<A: FileAlgebra>(&self) -> Result<&SceneSystem<A>, SceneFileError> {
        A::system_of(self).ok_or_else(|| {
            let algebras: Vec<&str> = self.checked.algebra.algebras().iter().map(|a| a.name()).collect();
            invalid(
                "algebra",
                format!("the scene runs in {} only, not in {}", algebras.join(" and "), A::NAME),
            )
        })
    }

    /// Runs the scene in algebra `A` with its integrator and schedule.
    pub fn simulate<A: FileAlgebra>(&self) -> Result<Simulation<A>, SceneFileError> {
        let integrator = Integrator::from(self.checked.integrator);
        self.system::<A>()?.run(integrator, &self.checked.schedule)
    }
}
