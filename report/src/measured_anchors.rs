//! MuJoCo's and Pinocchio's times measured on this machine beside the run (`--anchors FILE`, written by
//! `tools/anchors/measure`; docs/benchmarks.md). A ratio of our cost to a constant measured on another day reads
//! whatever load the machine had then; measured in the same hour, both sides see the same machine. Every figure the
//! file lacks falls back to the recorded constant of `recorded_anchors`, and the report says which is which.
//!
//! The file is checked whole before the job runs: a careless or stale file is an error naming the figure, never a
//! silent fallback. Each figure the report uses is then the file's where it has it, else the constant
//! (`double_pendulum_time`, `four_bar_time`, `chain_times`, `pinocchio_chain_times`, `mujoco_time`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use reference::robots::RobotId;
use reference::SceneId;
use serde::Deserialize;

use crate::recorded_anchors::{
    self, Anchor, CHAIN_BALL_TIME_PER_STEP, CHAIN_HINGE_TIME_PER_STEP, DOUBLE_PENDULUM, FOUR_BAR_TIME_PER_STEP,
    MECHANISMS_DATE, PINOCCHIO_CHAIN_EVALUATION, RECORDED_WHEN, SINGLE_BODY_MEASURED, SINGLE_BODY_RECORDED,
};

/// The version of the file layout this report reads.
pub const FORMAT: u32 = 1;

/// The fewest repeats of a figure: the minimum of fewer is too easily a run slowed by other work.
pub const MIN_REPEATS: usize = 5;

/// A figure whose repeats differ by more than this (largest/smallest − 1) is flagged: its ratio is that uncertain.
pub const SPREAD_LIMIT: f64 = 0.2;

/// How far a file's time may lie ahead of this machine's clock (s): clocks of two machines differ a little.
const CLOCK_SLACK: i64 = 300;

/// The robots' MuJoCo steps the runner measures (those of the recorded reference runs).
const ROBOT_STEPS: [(f64, &str); 2] = [(1e-3, "1e-3"), (1e-4, "1e-4")];

/// The step (s) at which the mechanisms' MuJoCo times are measured and compared.
const MECHANISM_STEP: f64 = 1e-3;

/// Why an anchors file cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AnchorsError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// Not JSON of the expected shape: a missing or unknown key, a wrong type, NaN (not JSON), … with its line.
    #[error("not an anchors file: {0}")]
    Json(#[from] serde_json::Error),
    /// Written for another layout.
    #[error("format {found}: this report reads format {FORMAT}")]
    Format {
        /// The file's format.
        found: u32,
    },
    /// `measured_at` is not a UTC date-time as the runner writes it.
    #[error("measured_at {0:?}: not a UTC date-time such as 2026-11-27T18:05:00Z")]
    Date(String),
    /// `measured_at` lies ahead of this machine's clock: the file or a clock is wrong.
    #[error("measured_at {0}: later than this machine's clock says it is now")]
    FromTheFuture(String),
    /// The machine's description is impossible.
    #[error("machine: {0}")]
    Machine(String),
    /// A figure the report does not use: a typo would otherwise leave the recorded constant in place silently.
    #[error(
        "figure {0:?}: not a figure the report uses (scene1, scene2, scene3a, scene4-circle, m1, m2, m3-ball-N, \
             m3-hinge-N, m3-pinocchio-N for N = 1, 2, 4, …, 64, ur5-dt1e-3, ur5-dt1e-4, solo12-dt1e-3, solo12-dt1e-4)"
    )]
    UnknownKey(String),
    /// The same figure twice.
    #[error("figure {0:?} appears twice")]
    Duplicate(String),
    /// A figure's numbers are impossible or disagree with each other.
    #[error("figure {key:?}: {problem}")]
    Figure {
        /// The figure.
        key: String,
        /// What is wrong.
        problem: String,
    },
}

