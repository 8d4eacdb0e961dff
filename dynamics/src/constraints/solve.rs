//! The reaction solve (SPEC §7.1). Given rows `a_i` (velocity coordinates) and right-hand sides `r'_i`, find
//! the reaction wrench coordinates y with `a_i·H⁻¹y = r'_i`, where `H = diag(I₁, I₂, I₃, m, m, m)`.
//!
//! **Kinetic-metric solution** (method 1 of §7.1): the y of least `yᵀH⁻¹y` — the reaction that does no work
//! on any motion the constraint allows. With `G = A H^{-1/2}`, `y = H^{1/2} G⁺_r r'`, where `G⁺_r` is the
//! pseudo-inverse truncated to the constraint's **known rank r**: off the manifold incidence constraints pick
//! up small spurious singular values (E8), which a relative cut-off would switch on as drift grows. The plain
//! pseudo-inverse `C⁺` in wrench coordinates is never used (it does work, §7.1 method 3).
//!
//! Two evaluations of the same solution, both on fixed-size 6×6 matrices:
//! * rows = rank (e.g. virtual power, whose rows are independent, or a PGA point once its identically zero
//!   e123 row is dropped): `y = Aᵀλ` with the Cholesky solve of the Gram matrix `(A H⁻¹ Aᵀ) λ = r'` — SPEC §6's
//!   `K λ = b`;
//! * rows > rank (pinning: one row per coefficient): the eigen-decomposition of the normal matrix
//!   `N = GᵀG = V Σ² Vᵀ`, keeping the r largest: `G⁺_r r' = V_r Σ_r⁻² V_rᵀ Gᵀ r'`. This squares the condition
//!   number of G; with the H^{-1/2} scaling the kept singular values of the scenes lie within a factor ~10²
//!   of each other, so the loss is below 1e-12 relative. The decomposition is a cyclic Jacobi iteration
//!   ([`symmetric_eigen`]): nalgebra's `SymmetricEigen` mis-pairs eigenvalues and eigenvectors for some
//!   matrices (nalgebra issue #1109, open), and did so on the pinned hinge's normal matrix.
//!
//! **Supplied reaction basis** (method 2): `y = Y λ` with λ the least-squares solution of `(A H⁻¹ Y) λ = r'`.

use nalgebra::{Matrix6, Vector6};

use crate::constraints::rows::{ConstraintRow, MAX_ROWS};

/// Thresholds of the solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverSettings {
    /// The system is rank deficient when its r-th singular value (of `A H^{-1/2}`, or of `A H⁻¹ Y` for a
    /// basis) is below this fraction of the largest. Eigenvalues of the normal matrix resolve singular value
    /// ratios down to ~1e-7, hence 1e-6.
    pub rank_tolerance: f64,
    /// The system is inconsistent when the solution leaves a residual `|a·H⁻¹y − r'|` above this fraction of
    /// `|r'|` (and above round-off, see [`Consistency`]). Off the manifold, incidence constraints are
    /// inconsistent by construction, by about the drift over the object's size (0.1 relative for the rod end 1 cm
    /// off its circle of radius 0.5 m, measured), which the fixed-rank solve is designed to ride out; a
    /// contradiction — a reaction basis that cannot hold the body — leaves a residual of order 1.
    pub consistency_tolerance: f64,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            rank_tolerance: 1e-6,
            consistency_tolerance: 0.5,
        }
    }
}

/// Whether to check that the solution satisfies the rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Consistency {
    /// Check, ignoring residuals below [`ROUND_OFF`] × `scale`, the size of the terms that were summed into the
    /// right-hand sides (a right-hand side that cancels to round-off is noise, not a condition to satisfy).
    Check { scale: f64 },
    /// Do not check: a least-squares step (the projection's Gauss–Newton step) is fine with a residual.
    Skip,
}

/// Relative size of round-off in a right-hand side summed from terms of size `scale`.
pub const ROUND_OFF: f64 = 1e-10;

impl Consistency {
    fn violated(self, residual_squared: f64, rhs_squared: f64, settings: &SolverSettings) -> bool {
        match self {
            Consistency::Check { scale } => {
                residual_squared > settings.consistency_tolerance.powi(2) * rhs_squared
                    && residual_squared > (ROUND_OFF * scale).powi(2)
            }
            Consistency::Skip => false,
        }
    }
}

/// Why a solve failed (the system adds the constraint names).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolveFailure {
    RankDeficient { singular_value: f64, largest: f64 },
    Inconsistent { relative_residual: f64 },
}

fn dot(a: &[f64; 6], b: &Vector6<f64>) -> f64 {
    a.iter().zip(b.iter()).map(|(x, y)| x * y).sum()
}

