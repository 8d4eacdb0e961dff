//! Decompositions by Jacobi rotations: the symmetric eigendecomposition (a body's principal axes from its inertia
//! tensor, [`crate::body`], and the rank of a joint's rows, `mechanism::reduce`) and the singular value decomposition
//! (the least-norm multipliers of rows that repeat each other, and the loads they balance among themselves); and, for
//! the symmetric Gram matrices of held contacts at every evaluation, the same least-norm solution by a pivoted
//! Cholesky factorisation at a fraction of the cost.
//!
//! Jacobi resolves small eigen- and singular values to high relative accuracy, which rank decisions need; nalgebra's
//! `SymmetricEigen` mis-pairs eigenvalues and eigenvectors for some matrices (nalgebra issue #1109, open) and its
//! `SVD` of some rank-deficient square matrices recomposes to a different matrix (issue #1172, open: a 4 × 4 Gram
//! matrix of a box's corners with friction came back 2e-2 off).

use nalgebra::{DMatrix, DVector};

/// Eigenvalues and orthonormal eigenvectors (columns, column-major in `matrix`'s place) of a symmetric `n × n`
/// matrix (column-major; `work` holds n² numbers), by cyclic Jacobi rotations until the off-diagonal part is below round-off of the
/// diagonal (at most [`JACOBI_SWEEPS`] sweeps; Jacobi converges quadratically, 5–8 sweeps in practice). Jacobi
/// resolves small eigenvalues to high relative accuracy, which the rank decision needs; nalgebra's
/// `SymmetricEigen` mis-pairs eigenvalues and eigenvectors for some matrices (nalgebra issue #1109, open).
pub(crate) fn symmetric_eigen(matrix: &mut [f64], values: &mut [f64], work: &mut [f64], n: usize) {
    let index = |row: usize, column: usize| column * n + row;
    let a = work;
    a.copy_from_slice(matrix);
    let vectors = matrix;
    vectors.fill(0.0);
    for i in 0..n {
        vectors[index(i, i)] = 1.0;
    }
    for _ in 0..JACOBI_SWEEPS {
        let mut off = 0.0;
        let mut diagonal = 0.0;
        for q in 0..n {
            for p in 0..n {
                let x = a[index(p, q)] * a[index(p, q)];
                if p == q {
                    diagonal += x;
                } else {
                    off += x;
                }
            }
        }
        if off <= (f64::EPSILON * f64::EPSILON) * diagonal {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[index(p, q)];
                if apq == 0.0 {
                    continue;
                }
                // The rotation by φ with tan φ = t zeroing a_pq: cot 2φ = (a_qq − a_pp)/(2 a_pq), t the smaller root
                // of t² + 2t cot 2φ − 1 = 0.
                let theta = (a[index(q, q)] - a[index(p, p)]) / (2.0 * apq);
                // √(θ² + 1) without libm's (slow) hypot: θ² overflows only beyond 1e154, where √ ≈ |θ|.
                let root = if theta.abs() < 1e150 {
                    (theta * theta + 1.0).sqrt()
                } else {
                    theta.abs()
                };
                let t = theta.signum() / (theta.abs() + root);
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..n {
                    let (arp, arq) = (a[index(r, p)], a[index(r, q)]);
                    a[index(r, p)] = c * arp - s * arq;
                    a[index(r, q)] = s * arp + c * arq;
                }
                for r in 0..n {
                    let (apr, aqr) = (a[index(p, r)], a[index(q, r)]);
                    a[index(p, r)] = c * apr - s * aqr;
                    a[index(q, r)] = s * apr + c * aqr;
                }
                for r in 0..n {
                    let (vrp, vrq) = (vectors[index(r, p)], vectors[index(r, q)]);
                    vectors[index(r, p)] = c * vrp - s * vrq;
                    vectors[index(r, q)] = s * vrp + c * vrq;
                }
            }
        }
    }
    for (i, value) in values.iter_mut().enumerate().take(n) {
        *value = a[index(i, i)];
    }
}

/// Sweeps after which [`symmetric_eigen`] and [`SingularValues::of`] stop even if not converged (they converge in
/// well under 10).
const JACOBI_SWEEPS: usize = 30;

/// The singular value decomposition `A = U Σ Vᵀ` of an m × n matrix by one-sided Jacobi rotations (Hestenes): plane
/// rotations V of A's columns until every two are orthogonal, so that `A V = U Σ` has columns `σ_j u_j`.
pub(crate) struct SingularValues {
    /// `A V`: column j is `σ_j u_j`.
    scaled_left: DMatrix<f64>,
    /// V (n × n, orthogonal): column j the right singular vector of `σ_j`.
    right: DMatrix<f64>,
    /// `σ_j`, in the order of the columns (not sorted).
    values: DVector<f64>,
}