/// The file as the runner writes it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    format: u32,
    measured_at: String,
    machine: Machine,
    figures: Vec<FileFigure>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Machine {
    nproc: u32,
    /// /proc/loadavg's 1, 5 and 15-minute averages before and after the measurements.
    load_before: [f64; 3],
    load_after: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileFigure {
    key: String,
    what: String,
    /// The step the time per step was measured at (s); none for a time per dynamics evaluation.
    dt: Option<f64>,
    /// The command that measured it, its scratch folder named OUTDIR.
    command: String,
    /// Seconds, one per repeat.
    repeats: Vec<f64>,
    min: f64,
    spread: f64,
    /// The script's errors at T, checked to be numbers; the report keeps its recorded errors, which do not depend
    /// on the machine.
    #[serde(default)]
    errors: Vec<ErrorPoint>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ErrorPoint {
    dt: f64,
    error: f64,
}

/// When and under what load the figures were measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Occasion {
    /// "2026-11-27 18:05 UTC".
    pub when: String,
    /// Cores of the machine.
    pub cores: u32,
    /// The 1-minute load average before and after the measurements.
    pub load: (f64, f64),
}

/// One measured figure: the fastest repeat (s), the repeats' spread (largest/smallest − 1), how many there were,
/// and what and how it measured.
#[derive(Clone, Debug, PartialEq)]
struct Measured {
    seconds: f64,
    spread: f64,
    repeats: usize,
    what: String,
    command: String,
}

/// The figures measured beside this run, if any: [`Anchors::none`] leaves every figure on its recorded constant.
#[derive(Clone, Debug, Default)]
pub struct Anchors {
    measured: Option<(Occasion, BTreeMap<String, Measured>)>,
}

/// A figure the report uses, by the key the anchors file names it with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Key {
    /// A single-body scene with a recorded MuJoCo anchor, MuJoCo RK4, s per step at dt = 1e-3.
    SingleBody(SceneId),
    /// M1, MuJoCo RK4, s per step at dt = 1e-3.
    DoublePendulum,
    /// M2, MuJoCo RK4 with the loop closed by an equality, s per step at dt = 1e-3.
    FourBar,
    /// M3, MuJoCo RK4 on the chain of N ball joints (true) or hinges (false), s per step at dt = 1e-3.
    Chain { ball: bool, links: usize },
    /// M3, Pinocchio's ABA on the ball chain of N links, s per dynamics evaluation.
    PinocchioChain(usize),
    /// A robot, MuJoCo RK4, s per step at the step of [`ROBOT_STEPS`] with this index.
    Robot(RobotId, usize),
}

impl Key {
    /// Every figure the report can take from a file.
    fn all() -> Vec<Key> {
        let mut keys: Vec<Key> = SceneId::ALL
            .into_iter()
            .filter(|&scene| recorded_anchors::anchor(scene).is_some())
            .map(Key::SingleBody)
            .collect();
        keys.extend([Key::DoublePendulum, Key::FourBar]);
        for &(links, _) in &CHAIN_BALL_TIME_PER_STEP {
            keys.extend([
                Key::Chain { ball: true, links },
                Key::Chain { ball: false, links },
                Key::PinocchioChain(links),
            ]);
        }
        for robot in RobotId::ALL {
            keys.extend((0..ROBOT_STEPS.len()).map(|step| Key::Robot(robot, step)));
        }
        keys
    }

    /// The robot figure at `dt`, if the runner measures one.
    pub(crate) fn robot(robot: RobotId, dt: f64) -> Option<Key> {
        ROBOT_STEPS
            .iter()
            .position(|&(step, _)| (step - dt).abs() <= 1e-9 * step)
            .map(|step| Key::Robot(robot, step))
    }

    /// The name in the file: "scene1", "scene4-circle", "m1", "m3-ball-8", "m3-pinocchio-8", "ur5-dt1e-3".
    fn name(self) -> String {
        match self {
            Key::SingleBody(scene) => match scene {
                SceneId::Cuboid => "scene1",
                SceneId::Pendulum => "scene2",
                SceneId::TopCusp => "scene3a",
                SceneId::TopSteady => "scene3b",
                SceneId::RodOnSphere => "scene4-sphere",
                SceneId::RodOnCircle => "scene4-circle",
            }
            .to_owned(),
            Key::DoublePendulum => "m1".to_owned(),
            Key::FourBar => "m2".to_owned(),
            Key::Chain { ball, links } => format!("m3-{}-{links}", if ball { "ball" } else { "hinge" }),
            Key::PinocchioChain(links) => format!("m3-pinocchio-{links}"),
            Key::Robot(robot, step) => format!("{}-dt{}", robot.name(), ROBOT_STEPS[step].1),
        }
    }