/// Solve of the leading `n×n` block of a Gram matrix (`n` ≤ 6; the rest of the result is zero) by its
/// `L D Lᵀ` factorisation (Cholesky without square roots), checking that the pivots `D_jj` stay above
/// `tolerance²` × the largest diagonal entry (pivots scale like squared singular values). The block is
/// factored at its own fixed size, so the loops unroll: a 3-row ball joint does not pay for a padded 6×6
/// factorisation. (nalgebra's `Cholesky` on the same fixed-size blocks, with its two triangular solves, took
/// 20% of a constrained PGA step, measured with perf: the chain of square roots and divisions dominates at
/// these sizes, and this is the textbook algorithm, Golub & Van Loan §4.1, with one division per column.)
fn solve_gram(gram: Matrix6<f64>, rhs: Vector6<f64>, n: usize, tolerance: f64) -> Result<Vector6<f64>, SolveFailure> {
    match n {
        0 => Ok(Vector6::zeros()),
        1 => solve_gram_block::<1>(&gram, &rhs, tolerance),
        2 => solve_gram_block::<2>(&gram, &rhs, tolerance),
        3 => solve_gram_block::<3>(&gram, &rhs, tolerance),
        4 => solve_gram_block::<4>(&gram, &rhs, tolerance),
        5 => solve_gram_block::<5>(&gram, &rhs, tolerance),
        _ => solve_gram_block::<6>(&gram, &rhs, tolerance),
    }
}

fn solve_gram_block<const N: usize>(
    gram: &Matrix6<f64>,
    rhs: &Vector6<f64>,
    tolerance: f64,
) -> Result<Vector6<f64>, SolveFailure> {
    let largest = (0..N).map(|i| gram[(i, i)]).fold(0.0, f64::max);
    // G = L D Lᵀ with unit lower L, column by column; `scaled[i][k]` = L_ik D_kk.
    let mut lower = [[0.0; N]; N];
    let mut scaled = [[0.0; N]; N];
    let mut reciprocal = [0.0; N];
    for j in 0..N {
        let pivot = gram[(j, j)] - (0..j).map(|k| lower[j][k] * scaled[j][k]).sum::<f64>();
        if !(largest > 0.0 && pivot > tolerance * tolerance * largest) {
            return Err(SolveFailure::RankDeficient {
                singular_value: pivot.max(0.0).sqrt(),
                largest: largest.max(0.0).sqrt(),
            });
        }
        reciprocal[j] = 1.0 / pivot;
        for i in j + 1..N {
            scaled[i][j] = gram[(i, j)] - (0..j).map(|k| scaled[i][k] * lower[j][k]).sum::<f64>();
            lower[i][j] = scaled[i][j] * reciprocal[j];
        }
    }
    // L z = rhs, D w = z, Lᵀ x = w.
    let mut x = Vector6::zeros();
    for i in 0..N {
        x[i] = rhs[i] - (0..i).map(|k| lower[i][k] * x[k]).sum::<f64>();
    }
    for i in (0..N).rev() {
        x[i] = x[i] * reciprocal[i] - (i + 1..N).map(|k| lower[k][i] * x[k]).sum::<f64>();
    }
    Ok(x)
}

