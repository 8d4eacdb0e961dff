//! A joint's rows reduced to exactly its rank of independent rows (docs/mechanisms.md §M3).
//!
//! A constraint emits one row per condition it writes: a pinned CGA line has 10 coefficients and constrains 4
//! degrees of freedom, a PGA point has 4 (one identically zero) for 3. The system solve needs each joint's
//! reaction space as `r` independent rows, so that `K` is positive definite on trees. Rows `a_i` (covectors on
//! the relative velocity, m of them) with right-hand sides `β_i` become `r` rows `q_k` and values `z_k`:
//!
//! * when the nonzero rows already number the rank (virtual power, a PGA point once its zero row is dropped),
//!   they are used as they are;
//! * otherwise by the kinetic-metric solution truncated to the known rank (theory §7.1 method 1): with `g` the
//!   held body's inverse inertia (diagonal) and `A' = A diag(√g)`, the eigenvectors `v_k` of `A'ᵀA'` with the
//!   r largest eigenvalues `σ_k²` span the kept row space, `q_k = v_k ⊙ √(1/g)` and
//!   `z_k = Σᵢ (A'ᵢ·v_k) βᵢ / σ_k²`. The (r+1)-th singular value, the spurious one of an incidence pin off its
//!   manifold (theory §12, E8), is dropped. For a body held by the world this is exactly theory §7.1's
//!   `y = H^{1/2}(A H^{-1/2})⁺_r β` (then `q G qᵀ = I`); for two bodies the held body's metric chooses the
//!   truncation, which matters only off the manifold;
//! * with a supplied reaction basis (§7.1 method 2), `q` is the basis, orthonormalised, and `z` solves
//!   `C z = β` in least squares with `C = A qᵀ`; rows the basis cannot express leave a residual, reported as an
//!   inconsistency.

use crate::constraints::{ConstraintRow, MAX_ROWS};
use crate::eigen::symmetric_eigen;
use crate::mechanism::solve::{dot6, exceeds};

/// How many right-hand sides a reduction carries: the acceleration condition, the position residual and the
/// velocity residual (both for the projection).
pub(crate) const RIGHT_HAND_SIDES: usize = 3;

/// The reduced rows of one joint and its reduced right-hand sides.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Reduced {
    pub rank: usize,
    pub rows: [[f64; 6]; 6],
    pub values: [[f64; 6]; RIGHT_HAND_SIDES],
    /// `|C z − β|²` and `|β|²` of the first right-hand side (the acceleration condition).
    pub residual_squared: f64,
    pub rhs_squared: f64,
    /// Whether the rows are the constraint's own (nonzero) rows, not a basis the reduction chose: then rows
    /// evaluated at nearby states are nearby, and a factorisation of K from one serves the other.
    pub direct: bool,
}

impl Default for Reduced {
    fn default() -> Self {
        Reduced {
            rank: 0,
            rows: [[0.0; 6]; 6],
            values: [[0.0; 6]; RIGHT_HAND_SIDES],
            residual_squared: 0.0,
            rhs_squared: 0.0,
            direct: false,
        }
    }
}

/// Why a joint's rows cannot be reduced to its rank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RankDeficiency {
    pub singular_value: f64,
    pub largest: f64,
}

