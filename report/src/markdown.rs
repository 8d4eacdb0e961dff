//! The Markdown the report's sections share: user text escaped, numbers for tables, and the order of table rows.

use std::cmp::Ordering;
use std::fmt::Write as _;

use dynamics::integrate::Integrator;
use dynamics::limits::{LimitChange, LimitTransition};
use scenarios::Formulation;
use scene_file::AlgebraKind;

/// User text (a scene's title, body and joint names, a path) as inline Markdown that shows as written: line
/// breaks and other control characters become spaces (no new block, so no heading or list can start), and the
/// characters that open emphasis, code, links, HTML or table cells are backslash-escaped.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.push(' ');
        } else {
            if matches!(c, '\\' | '`' | '*' | '_' | '[' | ']' | '<' | '>' | '#' | '|') {
                out.push('\\');
            }
            out.push(c);
        }
    }
    out
}

/// A table's header row and the row under it, for `columns`.
pub(crate) fn table_header(out: &mut String, columns: &[impl AsRef<str>]) {
    let columns: Vec<&str> = columns.iter().map(AsRef::as_ref).collect();
    let _ = writeln!(out, "| {} |", columns.join(" | "));
    let _ = writeln!(out, "|{}|", vec!["---"; columns.len()].join("|"));
}

/// A number for a table: two significant digits, or a plain 0.
pub(crate) fn scientific(value: f64) -> String {
    if value == 0.0 {
        "0".to_string()
    } else {
        format!("{value:.1e}")
    }
}

/// Where a table row goes: algebra, formulation and integrator (each in its declared order), then the step.
pub(crate) type RowKey = (AlgebraKind, usize, usize, f64);

/// A formulation's place in [`Formulation::ALL`] (the free body's `None` first).
pub(crate) fn formulation_rank(formulation: Option<Formulation>) -> usize {
    formulation.map_or(0, |f| {
        1 + Formulation::ALL.iter().position(|&g| g == f).unwrap_or(usize::MAX - 1)
    })
}

/// An integrator's place in [`Integrator::ALL`].
pub(crate) fn integrator_rank(integrator: Integrator) -> usize {
    Integrator::ALL
        .iter()
        .position(|&i| i == integrator)
        .unwrap_or(usize::MAX)
}

/// The order of table rows: by configuration, then by step from the coarsest to the finest, compared as numbers
/// (as text, 1e-4 would come before 2e-3).
pub(crate) fn compare_rows(a: &RowKey, b: &RowKey) -> Ordering {
    (a.0, a.1, a.2).cmp(&(b.0, b.1, b.2)).then_with(|| b.3.total_cmp(&a.3))
}

/// How many of each one-sided transition a run made.
pub(crate) struct TransitionCounts {
    pub(crate) bounces: usize,
    pub(crate) holds: usize,
    pub(crate) releases: usize,
    pub(crate) sticks: usize,
    pub(crate) slips: usize,
}

impl TransitionCounts {
    /// The counts of `transitions`.
    pub(crate) fn of(transitions: &[LimitTransition]) -> Self {
        let count = |kind: fn(&LimitChange) -> bool| transitions.iter().filter(|t| kind(&t.change)).count();
        TransitionCounts {
            bounces: count(|c| matches!(c, LimitChange::Bounced { .. })),
            holds: count(|c| matches!(c, LimitChange::Held { .. })),
            releases: count(|c| matches!(c, LimitChange::Released { .. })),
            sticks: count(|c| matches!(c, LimitChange::Stuck { .. })),
            slips: count(|c| matches!(c, LimitChange::Slipped { .. })),
        }
    }
}

/// The table cells of a run's transitions: bounces, holds, releases and the first transition's time (s).
pub(crate) fn transition_cells(transitions: &[LimitTransition]) -> String {
    let counts = TransitionCounts::of(transitions);
    let first = transitions.first().map_or("–".to_owned(), |t| format!("{:.15}", t.t));
    format!("{} | {} | {} | {first}", counts.bounces, counts.holds, counts.releases)
}