/// The kinetic-metric reaction `y` (wrench coordinates `(τ; f)`) for rows `a_i·H⁻¹y = rhs_i` of known
/// `rank`; `metric` is the diagonal of H.
pub fn kinetic_metric(
    rows: &[ConstraintRow],
    rhs: &[f64],
    rank: usize,
    metric: &Vector6<f64>,
    settings: &SolverSettings,
    consistency: Consistency,
) -> Result<Vector6<f64>, SolveFailure> {
    if rank == 0 || rows.is_empty() {
        return Ok(Vector6::zeros());
    }
    // Rows with an exactly zero Jacobian (e.g. the e123 coefficient of a PGA point, which no motion changes)
    // add nothing to either evaluation; without them the rows are often exactly the rank.
    let mut independent = [0usize; 6];
    let mut count = 0;
    for (i, row) in rows.iter().enumerate() {
        if row.jacobian.iter().any(|&a| a != 0.0) {
            if count < 6 {
                independent[count] = i;
            }
            count += 1;
        }
    }
    if count == rank && rank <= 6 {
        let selected = &independent[..rank];
        let inverse_metric = metric.map(|h| 1.0 / h);
        let mut gram = Matrix6::identity();
        let mut padded = Vector6::zeros();
        for (i, &row_i) in selected.iter().enumerate() {
            let weighted = Vector6::from(rows[row_i].jacobian).component_mul(&inverse_metric);
            for (j, &row_j) in selected.iter().enumerate() {
                gram[(i, j)] = dot(&rows[row_j].jacobian, &weighted);
            }
            padded[i] = rhs[row_i];
        }
        let lambda = solve_gram(gram, padded, rank, settings.rank_tolerance)?;
        return Ok(selected
            .iter()
            .zip(lambda.iter())
            .fold(Vector6::zeros(), |y, (&row, l)| {
                y + Vector6::from(rows[row].jacobian) * *l
            }));
    }
    let scale = metric.map(|h| 1.0 / h.sqrt());
    // Σ g gᵀ accumulated on the upper triangle only (the products are symmetric, so the mirror is exact).
    let mut upper = [[0.0; 6]; 6];
    let mut projected = [0.0; 6];
    let mut rhs_squared = 0.0;
    for (row, &r) in rows.iter().zip(rhs) {
        let g: [f64; 6] = std::array::from_fn(|i| row.jacobian[i] * scale[i]);
        for i in 0..6 {
            for j in i..6 {
                upper[i][j] += g[i] * g[j];
            }
            projected[i] += g[i] * r;
        }
        rhs_squared += r * r;
    }
    let normal = Matrix6::from_fn(|i, j| if i <= j { upper[i][j] } else { upper[j][i] });
    let projected = Vector6::from(projected);
    let (eigenvalues, eigenvectors) = symmetric_eigen(normal);
    // Indices by decreasing eigenvalue (a stable insertion sort: the same order as a stable library sort,
    // without its call overhead on 6 entries).
    let mut order: [usize; 6] = std::array::from_fn(|i| i);
    for end in 1..6 {
        let mut k = end;
        while k > 0 && eigenvalues[order[k]].total_cmp(&eigenvalues[order[k - 1]]).is_gt() {
            order.swap(k, k - 1);
            k -= 1;
        }
    }
    let largest = eigenvalues[order[0]];
    let kept = eigenvalues[order[rank.min(6) - 1]];
    if rank > 6 || !(largest > 0.0 && kept > settings.rank_tolerance.powi(2) * largest) {
        return Err(SolveFailure::RankDeficient {
            singular_value: kept.max(0.0).sqrt(),
            largest: largest.max(0.0).sqrt(),
        });
    }
    let mut z = Vector6::zeros();
    let mut explained = 0.0;
    for &k in &order[..rank] {
        let v = eigenvectors.column(k);
        let component = v.dot(&projected);
        z += v * (component / eigenvalues[k]);
        explained += component * component / eigenvalues[k];
    }
    // |G z − r'|² = |r'|² − Σ_kept (v·Gᵀr')²/σ²: what the kept directions do not explain.
    let residual_squared = (rhs_squared - explained).max(0.0);
    if consistency.violated(residual_squared, rhs_squared, settings) {
        return Err(SolveFailure::Inconsistent {
            relative_residual: (residual_squared / rhs_squared).sqrt(),
        });
    }
    Ok(z.component_mul(&metric.map(f64::sqrt)))
}

/// The reaction `y = Y λ` within the span of a supplied basis (body wrench coordinates, at most 6), with λ the
/// least-squares solution of `(A H⁻¹ Y) λ = rhs`.
pub fn with_basis(
    rows: &[ConstraintRow],
    rhs: &[f64],
    basis: &[Vector6<f64>],
    metric: &Vector6<f64>,
    settings: &SolverSettings,
    consistency: Consistency,
) -> Result<Vector6<f64>, SolveFailure> {
    let n = basis.len().min(6);
    if n == 0 || rows.is_empty() {
        return Ok(Vector6::zeros());
    }
    let inverse_metric = metric.map(|h| 1.0 / h);
    let accelerations: [Vector6<f64>; 6] = std::array::from_fn(|k| {
        if k < n {
            basis[k].component_mul(&inverse_metric)
        } else {
            Vector6::zeros()
        }
    });
    // D_ik = a_i·H⁻¹Y_k; normal equations DᵀD λ = Dᵀ r'.
    let mut images = [[0.0; 6]; MAX_ROWS];
    for (image, row) in images.iter_mut().zip(rows) {
        *image = std::array::from_fn(|k| dot(&row.jacobian, &accelerations[k]));
    }
    let images = &images[..rows.len().min(MAX_ROWS)];
    let mut gram = Matrix6::identity();
    let mut projected = Vector6::zeros();
    for k in 0..n {
        for l in 0..n {
            gram[(k, l)] = images.iter().map(|d| d[k] * d[l]).sum();
        }
        projected[k] = images.iter().zip(rhs).map(|(d, r)| d[k] * r).sum();
    }
    let lambda = solve_gram(gram, projected, n, settings.rank_tolerance)?;
    let (mut residual_squared, mut rhs_squared) = (0.0, 0.0);
    for (d, r) in images.iter().zip(rhs) {
        let fitted: f64 = (0..n).map(|k| d[k] * lambda[k]).sum();
        residual_squared += (fitted - r).powi(2);
        rhs_squared += r * r;
    }
    if consistency.violated(residual_squared, rhs_squared, settings) {
        return Err(SolveFailure::Inconsistent {
            relative_residual: (residual_squared / rhs_squared).sqrt(),
        });
    }
    Ok(basis[..n]
        .iter()
        .zip(lambda.iter())
        .fold(Vector6::zeros(), |y, (b, l)| y + b * *l))
}