    /// The step the figure is measured at (s); None for a time per dynamics evaluation.
    fn step(self) -> Option<f64> {
        match self {
            Key::SingleBody(_) | Key::DoublePendulum | Key::FourBar | Key::Chain { .. } => Some(MECHANISM_STEP),
            Key::PinocchioChain(_) => None,
            Key::Robot(_, step) => Some(ROBOT_STEPS[step].0),
        }
    }
}

/// Where a time the report uses comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Source<'a> {
    /// Measured beside this run; the repeats' spread (largest/smallest − 1).
    Measured(&'a Occasion, f64),
    /// A constant recorded on this day (or as this phrase says).
    Recorded(&'static str),
}

impl Source<'_> {
    /// "measured in this run" or "recorded 2026-11-25", for a legend or a column heading.
    pub(crate) fn short(&self) -> String {
        match self {
            Source::Measured(..) => "measured in this run".to_owned(),
            Source::Recorded(date) => format!("recorded {date}"),
        }
    }

    /// The repeats of a measured figure differ by more than [`SPREAD_LIMIT`].
    pub(crate) fn uncertain(&self) -> bool {
        matches!(self, Source::Measured(_, spread) if *spread > SPREAD_LIMIT)
    }

    /// " ±" after a figure or ratio from an uncertain measurement ([`SPREAD_NOTE`]), else nothing.
    pub(crate) fn flag(&self) -> &'static str {
        if self.uncertain() {
            " ±"
        } else {
            ""
        }
    }
}

/// What [`Source::flag`]'s "±" means, said below a table that shows one.
pub(crate) const SPREAD_NOTE: &str = "±: the repeats of this MuJoCo or Pinocchio figure, measured in this run, \
     differ by more than 20 % (largest/smallest − 1): the machine was busy, and the ratio is uncertain by as much";

/// "measured in this run" if every source is, "recorded DATE" if every one is that constant, else both.
pub(crate) fn sources_short(sources: &[Source]) -> String {
    let measured = sources.iter().filter(|s| matches!(s, Source::Measured(..))).count();
    let recorded = sources.iter().find_map(|s| match s {
        Source::Recorded(date) => Some(*date),
        Source::Measured(..) => None,
    });
    match (measured, recorded) {
        (_, None) => "measured in this run".to_owned(),
        (0, Some(date)) => format!("recorded {date}"),
        (_, Some(date)) => format!("measured in this run, except those recorded {date}"),
    }
}

/// A time (s) and where it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Time<'a> {
    pub(crate) seconds: f64,
    pub(crate) source: Source<'a>,
}

impl Anchors {
    /// No measured figures: the report uses its recorded constants.
    ///
    /// ```
    /// use report::measured_anchors::Anchors;
    ///
    /// assert_eq!(format!("{:?}", Anchors::none()), format!("{:?}", Anchors::default()));
    /// ```
    pub fn none() -> Anchors {
        Anchors::default()
    }