/// Reduces `rows` with right-hand sides `rhs[i][s]` (per raw row i) to `rank` rows in the metric `inverse_metric`
/// (the held body's `H⁻¹` diagonal), or to the span of `basis` (covectors, at most 6) if given; `tolerance` is
/// the relative singular value below which rows count as dependent.
#[inline]
pub(crate) fn reduce(
    rows: &[ConstraintRow],
    rhs: &[[f64; RIGHT_HAND_SIDES]],
    rank: usize,
    inverse_metric: &[f64; 6],
    basis: Option<&[[f64; 6]]>,
    tolerance: f64,
    out: &mut Reduced,
) -> Result<(), RankDeficiency> {
    out.rank = rank;
    out.residual_squared = 0.0;
    out.rhs_squared = 0.0;
    out.direct = false;
    // The rows that constrain anything (a PGA point's e123 row is identically zero).
    let mut nonzero = [0usize; MAX_ROWS];
    let mut count = 0;
    for (i, row) in rows.iter().enumerate() {
        if row.jacobian.iter().any(|&a| a != 0.0) {
            nonzero[count] = i;
            count += 1;
        }
    }
    let nonzero = &nonzero[..count];
    if basis.is_none() && count == rank {
        for (k, &i) in nonzero.iter().enumerate() {
            out.rows[k] = rows[i].jacobian;
            for (values, value) in out.values.iter_mut().zip(rhs[i]) {
                values[k] = value;
            }
        }
        out.rhs_squared = nonzero.iter().map(|&i| rhs[i][0] * rhs[i][0]).sum();
        out.direct = true;
        return Ok(());
    }

    let Some(basis) = basis else {
        return truncated_kinetic_metric(rows, nonzero, rhs, rank, inverse_metric, tolerance, out);
    };

    // The supplied basis, orthonormalised (Gram–Schmidt).
    out.rank = basis.len();
    let scale = basis.iter().map(|b| dot6(b, b)).fold(0.0, f64::max);
    for (k, b) in basis.iter().enumerate() {
        let mut w = *b;
        for q in &out.rows[..k] {
            let c = dot6(&w, q);
            w.iter_mut().zip(q).for_each(|(x, y)| *x -= c * y);
        }
        let norm = dot6(&w, &w);
        if !exceeds(norm, tolerance * tolerance * scale) {
            return Err(RankDeficiency {
                singular_value: norm.max(0.0).sqrt(),
                largest: scale.sqrt(),
            });
        }
        let inverse = 1.0 / norm.sqrt();
        out.rows[k] = w.map(|x| x * inverse);
    }
    let r = out.rank;
    let largest = scale;

    // C = A qᵀ over all rows, the normal matrix CᵀC (r × r) and its Cholesky factor.
    let mut coefficients = [[0.0; 6]; MAX_ROWS];
    for (c, row) in coefficients.iter_mut().zip(rows) {
        for (k, q) in out.rows[..r].iter().enumerate() {
            c[k] = dot6(&row.jacobian, q);
        }
    }
    let coefficients = &coefficients[..rows.len()];
    let mut normal = [[0.0; 6]; 6];
    for i in 0..r {
        for j in 0..=i {
            normal[i][j] = coefficients.iter().map(|c| c[i] * c[j]).sum();
        }
    }
    let mut cholesky = [[0.0; 6]; 6];
    for j in 0..r {
        let pivot = normal[j][j] - (0..j).map(|k| cholesky[j][k] * cholesky[j][k]).sum::<f64>();
        if !exceeds(pivot, tolerance * tolerance * largest) {
            return Err(RankDeficiency {
                singular_value: pivot.max(0.0).sqrt(),
                largest: largest.sqrt(),
            });
        }
        cholesky[j][j] = pivot.sqrt();
        for i in j + 1..r {
            cholesky[i][j] =
                (normal[i][j] - (0..j).map(|k| cholesky[i][k] * cholesky[j][k]).sum::<f64>()) / cholesky[j][j];
        }
    }
    for (side, values) in out.values.iter_mut().enumerate() {
        // z = (CᵀC)⁻¹ Cᵀ β by the two triangular solves.
        let mut z = [0.0; 6];
        for (k, zk) in z.iter_mut().enumerate().take(r) {
            *zk = coefficients.iter().zip(rhs).map(|(c, b)| c[k] * b[side]).sum();
        }
        for i in 0..r {
            z[i] = (z[i] - (0..i).map(|k| cholesky[i][k] * z[k]).sum::<f64>()) / cholesky[i][i];
        }
        for i in (0..r).rev() {
            z[i] = (z[i] - (i + 1..r).map(|k| cholesky[k][i] * z[k]).sum::<f64>()) / cholesky[i][i];
        }
        *values = z;
    }
    for (c, b) in coefficients.iter().zip(rhs) {
        let fitted: f64 = (0..r).map(|k| c[k] * out.values[0][k]).sum();
        out.residual_squared += (fitted - b[0]).powi(2);
        out.rhs_squared += b[0] * b[0];
    }
    Ok(())
}