/// Eigenvalues and orthonormal eigenvectors (columns) of a symmetric 6×6 matrix, by cyclic Jacobi rotations
/// until the off-diagonal part is below round-off of the diagonal (at most `JACOBI_SWEEPS` sweeps; Jacobi
/// converges quadratically, 5–7 sweeps in practice). Jacobi also resolves small eigenvalues to high relative
/// accuracy, which the rank decision needs.
pub fn symmetric_eigen(matrix: Matrix6<f64>) -> (Vector6<f64>, Matrix6<f64>) {
    let mut a = matrix;
    let mut vectors = Matrix6::identity();
    for _ in 0..JACOBI_SWEEPS {
        let off: f64 = (0..6)
            .flat_map(|p| (p + 1..6).map(move |q| (p, q)))
            .map(|(p, q)| a[(p, q)].powi(2))
            .sum();
        let diagonal: f64 = (0..6).map(|i| a[(i, i)].powi(2)).sum();
        if off <= (f64::EPSILON * f64::EPSILON) * diagonal {
            break;
        }
        for p in 0..5 {
            for q in p + 1..6 {
                let apq = a[(p, q)];
                if apq == 0.0 {
                    continue;
                }
                // The rotation by angle φ with tan φ = t zeroing a_pq: cot 2φ = (a_qq − a_pp)/(2 a_pq), t the smaller
                // root of t² + 2t cot 2φ − 1 = 0.
                let theta = (a[(q, q)] - a[(p, p)]) / (2.0 * apq);
                // √(θ² + 1) without libm's (slow) hypot: θ² overflows only beyond 1e154, where √ ≈ |θ|.
                let root = if theta.abs() < 1e150 {
                    (theta * theta + 1.0).sqrt()
                } else {
                    theta.abs()
                };
                let t = theta.signum() / (theta.abs() + root);
                // |t| ≤ 1, so t² + 1 cannot overflow.
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..6 {
                    let (akp, akq) = (a[(k, p)], a[(k, q)]);
                    a[(k, p)] = c * akp - s * akq;
                    a[(k, q)] = s * akp + c * akq;
                }
                for k in 0..6 {
                    let (apk, aqk) = (a[(p, k)], a[(q, k)]);
                    a[(p, k)] = c * apk - s * aqk;
                    a[(q, k)] = s * apk + c * aqk;
                }
                for k in 0..6 {
                    let (vkp, vkq) = (vectors[(k, p)], vectors[(k, q)]);
                    vectors[(k, p)] = c * vkp - s * vkq;
                    vectors[(k, q)] = s * vkp + c * vkq;
                }
            }
        }
    }
    (a.diagonal(), vectors)
}

/// Sweeps after which [`symmetric_eigen`] stops even if not converged (it converges in well under 10).
const JACOBI_SWEEPS: usize = 30;

#[cfg(test)]
mod tests {
    use super::*;

    /// The hinge normal matrix on which nalgebra's SymmetricEigen returned a decomposition off by 8.5 (issue
    /// #1109), and a few pseudo-random symmetric matrices with spread spectra.
    #[test]
    fn jacobi_reconstructs_symmetric_matrices() {
        let mut matrices = Vec::new();
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..200 {
            let b = Matrix6::from_fn(|_, _| next());
            let scales = Vector6::from_fn(|i, _| 10f64.powi(3 - i as i32));
            matrices.push(b * Matrix6::from_diagonal(&scales) * b.transpose());
        }
        for matrix in matrices {
            let (values, vectors) = symmetric_eigen(matrix);
            let rebuilt = vectors * Matrix6::from_diagonal(&values) * vectors.transpose();
            assert!((rebuilt - matrix).norm() <= 1e-13 * matrix.norm(), "{matrix}");
            assert!((vectors.transpose() * vectors - Matrix6::identity()).norm() < 1e-14);
        }
    }
}