    /// Reads and checks the file at `path` ([`Anchors::parse`]).
    ///
    /// ```
    /// use report::measured_anchors::{Anchors, AnchorsError};
    ///
    /// let missing = Anchors::read(std::path::Path::new("no/such/anchors.json"));
    /// assert!(matches!(missing, Err(AnchorsError::Io { .. })));
    /// ```
    pub fn read(path: &Path) -> Result<Anchors, AnchorsError> {
        let text = std::fs::read_to_string(path).map_err(|source| AnchorsError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Anchors::parse(&text, SystemTime::now())
    }

    /// Checks the text of an anchors file measured no later than `now`: the format, the date, the machine, and per
    /// figure a key the report uses, the step it names, at least [`MIN_REPEATS`] positive finite repeats, and a
    /// minimum and spread that are those of the repeats.
    ///
    /// ```
    /// use std::time::SystemTime;
    /// use report::measured_anchors::Anchors;
    ///
    /// // Not what `tools/anchors/measure` writes: an error naming what is missing, never a silent fallback.
    /// let error = Anchors::parse("{}", SystemTime::now()).unwrap_err();
    /// assert!(error.to_string().contains("missing field"), "{error}");
    /// ```
    pub fn parse(text: &str, now: SystemTime) -> Result<Anchors, AnchorsError> {
        let file: File = serde_json::from_str(text)?;
        if file.format != FORMAT {
            return Err(AnchorsError::Format { found: file.format });
        }
        let measured_at =
            unix_seconds(&file.measured_at).ok_or_else(|| AnchorsError::Date(file.measured_at.clone()))?;
        let now = now.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64);
        if measured_at > now + CLOCK_SLACK {
            return Err(AnchorsError::FromTheFuture(file.measured_at));
        }
        let machine = &file.machine;
        if machine.nproc == 0 {
            return Err(AnchorsError::Machine("nproc is 0".to_owned()));
        }
        let loads = machine.load_before.iter().chain(&machine.load_after);
        if let Some(load) = loads.copied().find(|l| !(l.is_finite() && *l >= 0.0)) {
            return Err(AnchorsError::Machine(format!(
                "load average {load}: must be a finite number, at least 0"
            )));
        }
        let known = Key::all();
        let mut figures = BTreeMap::new();
        for figure in &file.figures {
            let key = known
                .iter()
                .copied()
                .find(|k| k.name() == figure.key)
                .ok_or_else(|| AnchorsError::UnknownKey(figure.key.clone()))?;
            let measured = check_figure(figure, key).map_err(|problem| AnchorsError::Figure {
                key: figure.key.clone(),
                problem,
            })?;
            if figures.insert(figure.key.clone(), measured).is_some() {
                return Err(AnchorsError::Duplicate(figure.key.clone()));
            }
        }
        let occasion = Occasion {
            when: format!("{} {} UTC", &file.measured_at[..10], &file.measured_at[11..16]),
            cores: machine.nproc,
            load: (machine.load_before[0], machine.load_after[0]),
        };
        Ok(Anchors {
            measured: Some((occasion, figures)),
        })
    }

    /// When and under what load the figures were measured, if they were.
    pub fn occasion(&self) -> Option<&Occasion> {
        self.measured.as_ref().map(|(occasion, _)| occasion)
    }

    /// How many figures were measured.
    pub fn len(&self) -> usize {
        self.measured.as_ref().map_or(0, |(_, figures)| figures.len())
    }