impl SingularValues {
    /// The decomposition of `matrix`.
    pub(crate) fn of(matrix: &DMatrix<f64>) -> Self {
        let n = matrix.ncols();
        let mut a = matrix.clone();
        let mut v = DMatrix::identity(n, n);
        // Columns below round-off of the whole matrix are null: their pairs are never orthogonal to relative
        // precision (they are noise), so they are left as they are.
        let negligible = (f64::EPSILON * matrix.norm()).powi(2);
        for _ in 0..JACOBI_SWEEPS {
            let mut rotated = false;
            for p in 0..n {
                for q in p + 1..n {
                    let alpha = a.column(p).norm_squared();
                    let beta = a.column(q).norm_squared();
                    let gamma = a.column(p).dot(&a.column(q));
                    if gamma == 0.0
                        || alpha <= negligible
                        || beta <= negligible
                        || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt()
                    {
                        continue;
                    }
                    rotated = true;
                    // The rotation by φ making columns p and q orthogonal: cot 2φ = (β − α)/(2γ), t = tan φ the
                    // smaller root of t² + 2t cot 2φ − 1 = 0.
                    let zeta = (beta - alpha) / (2.0 * gamma);
                    let t = zeta.signum() / (zeta.abs() + (zeta * zeta + 1.0).sqrt());
                    let c = 1.0 / (t * t + 1.0).sqrt();
                    let s = c * t;
                    for m in [&mut a, &mut v] {
                        for r in 0..m.nrows() {
                            let (x, y) = (m[(r, p)], m[(r, q)]);
                            m[(r, p)] = c * x - s * y;
                            m[(r, q)] = s * x + c * y;
                        }
                    }
                }
            }
            if !rotated {
                break;
            }
        }
        let values = DVector::from_iterator(n, a.column_iter().map(|column| column.norm()));
        Self {
            scaled_left: a,
            right: v,
            values,
        }
    }

