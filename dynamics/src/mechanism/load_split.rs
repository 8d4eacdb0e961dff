//! The split of an indeterminate load among held constraints (docs/contacts.md "Indeterminate loads"). A block resting
//! flat on four corners, a foot on two toes: the rows repeat each other, and every multiplier vector in
//! `λ₀ + span(Z)` (Z the Gram matrix's null space) moves the bodies alike. The motion does not care which; whether a
//! contact is pushed and sticks does. The split chosen is the one with the widest margin: it maximises m with every
//! held constraint's push at least m and every sticking contact's friction at least m inside its cone,
//!
//! ```text
//! push_i(y) ≥ m,    μ_s,i N_i(y) − |F_t,i(y)| ≥ m,    λ(y) = λ₀ + Z y,
//! ```
//!
//! a small second-order cone program, solved by a barrier method (Newton steps on
//! `−τ m − Σ log(push − m) − Σ log((μN − m)² − |F_t|²) − log(R² − |y|²)` for τ growing thirtyfold). Its margin m* is
//! positive exactly when some split pushes everywhere and sticks where it should: the held set is consistent.

use nalgebra::{DMatrix, DVector};

/// One held constraint's part of the margin: its push's row (with the push's sign) and, for a sticking contact, its
/// two friction rows and static coefficient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Held {
    pub push: (usize, f64),
    pub friction: Option<(usize, f64)>,
}

/// The split of `least_norm` (a solution of the rows' equations) over the `null` space's columns with the widest
/// margin for `held`, and that margin; `least_norm` itself where every margin is positive there already (the
/// transitions only need the sign of the least margin, and a positive one at some split means a positive widest).
/// Unbounded margins (a jammed set, whose pushes grow without end) are capped at `CAP` times the loads' size.
pub(super) fn widest_split(least_norm: &DVector<f64>, null: &DMatrix<f64>, held: &[Held]) -> (DVector<f64>, f64) {
    let margin_at = |lambda: &DVector<f64>| least_margin(lambda, held);
    let least = margin_at(least_norm);
    if null.ncols() == 0 || held.is_empty() || least > 0.0 {
        return (least_norm.clone(), least);
    }
    let scale = least_norm.amax().max(f64::MIN_POSITIVE);
    let radius = CAP * scale;
    let problem = Problem {
        base: least_norm,
        null,
        held,
        radius,
    };
    let d = null.ncols();
    // Strictly inside: the least-norm split with the margin below every constraint's.
    let mut x = DVector::zeros(d + 1);
    x[d] = least - scale;
    let mut tau = 1.0 / scale;
    let count = (held.len() + 1) as f64;
    let mut previous = f64::NEG_INFINITY;
    for _ in 0..OUTER_STEPS {
        problem.centre(&mut x, tau);
        // The margin stops growing once round-off holds the barrier's Newton steps back.
        if x[d] - previous <= GAP * scale {
            break;
        }
        previous = x[d];
        if count / tau <= GAP * scale {
            break;
        }
        tau *= TAU_GROWTH;
    }
    let lambda = problem.lambda(&x);
    let margin = margin_at(&lambda);
    (lambda, margin)
}

/// The least of the held constraints' margins at the multipliers `lambda` (infinite with none held).
pub(super) fn least_margin(lambda: &DVector<f64>, held: &[Held]) -> f64 {
    margins(lambda, held).fold(f64::INFINITY, f64::min)
}

/// Each held constraint's margin at the multipliers `lambda`: its push, or its cone's `μ N − |F_t|`.
fn margins<'a>(lambda: &'a DVector<f64>, held: &'a [Held]) -> impl Iterator<Item = f64> + 'a {
    held.iter().map(|h| {
        let push = h.push.1 * lambda[h.push.0];
        match h.friction {
            None => push,
            Some((row, mu)) => mu * push - lambda[row].hypot(lambda[row + 1]),
        }
    })
}

/// Barrier steps: the widest split's program at one weight τ.
struct Problem<'a> {
    base: &'a DVector<f64>,
    null: &'a DMatrix<f64>,
    held: &'a [Held],
    radius: f64,
}