    /// No figure was measured.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The figure `key`: measured, if the file has it, else the constant `recorded` (s) of the day `date`.
    pub(crate) fn time(&self, key: Key, recorded: f64, date: &'static str) -> Time<'_> {
        let measured = self
            .measured
            .as_ref()
            .and_then(|(occasion, figures)| Some((occasion, figures.get(&key.name())?)));
        match measured {
            Some((occasion, m)) => Time {
                seconds: m.seconds,
                source: Source::Measured(occasion, m.spread),
            },
            None => Time {
                seconds: recorded,
                source: Source::Recorded(date),
            },
        }
    }

    /// The sentence saying when and under what load the figures "measured in this run" were measured.
    pub(crate) fn occasion_note(&self) -> Option<String> {
        let occasion = self.occasion()?;
        Some(format!(
            "Measured in this run: {} MuJoCo and Pinocchio figures by `tools/anchors/measure` (its models in \
             `tools/anchors/scenes.py`), {}, 1-minute load average {:.2} before and {:.2} after on {} cores; each the fastest of \
             at least {MIN_REPEATS} repeats (listed with its command at the end of the report).",
            self.len(),
            occasion.when,
            occasion.load.0,
            occasion.load.1,
            occasion.cores
        ))
    }

    /// The report's last section: every measured figure with its command, repeats and spread; empty without a file.
    pub(crate) fn section(&self) -> String {
        let (Some(note), Some((_, figures))) = (self.occasion_note(), &self.measured) else {
            return String::new();
        };
        let mut out = format!(
            "## MuJoCo and Pinocchio figures measured in this run\n\n{note} Spread: largest/smallest − 1 of the \
             repeats; above {:.0} % the figure and its ratios are marked ±.\n\n| figure | what | fastest (µs) | \
             repeats | spread | command |\n|---|---|---|---|---|---|\n",
            SPREAD_LIMIT * 100.0
        );
        for (key, m) in figures {
            out.push_str(&format!(
                "| {key} | {} | {:.2} | {} | {:.0} %{} | `{}` |\n",
                m.what,
                m.seconds * 1e6,
                m.repeats,
                m.spread * 100.0,
                if m.spread > SPREAD_LIMIT { " ±" } else { "" },
                m.command
            ));
        }
        out.push('\n');
        out
    }
}

/// Why `figure` (known as `key`) cannot be used, or what it measured.
fn check_figure(figure: &FileFigure, key: Key) -> Result<Measured, String> {
    match (figure.dt, key.step()) {
        (None, None) => {}
        (Some(dt), Some(step)) if (dt - step).abs() <= 1e-9 * step => {}
        (dt, step) => {
            let show = |x: Option<f64>| x.map_or("none (a time per evaluation)".to_owned(), |x| format!("{x:e} s"));
            return Err(format!("dt {}: the report compares it at {}", show(dt), show(step)));
        }
    }
    if figure.repeats.len() < MIN_REPEATS {
        return Err(format!(
            "{} repeats: at least {MIN_REPEATS} are needed, their minimum kept",
            figure.repeats.len()
        ));
    }
    if let Some((k, t)) = figure
        .repeats
        .iter()
        .enumerate()
        .find(|(_, t)| !(t.is_finite() && **t > 0.0))
    {
        return Err(format!("repeat {} is {t} s: a time must be positive and finite", k + 1));
    }
    let fastest = figure.repeats.iter().copied().fold(f64::INFINITY, f64::min);
    let slowest = figure.repeats.iter().copied().fold(0.0, f64::max);
    if (figure.min - fastest).abs() > 1e-12 * fastest {
        return Err(format!(
            "min {:e} s is not the fastest repeat, {fastest:e} s",
            figure.min
        ));
    }
    let spread = slowest / fastest - 1.0;
    if (figure.spread - spread).abs() > 1e-9 {
        return Err(format!(
            "spread {} is not the repeats' largest/smallest − 1, {spread}",
            figure.spread
        ));
    }
    if let Some(point) = figure
        .errors
        .iter()
        .find(|p| !(p.dt.is_finite() && p.dt > 0.0 && p.error.is_finite() && p.error >= 0.0))
    {
        return Err(format!(
            "error {} at dt {}: a step must be positive and an error finite and at least 0",
            point.error, point.dt
        ));
    }
    Ok(Measured {
        seconds: fastest,
        spread,
        repeats: figure.repeats.len(),
        what: figure.what.clone(),
        command: figure.command.clone(),
    })
}

/// Seconds since 1970 of a UTC date-time "YYYY-MM-DDTHH:MM:SSZ", if it is one.
fn unix_seconds(text: &str) -> Option<i64> {
    let bytes = text.as_bytes();
    let shape = text.len() == 20
        && bytes.iter().enumerate().all(|(i, b)| match i {
            4 | 7 => *b == b'-',
            10 => *b == b'T',
            13 | 16 => *b == b':',
            19 => *b == b'Z',
            _ => b.is_ascii_digit(),
        });
    if !shape {
        return None;
    }
    let field = |range: std::ops::Range<usize>| text[range].parse::<i64>().ok();
    let (year, month, day) = (field(0..4)?, field(5..7)?, field(8..10)?);
    let (hour, minute, second) = (field(11..13)?, field(14..16)?, field(17..19)?);
    let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
    let days_in_month = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    if !(1..=12).contains(&month) || !(1..=days_in_month[month as usize - 1]).contains(&day) {
        return None;
    }
    if hour > 23 || minute > 59 || second > 59 {
        return None;
    }
    // Days from 1970-01-01 to the date (the proleptic Gregorian calendar, years counted from March).
    let (y, m) = if month <= 2 {
        (year - 1, month + 9)
    } else {
        (year, month - 3)
    };
    let era = y.div_euclid(400);
    let year_of_era = y - era * 400;
    let day_of_year = (153 * m + 2) / 5 + day - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    let days = era * 146_097 + day_of_era - 719_468;
    Some(days * 86_400 + hour * 3600 + minute * 60 + second)
}

/// A single-body scene's MuJoCo anchor, if it has one: the recorded errors (they belong to the model, not the
/// machine) with the time per step measured in this run where `anchors` has it; and where that time comes from.
pub(crate) fn single_body_anchor(anchors: &Anchors, scene: SceneId) -> Option<(Anchor, Source<'_>)> {
    let recorded = recorded_anchors::anchor(scene)?;
    let time = anchors.time(Key::SingleBody(scene), recorded.time_per_step, SINGLE_BODY_RECORDED);
    Some((
        Anchor {
            time_per_step: time.seconds,
            ..recorded
        },
        time.source,
    ))
}

/// Where a single-body scene's MuJoCo figures come from: recorded, or with the time measured in this run.
pub(crate) fn single_body_provenance(source: &Source) -> String {
    match source {
        Source::Recorded(_) => SINGLE_BODY_MEASURED.to_owned(),
        Source::Measured(..) => format!(
            "MuJoCo 4.0 (RK4): its time per step measured in this run by `tools/anchors/measure` (its models in \
             `tools/anchors/scenes.py`), its errors recorded in this code on {}",
            SINGLE_BODY_RECORDED
        ),
    }
}

/// M1's MuJoCo time per step at dt = 1e-3: measured in this run if `anchors` has it, else [`DOUBLE_PENDULUM`]'s.
pub(crate) fn double_pendulum_time(anchors: &Anchors) -> Time<'_> {
    anchors.time(Key::DoublePendulum, DOUBLE_PENDULUM.time_per_step, MECHANISMS_DATE)
}

