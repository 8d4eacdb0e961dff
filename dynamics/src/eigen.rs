//! The symmetric eigendecomposition by cyclic Jacobi rotations: a body's principal axes from its inertia tensor
//! ([`crate::body`]), and the rank of a joint's rows (`mechanism::reduce`).

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

/// Sweeps after which [`symmetric_eigen`] stops even if not converged (it converges in well under 10).
const JACOBI_SWEEPS: usize = 30;

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
}