impl Problem<'_> {
    fn lambda(&self, x: &DVector<f64>) -> DVector<f64> {
        let d = self.null.ncols();
        self.base + self.null * x.rows(0, d)
    }

    /// The barrier's value, gradient and Hessian at x = (y, m), or `None` outside the constraints.
    fn barrier(&self, x: &DVector<f64>, tau: f64) -> Option<(f64, DVector<f64>, DMatrix<f64>)> {
        let d = self.null.ncols();
        let n = d + 1;
        let lambda = self.lambda(x);
        let m = x[d];
        let mut value = -tau * m;
        let mut gradient = DVector::zeros(n);
        gradient[d] = -tau;
        let mut hessian = DMatrix::zeros(n, n);
        // The row of a multiplier as a function of x: (Z's row, 0).
        let row_of = |r: usize| {
            let mut g = DVector::zeros(n);
            g.rows_mut(0, d).copy_from(&self.null.row(r).transpose());
            g
        };
        let mut unit_m = DVector::zeros(n);
        unit_m[d] = 1.0;
        for h in self.held {
            let push_row = row_of(h.push.0) * h.push.1;
            let push = h.push.1 * lambda[h.push.0];
            match h.friction {
                None => {
                    // −log(u), u = push − m.
                    let u = push - m;
                    if u <= 0.0 {
                        return None;
                    }
                    let du = &push_row - &unit_m;
                    value -= u.ln();
                    gradient -= &du / u;
                    hessian += &du * du.transpose() / (u * u);
                }
                Some((row, mu)) => {
                    // −log(u² − v·v), u = μ push − m, v = (F₁, F₂).
                    let u = mu * push - m;
                    let v = [lambda[row], lambda[row + 1]];
                    let s = u * u - v[0] * v[0] - v[1] * v[1];
                    if u <= 0.0 || s <= 0.0 {
                        return None;
                    }
                    let du = &push_row * mu - &unit_m;
                    let dv = [row_of(row), row_of(row + 1)];
                    let ds = &du * (2.0 * u) - &dv[0] * (2.0 * v[0]) - &dv[1] * (2.0 * v[1]);
                    value -= s.ln();
                    gradient -= &ds / s;
                    // ∇²s = 2 du duᵀ − 2 Σ dv dvᵀ; ∇²(−log s) = ds dsᵀ/s² − ∇²s/s.
                    let second = &du * du.transpose() * 2.0
                        - &dv[0] * dv[0].transpose() * 2.0
                        - &dv[1] * dv[1].transpose() * 2.0;
                    hessian += &ds * ds.transpose() / (s * s) - second / s;
                }
            }
        }
        // −log(R² − |y|²): the split stays bounded.
        let y = x.rows(0, d);
        let w = self.radius * self.radius - y.norm_squared();
        if w <= 0.0 {
            return None;
        }
        value -= w.ln();
        let mut dw = DVector::zeros(n);
        dw.rows_mut(0, d).copy_from(&(y * -2.0));
        gradient -= &dw / w;
        let mut second = DMatrix::zeros(n, n);
        second.view_mut((0, 0), (d, d)).fill_diagonal(-2.0);
        hessian += &dw * dw.transpose() / (w * w) - second / w;
        Some((value, gradient, hessian))
    }

    /// Newton's method on the barrier at weight τ from `x`, with backtracking that stays inside.
    fn centre(&self, x: &mut DVector<f64>, tau: f64) {
        for _ in 0..NEWTON_STEPS {
            let Some((value, gradient, hessian)) = self.barrier(x, tau) else {
                return;
            };
            let Some(step) = hessian.clone().cholesky().map(|c| c.solve(&-&gradient)) else {
                return;
            };
            let decrement = -gradient.dot(&step);
            if decrement <= NEWTON_TOLERANCE {
                return;
            }
            let mut length = 1.0;
            loop {
                let trial = &*x + &step * length;
                match self.barrier(&trial, tau) {
                    Some((next, ..)) if next <= value - 0.25 * length * decrement => {
                        *x = trial;
                        break;
                    }
                    _ if length < MIN_STEP => return,
                    _ => length *= 0.5,
                }
            }
        }
    }
}

/// The barrier's weight grows this many times at most, by this factor each time.
const OUTER_STEPS: usize = 12;
const TAU_GROWTH: f64 = 30.0;
/// Newton steps per weight at most, and the shortest backtracked step.
const NEWTON_STEPS: usize = 30;
const MIN_STEP: f64 = 1e-6;
/// A Newton decrement (`gᵀH⁻¹g`, scale-free for a barrier) below this has converged.
const NEWTON_TOLERANCE: f64 = 1e-12;
/// The barrier's duality gap, relative to the loads, at which the split is found.
const GAP: f64 = 1e-14;
/// Margins beyond this many times the loads count as unbounded.
const CAP: f64 = 1e6;