    /// The largest singular value.
    pub(crate) fn largest(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// The least-norm least-squares solution of `A x = b`, singular values at or below `threshold` taken as zero:
    /// `x = Σ v_j (σ_j u_j · b) / σ_j²` over the others.
    pub(crate) fn solve(&self, rhs: &DVector<f64>, threshold: f64) -> DVector<f64> {
        let mut x = DVector::zeros(self.right.nrows());
        for (j, &sigma) in self.values.iter().enumerate() {
            if sigma > threshold {
                x += self.right.column(j) * (self.scaled_left.column(j).dot(rhs) / (sigma * sigma));
            }
        }
        x
    }

    /// The right singular vectors of singular values at or below `threshold`: the loads `A` does not see.
    pub(crate) fn null_vectors(&self, threshold: f64) -> Vec<DVector<f64>> {
        (self.values.iter().enumerate())
            .filter(|&(_, &sigma)| sigma <= threshold)
            .map(|(j, _)| self.right.column(j).into_owned())
            .collect()
    }
}

/// The least-norm solution of `G x = b` for a symmetric positive semidefinite `G` (a Gram matrix), pivots at or
/// below `threshold` taken as zero: Cholesky with diagonal pivoting, `P G Pᵀ = L Lᵀ` with L (n × r) of rank r; with
/// `y = P b` and `z = L₁⁻¹ y₁` (L₁ its leading r × r triangle) the pivot equations are `Lᵀ x = z`, solved by
/// `x = L₁⁻ᵀ z` at full rank, else by their least-norm solution `L (LᵀL)⁻¹ z`, permuted back. O(n² r) with a
/// small constant, where Jacobi's SVD sweeps O(n³) several times: rows repeating others cost their count, not its
/// cube.
pub(crate) fn symmetric_least_norm(matrix: &DMatrix<f64>, rhs: &DVector<f64>, threshold: f64) -> DVector<f64> {
    let n = matrix.nrows();
    let mut a = matrix.clone();
    let mut order: Vec<usize> = (0..n).collect();
    let mut rank = 0;
    while rank < n {
        let (pivot, largest) = (rank..n)
            .map(|i| (i, a[(i, i)]))
            .fold((rank, f64::NEG_INFINITY), |best, x| if x.1 > best.1 { x } else { best });
        if largest <= threshold {
            break;
        }
        a.swap_rows(rank, pivot);
        a.swap_columns(rank, pivot);
        order.swap(rank, pivot);
        let root = largest.sqrt();
        a[(rank, rank)] = root;
        for i in rank + 1..n {
            a[(i, rank)] /= root;
        }
        // The whole trailing block (both triangles): a later pivot's swap brings upper entries into the lower.
        for j in rank + 1..n {
            for i in rank + 1..n {
                a[(i, j)] -= a[(i, rank)] * a[(j, rank)];
            }
        }
        for j in rank + 1..n {
            a[(rank, j)] = a[(j, rank)];
        }
        rank += 1;
    }
    let l1 = a.view((0, 0), (rank, rank)).lower_triangle();
    let y = DVector::from_iterator(rank, order[..rank].iter().map(|&i| rhs[i]));
    let z = l1.solve_lower_triangular(&y).unwrap_or_else(|| DVector::zeros(rank));
    let basic = if rank == 0 {
        DVector::zeros(n)
    } else if rank == n {
        l1.transpose()
            .solve_upper_triangular(&z)
            .unwrap_or_else(|| DVector::zeros(n))
    } else {
        // The first r equations are `L₁ Lᵀ x = y₁`, that is `Lᵀ x = z`; their least-norm solution lies in L's range,
        // `x = L (LᵀL)⁻¹ z`: O(n r²), where the null space's normal equations cost O((n − r)³), which many repeated
        // rows (n ≫ r) make the whole cost. Column j of L is `a[j.., j]`.
        let mut normal = DMatrix::zeros(rank, rank);
        for i in 0..rank {
            for j in 0..=i {
                let product: f64 = (i..n).map(|k| a[(k, i)] * a[(k, j)]).sum();
                (normal[(i, j)], normal[(j, i)]) = (product, product);
            }
        }
        let w = normal
            .cholesky()
            .map_or_else(|| DVector::zeros(rank), |factors| factors.solve(&z));
        DVector::from_fn(n, |k, _| (0..rank.min(k + 1)).map(|j| a[(k, j)] * w[j]).sum())
    };
    let mut x = DVector::zeros(n);
    for (k, &i) in order.iter().enumerate() {
        x[i] = basic[k];
    }
    x
}

/// The least-norm solution of `G x = b` for a Gram matrix `G` (pivots or singular values at or below `threshold`
/// taken as zero), solved block by block: rows that move no body in common (a stack of boxes and a ball rolling beside
/// it) leave exact zeros between them in G, and each group of rows that couple only among themselves is solved alone,
/// by [`symmetric_least_norm`], or by [`SingularValues`] where `by_svd` says so (a block whose G is not symmetric,
/// sliding friction tilting a row's force from its direction; or where the rank is to be decided by singular values). The same solution as the whole at once, at the cost
/// of the blocks: a sliding ball does not turn a resting stack's symmetric solve into an SVD.
pub(crate) fn least_norm_by_blocks(
    gram: &DMatrix<f64>,
    rhs: &DVector<f64>,
    threshold: f64,
    by_svd: impl Fn(&[usize]) -> bool,
) -> DVector<f64> {
    let mut x = DVector::zeros(gram.nrows());
    for block in coupled_blocks(gram) {
        let sub = gram.select_rows(&block).select_columns(&block);
        let sub_rhs = rhs.select_rows(&block);
        let solved = if by_svd(&block) {
            SingularValues::of(&sub).solve(&sub_rhs, threshold)
        } else {
            symmetric_least_norm(&sub, &sub_rhs, threshold)
        };
        for (&k, value) in block.iter().zip(solved.iter()) {
            x[k] = *value;
        }
    }
    x
}

/// The rows of `gram` in groups that couple only among themselves (`G[i][k]` or `G[k][i]` not zero joins rows i and
/// k), each in increasing order, the groups in the order of their first rows.
fn coupled_blocks(gram: &DMatrix<f64>) -> Vec<Vec<usize>> {
    fn root(group: &mut [usize], mut k: usize) -> usize {
        while group[k] != k {
            group[k] = group[group[k]];
            k = group[k];
        }
        k
    }
    let n = gram.nrows();
    let mut group: Vec<usize> = (0..n).collect();
    for i in 0..n {
        for k in i + 1..n {
            if gram[(i, k)] != 0.0 || gram[(k, i)] != 0.0 {
                let (a, b) = (root(&mut group, i), root(&mut group, k));
                group[a.max(b)] = a.min(b);
            }
        }
    }
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut block_of = vec![usize::MAX; n];
    for k in 0..n {
        let top = root(&mut group, k);
        if block_of[top] == usize::MAX {
            block_of[top] = blocks.len();
            blocks.push(Vec::new());
        }
        blocks[block_of[top]].push(k);
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Jacobi reconstructs pseudo-random symmetric matrices with spread spectra.
    #[test]
    fn jacobi_reconstructs_symmetric_matrices() {
        let mut uniform = crate::test_random::uniform(0x2545_f491_4f6c_dd1d_u64);
        let mut next = || uniform() - 0.5;
        for n in [1, 2, 5, 6, 9] {
            for _ in 0..50 {
                let b: Vec<f64> = (0..n * n).map(|_| next()).collect();
                let mut matrix = vec![0.0; n * n];
                for i in 0..n {
                    for j in 0..n {
                        matrix[j * n + i] = (0..n)
                            .map(|k| b[k * n + i] * b[k * n + j] * 10f64.powi(3 - k as i32))
                            .sum();
                    }
                }
                let original = matrix.clone();
                let mut values = vec![0.0; n];
                let mut work = vec![0.0; n * n];
                symmetric_eigen(&mut matrix, &mut values, &mut work, n);
                let norm: f64 = original.iter().map(|x| x * x).sum::<f64>().sqrt();
                for i in 0..n {
                    for j in 0..n {
                        let rebuilt: f64 = (0..n).map(|e| matrix[e * n + i] * values[e] * matrix[e * n + j]).sum();
                        assert!((rebuilt - original[j * n + i]).abs() <= 1e-13 * norm, "n = {n}");
                        let orthogonal: f64 = (0..n).map(|r| matrix[i * n + r] * matrix[j * n + r]).sum();
                        assert!((orthogonal - if i == j { 1.0 } else { 0.0 }).abs() < 1e-13);
                    }
                }
            }
        }
    }

    /// The pivoted Cholesky's least-norm solution of rank-deficient symmetric Gram matrices equals Jacobi's SVD's.
    #[test]
    fn pivoted_cholesky_solves_gram_matrices_least_norm() {
        let mut uniform = crate::test_random::uniform(0x1234_5678_9abc_def1_u64);
        for (n, rank) in [(1, 1), (4, 3), (4, 4), (6, 2), (12, 6), (9, 9), (5, 0)] {
            let rows = DMatrix::from_fn(rank, n, |_, _| uniform() - 0.5);
            let gram = rows.transpose() * &rows;
            let rhs = &gram * DVector::from_fn(n, |_, _| uniform() - 0.5);
            let threshold = 1e-12 * gram.diagonal().amax().max(f64::MIN_POSITIVE);
            let cholesky = symmetric_least_norm(&gram, &rhs, threshold);
            let jacobi = SingularValues::of(&gram).solve(&rhs, threshold);
            assert!((&gram * &cholesky - &rhs).amax() < 1e-13, "{n} × {n} of rank {rank}");
            assert!(
                (&cholesky - &jacobi).amax() < 1e-11 * jacobi.amax().max(1.0),
                "{n} × {n} of rank {rank}"
            );
        }
    }

    /// One-sided Jacobi recomposes pseudo-random matrices, rank-deficient ones included, and its least-norm solution
    /// solves consistent systems to round-off, where nalgebra's SVD of the same 4 × 4 matrix is 2e-2 off.
    #[test]
    fn jacobi_singular_values_solve_rank_deficient_systems() {
        let gram = DMatrix::from_row_slice(
            4,
            4,
            &[
                4.299999999999998,
                1.299999999999999,
                -1.7000000000000015,
                1.2999999999999967,
                1.300000000000002,
                4.300000000000001,
                1.3000000000000023,
                -1.6999999999999966,
                -2.299999999999997,
                0.7000000000000011,
                3.700000000000001,
                0.7000000000000028,
                0.6999999999999981,
                -2.3000000000000007,
                0.6999999999999975,
                3.6999999999999957,
            ],
        );
        let rhs = DVector::from_element(4, 9.371850958322199);
        let svd = SingularValues::of(&gram);
        let x = svd.solve(&rhs, 1e-12 * svd.largest());
        assert!((&gram * &x - &rhs).amax() < 1e-13, "{x}");
        assert_eq!(svd.null_vectors(1e-12 * svd.largest()).len(), 1);
        let mut uniform = crate::test_random::uniform(0x9e37_79b9_7f4a_7c15_u64);
        for (m, n, rank) in [(3, 3, 3), (4, 4, 3), (6, 4, 2), (3, 7, 3), (9, 9, 5)] {
            let left = DMatrix::from_fn(m, rank, |_, _| uniform() - 0.5);
            let right = DMatrix::from_fn(rank, n, |_, _| uniform() - 0.5);
            let matrix = left * right;
            let svd = SingularValues::of(&matrix);
            let recomposed = &svd.scaled_left * svd.right.transpose();
            assert!((recomposed - &matrix).amax() < 1e-14, "{m} × {n}");
            let threshold = 1e-12 * svd.largest();
            assert_eq!(svd.null_vectors(threshold).len(), n - rank, "{m} × {n} of rank {rank}");
            let consistent = &matrix * DVector::from_fn(n, |_, _| uniform() - 0.5);
            let x = svd.solve(&consistent, threshold);
            assert!((&matrix * &x - &consistent).amax() < 1e-13, "{m} × {n}");
            // Least norm: no component along the null space.
            for null in svd.null_vectors(threshold) {
                assert!(null.dot(&x).abs() < 1e-12);
            }
        }
    }
}