/// M2's MuJoCo time per step at dt = 1e-3: measured in this run if `anchors` has it, else [`FOUR_BAR_TIME_PER_STEP`].
pub(crate) fn four_bar_time(anchors: &Anchors) -> Time<'_> {
    anchors.time(Key::FourBar, FOUR_BAR_TIME_PER_STEP, MECHANISMS_DATE)
}

/// M3's MuJoCo times per step by chain length, ball joints or hinges: measured where `anchors` has them.
pub(crate) fn chain_times(anchors: &Anchors, ball: bool) -> Vec<(usize, Time<'_>)> {
    let recorded = if ball {
        &CHAIN_BALL_TIME_PER_STEP
    } else {
        &CHAIN_HINGE_TIME_PER_STEP
    };
    recorded
        .iter()
        .map(|&(links, seconds)| {
            (
                links,
                anchors.time(Key::Chain { ball, links }, seconds, MECHANISMS_DATE),
            )
        })
        .collect()
}

/// M3's Pinocchio times per evaluation by chain length: measured where `anchors` has them.
pub(crate) fn pinocchio_chain_times(anchors: &Anchors) -> Vec<(usize, Time<'_>)> {
    PINOCCHIO_CHAIN_EVALUATION
        .iter()
        .map(|&(links, seconds)| {
            (
                links,
                anchors.time(Key::PinocchioChain(links), seconds, MECHANISMS_DATE),
            )
        })
        .collect()
}