/// The kinetic-metric truncated reduction (see the module docs).
fn truncated_kinetic_metric(
    rows: &[ConstraintRow],
    nonzero: &[usize],
    rhs: &[[f64; RIGHT_HAND_SIDES]],
    rank: usize,
    inverse_metric: &[f64; 6],
    tolerance: f64,
    out: &mut Reduced,
) -> Result<(), RankDeficiency> {
    let scale = inverse_metric.map(f64::sqrt);
    // A'ᵀA' accumulated on the upper triangle (the products are symmetric, so the mirror is exact), and A'ᵀβ.
    let mut normal = [0.0; 36];
    let mut projected = [[0.0; 6]; RIGHT_HAND_SIDES];
    for &i in nonzero {
        let g: [f64; 6] = std::array::from_fn(|c| rows[i].jacobian[c] * scale[c]);
        for a in 0..6 {
            for b in a..6 {
                normal[b * 6 + a] += g[a] * g[b];
            }
            for (p, value) in projected.iter_mut().zip(rhs[i]) {
                p[a] += g[a] * value;
            }
        }
    }
    for a in 0..6 {
        for b in 0..a {
            normal[b * 6 + a] = normal[a * 6 + b];
        }
    }
    let mut eigenvalues = [0.0; 6];
    let mut work = [0.0; 36];
    symmetric_eigen(&mut normal, &mut eigenvalues, &mut work, 6);
    // Indices by decreasing eigenvalue (a stable insertion sort on six entries).
    let mut order: [usize; 6] = std::array::from_fn(|i| i);
    for end in 1..6 {
        let mut k = end;
        while k > 0 && eigenvalues[order[k]] > eigenvalues[order[k - 1]] {
            order.swap(k, k - 1);
            k -= 1;
        }
    }
    let largest = eigenvalues[order[0]];
    let kept = eigenvalues[order[rank.clamp(1, 6) - 1]];
    if rank > 6 || !(exceeds(largest, 0.0) && exceeds(kept, tolerance * tolerance * largest)) {
        return Err(RankDeficiency {
            singular_value: kept.max(0.0).sqrt(),
            largest: largest.max(0.0).sqrt(),
        });
    }
    out.rank = rank;
    let mut explained = 0.0;
    for (k, &e) in order[..rank].iter().enumerate() {
        let v: [f64; 6] = std::array::from_fn(|c| normal[e * 6 + c]);
        out.rows[k] = std::array::from_fn(|c| v[c] / scale[c]);
        for (values, p) in out.values.iter_mut().zip(&projected) {
            values[k] = dot6(&v, p) / eigenvalues[e];
        }
        explained += dot6(&v, &projected[0]).powi(2) / eigenvalues[e];
    }
    // |A' z − β|² = |β|² − Σ_kept (v·A'ᵀβ)²/σ²: what the kept directions do not explain (rows with a zero
    // Jacobian included: their β is unexplained by construction).
    out.rhs_squared = rhs.iter().map(|b| b[0] * b[0]).sum();
    out.residual_squared = (out.rhs_squared - explained).max(0.0);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(jacobian: [f64; 6]) -> ConstraintRow {
        ConstraintRow {
            jacobian,
            ..ConstraintRow::default()
        }
    }

    /// Duplicated and combined rows reduce to the rank, and the reduced system has the same solutions.
    #[test]
    fn redundant_rows_reduce_to_the_rank() {
        let a = [1.0, 2.0, 0.0, 0.5, 0.0, -1.0];
        let b = [0.0, 1.0, 3.0, 0.0, 1.0, 0.0];
        let rows = [row(a), row(b), row(a.map(|x| 2.0 * x)), row([0.0; 6])];
        // A solution x of a·x = 1, b·x = −2; the rows' values follow from it.
        let x = [0.3, 0.1, -0.8, 0.0, 0.2, -0.4];
        let rhs: Vec<[f64; RIGHT_HAND_SIDES]> = rows.iter().map(|r| [dot6(&r.jacobian, &x), 0.0, 0.0]).collect();
        let mut reduced = Reduced::default();
        reduce(
            &rows,
            &rhs,
            2,
            &[1.0, 2.0, 0.5, 1.0, 1.0, 3.0],
            None,
            1e-6,
            &mut reduced,
        )
        .unwrap();
        assert_eq!(reduced.rank, 2);
        for k in 0..2 {
            assert!((dot6(&reduced.rows[k], &x) - reduced.values[0][k]).abs() < 1e-14);
        }
        assert!(reduced.residual_squared < 1e-28);
        // Declaring rank 3 for these rows (two independent ones) fails. (With exactly three nonzero rows the rows
        // are taken as they are, and the system solve's pivots catch a dependence.)
        let sum: [f64; 6] = std::array::from_fn(|c| a[c] + b[c]);
        let dependent = [row(a), row(b), row(a.map(|x| 2.0 * x)), row(sum)];
        let rhs: Vec<[f64; RIGHT_HAND_SIDES]> = dependent.iter().map(|r| [dot6(&r.jacobian, &x), 0.0, 0.0]).collect();
        assert!(reduce(&dependent, &rhs, 3, &[1.0; 6], None, 1e-6, &mut reduced).is_err());
    }
}