/// MuJoCo's time per step of a recorded run of robot `id`: measured in this run if `anchors` has it.
pub(crate) fn mujoco_time<'a>(anchors: &'a Anchors, id: RobotId, run: &reference::robots::MujocoRun) -> Time<'a> {
    let recorded = run.microseconds_per_step * 1e-6;
    match Key::robot(id, run.dt) {
        Some(key) => anchors.time(key, recorded, RECORDED_WHEN),
        None => Time {
            seconds: recorded,
            source: Source::Recorded(RECORDED_WHEN),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unix_seconds_counts_from_1970() {
        assert_eq!(unix_seconds("1970-01-01T00:00:00Z"), Some(0));
        assert_eq!(unix_seconds("2000-03-01T00:00:00Z"), Some(951_868_800));
        assert_eq!(unix_seconds("2026-11-27T18:05:00Z"), Some(1_795_802_700));
        assert_eq!(unix_seconds("2026-02-29T00:00:00Z"), None);
        assert_eq!(unix_seconds("2026-11-27 18:05:00"), None);
    }

    const FILE: &str = r#"{"format": 1, "measured_at": "2026-11-27T18:05:00Z",
        "machine": {"nproc": 2, "load_before": [3.5, 3.2, 2.7], "load_after": [2.0, 2.5, 2.6]},
        "figures": [{"key": "m2", "what": "MuJoCo 4.0 RK4 step at dt = 1e-3", "dt": 0.001,
            "command": "python four_bar.py OUTDIR m2", "repeats": [8e-6, 8e-6, 8e-6, 8e-6, 12e-6], "min": 8e-6,
            "spread": 0.5}]}"#;

    #[test]
    fn a_measured_figure_replaces_its_constant_and_the_others_stay_recorded() {
        let anchors = Anchors::parse(FILE, SystemTime::now()).unwrap();
        let m2 = anchors.time(Key::FourBar, 11e-6, "2026-11-25");
        assert_eq!(m2.seconds, 8e-6);
        assert_eq!(
            (m2.source.short(), m2.source.flag()),
            ("measured in this run".to_owned(), " ±")
        );
        let m1 = anchors.time(Key::DoublePendulum, 5.19e-6, "2026-11-25");
        assert_eq!((m1.seconds, m1.source), (5.19e-6, Source::Recorded("2026-11-25")));
        assert_eq!(m1.source.flag(), "");
        assert_eq!(
            sources_short(&[m1.source, m2.source]),
            "measured in this run, except those recorded 2026-11-25"
        );
        let section = anchors.section();
        assert!(
            section.contains(
                "| m2 | MuJoCo 4.0 RK4 step at dt = 1e-3 | 8.00 | 5 | 50 % ± | `python four_bar.py OUTDIR m2` |"
            ),
            "{section}"
        );
        assert!(
            section.contains("load average 3.50 before and 2.00 after on 2 cores"),
            "{section}"
        );
        assert!(Anchors::none().section().is_empty());
        assert_eq!(Anchors::none().time(Key::FourBar, 11e-6, "2026-11-25").seconds, 11e-6);
    }

    #[test]
    fn every_key_names_itself_once() {
        let names: Vec<String> = Key::all().into_iter().map(Key::name).collect();
        let unique: std::collections::BTreeSet<&String> = names.iter().collect();
        assert_eq!(unique.len(), names.len());
        assert!(names.contains(&"m3-hinge-64".to_owned()) && names.contains(&"solo12-dt1e-4".to_owned()));
        // The single bodies with a recorded anchor, and no others.
        for name in ["scene1", "scene2", "scene3a", "scene4-circle"] {
            assert!(names.contains(&name.to_owned()), "{name}");
        }
        assert!(!names.contains(&"scene3b".to_owned()) && !names.contains(&"scene4-sphere".to_owned()));
    }

    /// A single body's measured time replaces the recorded one and says so; its errors stay the recorded ones; a
    /// scene without a recorded anchor has none, measured or not.
    #[test]
    fn a_single_body_takes_its_measured_time_and_keeps_its_recorded_errors() {
        let file = FILE.replace(r#""key": "m2""#, r#""key": "scene1""#);
        let anchors = Anchors::parse(&file, SystemTime::now()).unwrap();
        let recorded = recorded_anchors::anchor(SceneId::Cuboid).unwrap();
        let (anchor, source) = single_body_anchor(&anchors, SceneId::Cuboid).unwrap();
        assert_eq!(anchor.time_per_step, 8e-6);
        assert_eq!(anchor.points, recorded.points);
        assert_eq!(source.short(), "measured in this run");
        assert!(single_body_provenance(&source).contains("measured in this run by `tools/anchors/measure`"));
        let (unmeasured, source) = single_body_anchor(&anchors, SceneId::Pendulum).unwrap();
        assert_eq!(
            unmeasured.time_per_step,
            recorded_anchors::anchor(SceneId::Pendulum).unwrap().time_per_step
        );
        assert_eq!(single_body_provenance(&source), SINGLE_BODY_MEASURED);
        assert!(single_body_anchor(&anchors, SceneId::TopSteady).is_none());
        // A single-body figure measured at another step is refused by name.
        let wrong = file.replace(r#""dt": 0.001"#, r#""dt": 0.01"#);
        let error = Anchors::parse(&wrong, SystemTime::now()).unwrap_err().to_string();
        assert!(
            error.contains("scene1") && error.contains("the report compares it at"),
            "{error}"
        );
    }
}
