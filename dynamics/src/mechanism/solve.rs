//! The joint-space solve `K λ = rhs`, `K = J G Jᵀ` (docs/mechanisms.md §M4).
//!
//! Every joint contributes `r` independent rows (its rank); body i contributes `G_i = H_i⁻¹`, the inverse of
//! its (diagonal) inertia in its own frame. `K` couples two joints only through a body they share, so it is
//! assembled body by body: body v adds `J_{j,v} G_v J_{k,v}ᵀ` for every pair of joints j, k at v.
//!
//! * **Tree joints** (a spanning forest of the mechanism, [`Topology`]) are factored `K_TT = L D Lᵀ` front by
//!   front, from the leaves up: a front is dense over the joints at one vertex, and eliminating its children
//!   joints leaves a Schur complement on its parent joint for the parent's front. For a tree `K_TT` is positive
//!   definite (a leaf body's joint is the only one that acts on it, and so on up), so a vanishing pivot means a
//!   joint whose own rows are dependent: an error naming it.
//! * **Loop joints** enter through their Schur complement `S = K_LL − K_LT K_TT⁻¹ K_TL` (`k × k` for k loop
//!   rows; O(N·k) to form). A closed loop's rows may be redundant — a planar four-bar's 20 hinge rows have
//!   rank 17 — so S is singular: it is scaled by the loop rows' own size (`K_LL`'s diagonal) and factored
//!   `L D Lᵀ` with diagonal pivoting (rank-revealing for a positive semi-definite matrix), stopping at pivots below
//!   [`SolverSettings::rank_tolerance`]² of the largest diagonal; the redundant rows' multipliers are zero. The
//!   multipliers are then not unique, but the reactions `Jᵀλ` are. A right-hand side outside the kept range (the
//!   joints demand contradictory accelerations) is an error naming the loop's joints.

use crate::mechanism::topology::{Front, Place, Side, Topology};

/// Thresholds of the reaction solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverSettings {
    /// A joint's rows (or a tree pivot) are rank deficient, and loop rows redundant, when their singular value
    /// is below this fraction of the largest (pivots and eigenvalues scale like squared singular values, so
    /// they are compared with its square). Pivots and eigenvalues of normal matrices resolve singular value
    /// ratios down to ~1e-7, hence 1e-6.
    pub rank_tolerance: f64,
    /// The acceleration conditions are inconsistent when the solve leaves a residual above this fraction of the
    /// right-hand side (and above round-off, [`ROUND_OFF`]). Off the manifold, incidence constraints are
    /// inconsistent by construction, by about the drift over the object's size (0.1 relative for a rod end
    /// 1 cm off its circle of radius 0.5 m, measured), which the fixed-rank solve is designed to ride out; a
    /// contradiction — a reaction basis that cannot hold the body, two joints pulling one point to two places —
    /// leaves a residual of order 1.
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

/// Whether `value` exceeds `threshold`; false for NaN, so a non-finite pivot or norm counts as vanishing.
#[inline]
pub(crate) fn exceeds(value: f64, threshold: f64) -> bool {
    value > threshold
}

/// Relative size of round-off in a right-hand side summed from terms of a given size: residuals below this
/// fraction of it are noise, not conditions to satisfy.
pub const ROUND_OFF: f64 = 1e-10;

/// Whether a solve checks that its solution satisfies the conditions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Consistency {
    /// Check, ignoring residuals below [`ROUND_OFF`] × `scale` (the size of the terms summed into the
    /// right-hand sides).
    Check { scale: f64 },
    /// Do not check: a least-squares step (the projection's Gauss–Newton step) is fine with a residual.
    Skip,
}

impl Consistency {
    pub fn violated(self, residual_squared: f64, rhs_squared: f64, settings: &SolverSettings) -> bool {
        match self {
            Consistency::Check { scale } => {
                residual_squared > settings.consistency_tolerance.powi(2) * rhs_squared
                    && residual_squared > (ROUND_OFF * scale).powi(2)
            }
            Consistency::Skip => false,
        }
    }
}

/// Why the system could not be factored or solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SolveFailure {
    /// A tree pivot vanished: tree joint `joint`'s rows are dependent (its declared rank is too high here).
    TreeRank {
        joint: usize,
        singular_value: f64,
        largest: f64,
    },
    /// The loop conditions contradict each other: `joint` is the loop joint with the largest residual.
    Inconsistent { joint: usize, relative_residual: f64 },
}

/// The assembled and factored system, reused across evaluations (no allocation after the first).
#[derive(Clone, Debug, Default)]
pub(crate) struct SystemMatrix {
    /// The fronts' dense matrices (row-major, lower triangle): the assembled K entries, then the factors — L
    /// below the diagonal of the eliminated columns, D on it.
    fronts: Vec<f64>,
    /// `K_TL`, tree rows × loop columns, column-major.
    tree_loop: Vec<f64>,
    /// `X = K_TT⁻¹ K_TL`, same layout.
    coupling: Vec<f64>,
    /// `K_LL` (column-major, full), then the pivoted `L D Lᵀ` factors of the scaled Schur complement: L below the
    /// diagonal of the first `loop_rank` columns, D on it, in pivot order.
    loops: Vec<f64>,
    /// The scaling `1/√(K_LL)_ii` of each loop row.
    scaling: Vec<f64>,
    /// The loop rows in pivot order, and how many were kept (the rest are redundant).
    permutation: Vec<usize>,
    loop_rank: usize,
    /// Scratch of the factorisation of fronts too large for the specialised code.
    column: Vec<f64>,
    loop_scratch: Vec<f64>,
}

/// Where the products of two tree joints' rows at one body go in that body's front: joint rows at local
/// offsets `i` (first) and `j` (second) of a `size × size` lower triangle; `same` for a joint with itself.
struct Block {
    size: usize,
    i: usize,
    j: usize,
    same: bool,
}

impl Block {
    /// Adds `a_α · b_β` for every pair of rows to the front's lower triangle (inlined, so that rows of
    /// constant count unroll).
    #[inline(always)]
    fn add(&self, front: &mut [f64], first: &[[f64; 6]], second: &[[f64; 6]]) {
        let Block { size, i, j, same } = *self;
        if same {
            for (alpha, a) in first.iter().enumerate() {
                let at = (i + alpha) * size + i;
                for (beta, b) in second[..=alpha].iter().enumerate() {
                    front[at + beta] += dot6(a, b);
                }
            }
        } else if i > j {
            for (alpha, a) in first.iter().enumerate() {
                let at = (i + alpha) * size + j;
                for (beta, b) in second.iter().enumerate() {
                    front[at + beta] += dot6(a, b);
                }
            }
        } else {
            for (beta, b) in second.iter().enumerate() {
                let at = (j + beta) * size + i;
                for (alpha, a) in first.iter().enumerate() {
                    front[at + alpha] += dot6(a, b);
                }
            }
        }
    }
}

/// `add(α, β, a_α · b_β)` for every pair of rows.
#[inline]
fn for_each_product(first: &[[f64; 6]], second: &[[f64; 6]], mut add: impl FnMut(usize, usize, f64)) {
    for (alpha, a) in first.iter().enumerate() {
        for (beta, b) in second.iter().enumerate() {
            add(alpha, beta, dot6(a, b));
        }
    }
}

/// `a · b` over six coordinates.
#[inline]
pub(crate) fn dot6(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    // Summed pairwise: three dependent additions instead of five (these sums are latency-bound).
    (a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3]) + (a[4] * b[4] + a[5] * b[5])
}

impl SystemMatrix {
    /// Sizes the buffers for `topology`.
    ///
    /// Made once per [`crate::mechanism::MechanismWorkspace`] (this type is internal); its solve gives the
    /// reactions [`crate::Mechanism::reactions`] reports. A chain of two rods (1 kg above 2 kg) hanging at rest: the
    /// shoulder carries both weights, the elbow the lower rod's.
    ///
    /// ```
    /// use dynamics::constraints::VirtualPower;
    /// use dynamics::{Algebra, Body, Force, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let (light, heavy) = (Body::rod(1.0, 1.0, 1e-3)?, Body::rod(2.0, 1.0, 1e-3)?);
    /// let (top, bottom) = (Vector3::new(0.0, 0.0, 0.5), Vector3::new(0.0, 0.0, -0.5)); // body points, m
    /// let mut chain = Mechanism::<Pga>::new();
    /// let (upper, lower) = (chain.add_body("upper", light)?, chain.add_body("lower", heavy)?);
    /// chain.add_force(upper, Force::gravity())?;
    /// chain.add_force(lower, Force::gravity())?;
    /// chain.add_joint(upper, Reference::World, VirtualPower::ball_joint("shoulder", top, Vector3::zeros()))?;
    /// chain.add_joint(lower, upper, VirtualPower::ball_joint("elbow", top, bottom))?;
    /// let still = UnitQuaternion::identity();
    /// let states = [
    ///     State::new(&light, Vector3::z() * -0.5, &still, Vector3::zeros(), Vector3::zeros()),
    ///     State::new(&heavy, Vector3::z() * -1.5, &still, Vector3::zeros(), Vector3::zeros()),
    /// ];
    /// let reactions = chain.reactions(0.0, &states)?;
    /// let force = |k: usize| Pga::screw_coordinates(reactions[k]).l;
    /// assert!((force(0) - Vector3::z() * (3.0 * 9.81)).norm() < 1e-12); // N
    /// assert!((force(1) - Vector3::z() * (2.0 * 9.81)).norm() < 1e-12); // N
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(topology: &Topology) -> Self {
        let (n, k) = (topology.tree_size, topology.loop_size);
        SystemMatrix {
            fronts: vec![0.0; topology.storage],
            tree_loop: vec![0.0; n * k],
            coupling: vec![0.0; n * k],
            loops: vec![0.0; k * k],
            scaling: vec![0.0; k],
            permutation: (0..k).collect(),
            loop_rank: 0,
            column: Vec::new(),
            loop_scratch: vec![0.0; k],
        }
    }

    /// Assembles `K = J G Jᵀ` body by body: `rows(joint, side)` are a joint's rows as seen by one of its bodies
    /// (covectors on that body's velocity coordinates `(ω; v)`), `inverse_metric[v]` the diagonal of `G_v`.
    /// Front entries go to the lower triangle only: the factorisation reads nothing else.
    pub fn assemble<'r>(
        &mut self,
        topology: &Topology,
        inverse_metric: &[[f64; 6]],
        rows: impl Fn(usize, Side) -> &'r [[f64; 6]],
    ) {
        self.fronts.fill(0.0);
        self.tree_loop.fill(0.0);
        self.loops.fill(0.0);
        let (n, k) = (topology.tree_size, topology.loop_size);
        for (v, incidences) in topology.incidences.iter().enumerate() {
            let g = &inverse_metric[v];
            for (p, first) in incidences.iter().enumerate() {
                // G-scaled rows of the first joint, once for all its partners (plain loops: this is the hot path
                // of every evaluation, and iterator adapters here cost more than the products).
                let first_rows = rows(first.joint, first.side);
                let mut scaled_rows = [[0.0; 6]; 6];
                for (scaled, a) in scaled_rows.iter_mut().zip(first_rows) {
                    for c in 0..6 {
                        scaled[c] = a[c] * g[c];
                    }
                }
                let scaled = &scaled_rows[..first_rows.len()];
                for second in &incidences[p..] {
                    let second_rows = rows(second.joint, second.side);
                    // A joint attaches two different bodies, so at one body the same incidence is the same joint:
                    // its block is symmetric; a pair of joints fills two mirrored blocks.
                    let same = first.joint == second.joint;
                    match (first.place, second.place) {
                        (
                            Place::Front {
                                storage,
                                size,
                                local: i,
                                ..
                            },
                            Place::Front { local: j, .. },
                        ) => {
                            let front = &mut self.fronts[storage..storage + size * size];
                            let block = Block { size, i, j, same };
                            // Equal ranks (every joint of a chain of one kind) get loops of constant length.
                            match (scaled.len(), second_rows.len()) {
                                (3, 3) => block.add(front, &scaled[..3], &second_rows[..3]),
                                (5, 5) => block.add(front, &scaled[..5], &second_rows[..5]),
                                (6, 6) => block.add(front, &scaled[..6], &second_rows[..6]),
                                _ => block.add(front, scaled, second_rows),
                            }
                        }
                        (Place::Front { global, .. }, Place::Loop { offset }) => {
                            for_each_product(scaled, second_rows, |alpha, beta, value| {
                                self.tree_loop[(offset + beta) * n + global + alpha] += value
                            });
                        }
                        (Place::Loop { offset }, Place::Front { global, .. }) => {
                            for_each_product(scaled, second_rows, |alpha, beta, value| {
                                self.tree_loop[(offset + alpha) * n + global + beta] += value
                            });
                        }
                        (Place::Loop { offset: i }, Place::Loop { offset: j }) => {
                            for_each_product(scaled, second_rows, |alpha, beta, value| {
                                let (r, c) = (i + alpha, j + beta);
                                self.loops[c * k + r] += value;
                                if !same {
                                    self.loops[r * k + c] += value;
                                }
                            });
                        }
                    }
                }
            }
        }
    }

    /// Factors the tree part front by front and, if there are loop joints, their scaled Schur complement by a
    /// pivoted `L D Lᵀ`.
    pub fn factor(&mut self, topology: &Topology, settings: &SolverSettings) -> Result<(), SolveFailure> {
        let tolerance = settings.rank_tolerance * settings.rank_tolerance;
        for front in &topology.fronts {
            let size = front.size();
            let f = &mut self.fronts[front.storage..front.storage + size * size];
            with_front_size!(size, N => factor_front::<N>(f, front.eliminated, tolerance), {
                factor_dynamic(f, size, front.eliminated, tolerance, &mut self.column)
            })
            .map_err(|(e, pivot, diagonal)| SolveFailure::TreeRank {
                joint: topology.tree_owner[front.start + e],
                singular_value: pivot.max(0.0).sqrt(),
                largest: diagonal.max(0.0).sqrt(),
            })?;
            // The trailing block (the parent joint's) goes to the parent front's lower triangle.
            if let Some((parent, offset)) = front.parent {
                let m = front.eliminated;
                let parent_front = &topology.fronts[parent];
                let parent_size = parent_front.size();
                for i in m..size {
                    let source = front.storage + i * size + m;
                    let target = parent_front.storage + (offset + i - m) * parent_size + offset;
                    for d in 0..=i - m {
                        let value = self.fronts[source + d];
                        self.fronts[target + d] += value;
                    }
                }
            }
        }
        if topology.loop_size > 0 {
            self.factor_loops(topology, settings);
        }
        Ok(())
    }

    /// `x ← K_TT⁻¹ x` with the tree factors. A front's variables are two runs of x, its eliminated ones from
    /// `start` and its parent's from `parent_start`: adjacent in a chain (solved in place), otherwise gathered into
    /// a small buffer and scattered back.
    fn solve_tree(&self, topology: &Topology, x: &mut [f64]) {
        let mut dynamic = Vec::new();
        for front in &topology.fronts {
            self.visit(
                front,
                x,
                &mut dynamic,
                |f, size, m, x| with_front_size!(size, N => forward::<N>(f, m, x), { forward_dynamic(f, size, m, x) }),
            );
        }
        for front in &topology.fronts {
            let size = front.size();
            for e in 0..front.eliminated {
                x[front.start + e] /= self.fronts[front.storage + e * size + e];
            }
        }
        for front in topology.fronts.iter().rev() {
            self.visit(front, x, &mut dynamic, |f, size, m, x| {
                with_front_size!(size, N => backward::<N>(f, m, x), { backward_dynamic(f, size, m, x) })
            });
        }
    }

    /// Runs `pass(factor, size, eliminated, variables)` on one front's variables of x (generic, so that each pass
    /// is inlined into its loop over the fronts).
    #[inline(always)]
    fn visit(
        &self,
        front: &Front,
        x: &mut [f64],
        dynamic: &mut Vec<f64>,
        pass: impl Fn(&[f64], usize, usize, &mut [f64]),
    ) {
        let (size, m) = (front.size(), front.eliminated);
        let f = &self.fronts[front.storage..front.storage + size * size];
        if front.parent_size == 0 || front.parent_start == front.start + m {
            pass(f, size, m, &mut x[front.start..front.start + size]);
            return;
        }
        let mut local = [0.0; MAX_FIXED_FRONT];
        let buffer = if size <= MAX_FIXED_FRONT {
            &mut local[..size]
        } else {
            dynamic.resize(size, 0.0);
            &mut dynamic[..]
        };
        let parent = front.parent_start..front.parent_start + front.parent_size;
        buffer[..m].copy_from_slice(&x[front.start..front.start + m]);
        buffer[m..].copy_from_slice(&x[parent.clone()]);
        pass(f, size, m, buffer);
        x[front.start..front.start + m].copy_from_slice(&buffer[..m]);
        x[parent].copy_from_slice(&buffer[m..]);
    }

    /// `X = K_TT⁻¹ K_TL`, `S = K_LL − K_LT X`, scaled by `K_LL`'s diagonal and factored by
    /// pivoted `L D Lᵀ`, which finds its rank.
    fn factor_loops(&mut self, topology: &Topology, settings: &SolverSettings) {
        let (n, k) = (topology.tree_size, topology.loop_size);
        // A loop joint closes a cycle of tree joints, so there are tree variables whenever there are loop ones.
        let mut coupling = std::mem::take(&mut self.coupling);
        coupling.copy_from_slice(&self.tree_loop);
        for column in coupling.chunks_exact_mut(n) {
            self.solve_tree(topology, column);
        }
        self.coupling = coupling;
        // The scale of each loop row: its own diagonal in K_LL, before the tree's part is taken out. (Not S's
        // diagonal: a loop row wholly redundant with the tree has S_ii = round-off, which that scaling would
        // blow up to O(1).)
        for i in 0..k {
            let diagonal = self.loops[i * k + i];
            self.scaling[i] = if diagonal > 0.0 { 1.0 / diagonal.sqrt() } else { 0.0 };
        }
        // S = K_LL − K_TLᵀ X (symmetric; computed in full).
        for j in 0..k {
            for i in 0..k {
                let product: f64 = (0..n)
                    .map(|r| self.tree_loop[i * n + r] * self.coupling[j * n + r])
                    .sum();
                self.loops[j * k + i] -= product;
            }
        }
        for j in 0..k {
            for i in 0..k {
                self.loops[j * k + i] *= self.scaling[i] * self.scaling[j];
            }
        }
        // L D Lᵀ with diagonal pivoting (the largest remaining pivot first: rank-revealing for a positive
        // semi-definite matrix), stopping at the first pivot below rank_tolerance² of the largest diagonal.
        let a = &mut self.loops;
        let largest = (0..k).map(|i| a[i * k + i]).fold(0.0, f64::max);
        let threshold = settings.rank_tolerance * settings.rank_tolerance * largest;
        self.permutation.iter_mut().enumerate().for_each(|(i, p)| *p = i);
        self.loop_rank = 0;
        for s in 0..k {
            let pivot = (s..k)
                .max_by(|&x, &y| a[x * k + x].total_cmp(&a[y * k + y]))
                .unwrap_or(s);
            if !exceeds(a[pivot * k + pivot], threshold) {
                break;
            }
            if pivot != s {
                // The symmetric swap of rows and columns s and pivot.
                for c in 0..k {
                    a.swap(c * k + s, c * k + pivot);
                }
                for r in 0..k {
                    a.swap(s * k + r, pivot * k + r);
                }
                self.permutation.swap(s, pivot);
            }
            let d = a[s * k + s];
            for j in s + 1..k {
                let l = a[s * k + j] / d;
                for i in s + 1..k {
                    a[j * k + i] -= l * a[s * k + i];
                }
            }
            for i in s + 1..k {
                a[s * k + i] /= d;
                a[i * k + s] = a[s * k + i];
            }
            self.loop_rank += 1;
        }
    }

    /// Solves `K λ = rhs` in place: `tree` (tree multipliers, in tree-vector order) and `loops`. With loop
    /// joints, the loop multipliers are those of the kept (pivoted) rows of the Schur complement, the redundant
    /// rows' multipliers zero, checked for consistency.
    pub fn solve(
        &mut self,
        topology: &Topology,
        tree: &mut [f64],
        loops: &mut [f64],
        consistency: Consistency,
        settings: &SolverSettings,
    ) -> Result<(), SolveFailure> {
        let (n, k) = (topology.tree_size, topology.loop_size);
        self.solve_tree(topology, tree);
        if k == 0 {
            return Ok(());
        }
        // rhs'_L = rhs_L − K_LT K_TT⁻¹ rhs_T, in the scaled coordinates.
        let mut subtracted = 0.0f64;
        for (i, value) in loops.iter_mut().enumerate() {
            let coupling: f64 = (0..n).map(|r| self.tree_loop[i * n + r] * tree[r]).sum();
            subtracted += coupling * coupling + *value * *value;
            *value = (*value - coupling) * self.scaling[i];
        }
        // The pivoted L D Lᵀ solve on the kept rows; after the forward pass the redundant rows hold what the kept
        // ones do not explain (zero for consistent conditions), and their multipliers are zero.
        let rhs_squared: f64 = loops.iter().map(|x| x * x).sum();
        let (rank, a) = (self.loop_rank, &self.loops);
        let c = &mut self.loop_scratch;
        for (slot, &row) in c.iter_mut().zip(&self.permutation) {
            *slot = loops[row];
        }
        for s in 0..rank {
            let value = c[s];
            for i in s + 1..k {
                c[i] -= a[s * k + i] * value;
            }
        }
        let residual_squared: f64 = c[rank..].iter().map(|x| x * x).sum();
        let scale = match consistency {
            Consistency::Check { scale } => Consistency::Check {
                scale: scale.max(subtracted.sqrt()),
            },
            Consistency::Skip => Consistency::Skip,
        };
        if scale.violated(residual_squared, rhs_squared, settings) {
            // Name the loop joint whose redundant row is furthest from consistent.
            let joint = (rank..k)
                .max_by(|&x, &y| c[x].abs().total_cmp(&c[y].abs()))
                .map_or(0, |i| topology.loop_owner[self.permutation[i]]);
            return Err(SolveFailure::Inconsistent {
                joint,
                relative_residual: (residual_squared / rhs_squared).sqrt(),
            });
        }
        for s in 0..rank {
            c[s] /= a[s * k + s];
        }
        for s in (0..rank).rev() {
            let mut value = c[s];
            for i in s + 1..rank {
                value -= a[s * k + i] * c[i];
            }
            c[s] = value;
        }
        c[rank..].fill(0.0);
        for (s, &row) in self.permutation.iter().enumerate() {
            loops[row] = c[s] * self.scaling[row];
        }
        // λ_T = K_TT⁻¹ rhs_T − X λ_L.
        for (column, &lambda) in loops.iter().enumerate() {
            for (t, x) in tree.iter_mut().zip(&self.coupling[column * n..(column + 1) * n]) {
                *t -= x * lambda;
            }
        }
        Ok(())
    }
}

/// Fronts up to this size are factored and solved by code specialised to their size (loops unrolled, no bounds
/// checks): a chain of ball joints has fronts of 6, of hinges 10.
const MAX_FIXED_FRONT: usize = 12;

/// Runs `$fixed` with the const `$n` equal to `$value` when it is one of the listed constants (loops over a
/// constant count unroll), else `$dynamic`.
macro_rules! with_constant {
    ($value:expr, $n:ident in [$($k:literal),*] => $fixed:expr, $dynamic:block) => {
        match $value {
            $($k => {
                const $n: usize = $k;
                $fixed
            })*
            _ => $dynamic,
        }
    };
}
use with_constant;

/// [`with_constant`] over the front sizes up to [`MAX_FIXED_FRONT`].
macro_rules! with_front_size {
    ($size:expr, $n:ident => $fixed:expr, $dynamic:block) => {
        with_constant!($size, $n in [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12] => $fixed, $dynamic)
    };
}
use with_front_size;

/// A front's storage as an `N × N` array.
fn square<const N: usize>(f: &mut [f64]) -> &mut [[f64; N]; N] {
    let (rows, _) = f.as_chunks_mut::<N>();
    (&mut rows[..N])
        .try_into()
        .expect("a front's storage holds N × N entries")
}

fn square_ref<const N: usize>(f: &[f64]) -> &[[f64; N]; N] {
    let (rows, _) = f.as_chunks::<N>();
    (&rows[..N]).try_into().expect("a front's storage holds N × N entries")
}

/// `L D Lᵀ` of a front's first `m` variables, right-looking on the lower triangle, leaving the Schur complement
/// on the others in the trailing block. A pivot is checked against its own diagonal as assembled (the part of
/// the variable the earlier ones do not explain: scale-free); a failure returns (variable, pivot, diagonal).
fn factor_front<const N: usize>(f: &mut [f64], m: usize, tolerance: f64) -> Result<(), (usize, f64, f64)> {
    with_constant!(m, M in [1, 2, 3, 4, 5, 6] => eliminate::<N>(f, M, tolerance), { eliminate::<N>(f, m, tolerance) })
}

/// [`factor_front`]'s elimination; inlined into each call so that a constant `m` unrolls its loops.
#[inline(always)]
fn eliminate<const N: usize>(f: &mut [f64], m: usize, tolerance: f64) -> Result<(), (usize, f64, f64)> {
    let a = square::<N>(f);
    let diagonal: [f64; N] = std::array::from_fn(|i| a[i][i]);
    for e in 0..m.min(N) {
        let pivot = a[e][e];
        if !exceeds(pivot, tolerance * diagonal[e].max(f64::MIN_POSITIVE)) {
            return Err((e, pivot, diagonal[e]));
        }
        let inverse = 1.0 / pivot;
        let column: [f64; N] = std::array::from_fn(|i| a[i][e]);
        for i in e + 1..N {
            let l = column[i] * inverse;
            let row = &mut a[i];
            for j in e + 1..i + 1 {
                row[j] -= l * column[j];
            }
            row[e] = l;
        }
    }
    Ok(())
}

fn factor_dynamic(
    f: &mut [f64],
    size: usize,
    m: usize,
    tolerance: f64,
    scratch: &mut Vec<f64>,
) -> Result<(), (usize, f64, f64)> {
    scratch.clear();
    scratch.extend((0..size).map(|i| f[i * size + i]));
    scratch.extend((0..size).map(|_| 0.0));
    let (diagonal, column) = scratch.split_at_mut(size);
    for e in 0..m {
        let pivot = f[e * size + e];
        if !exceeds(pivot, tolerance * diagonal[e].max(f64::MIN_POSITIVE)) {
            return Err((e, pivot, diagonal[e]));
        }
        let inverse = 1.0 / pivot;
        for (i, c) in column.iter_mut().enumerate().skip(e + 1) {
            *c = f[i * size + e];
        }
        for i in e + 1..size {
            let l = column[i] * inverse;
            for (x, c) in f[i * size + e + 1..=i * size + i].iter_mut().zip(&column[e + 1..=i]) {
                *x -= l * c;
            }
            f[i * size + e] = l;
        }
    }
    Ok(())
}

/// `L y = x` over a front's eliminated variables, and the parent's part of x updated.
fn forward<const N: usize>(f: &[f64], m: usize, x: &mut [f64]) {
    with_constant!(m, M in [1, 2, 3, 4, 5, 6] => forward_eliminated::<N>(f, M, x), { forward_eliminated::<N>(f, m, x) })
}

#[inline(always)]
fn forward_eliminated<const N: usize>(f: &[f64], m: usize, x: &mut [f64]) {
    let a = square_ref::<N>(f);
    let x: &mut [f64; N] = x.try_into().expect("N values");
    for e in 0..m.min(N) {
        let value = x[e];
        for i in e + 1..N {
            x[i] -= a[i][e] * value;
        }
    }
}

fn forward_dynamic(f: &[f64], size: usize, m: usize, x: &mut [f64]) {
    for e in 0..m {
        let value = x[e];
        for i in e + 1..size {
            x[i] -= f[i * size + e] * value;
        }
    }
}

/// `Lᵀ x = y` over a front's eliminated variables, the parent's already solved.
fn backward<const N: usize>(f: &[f64], m: usize, x: &mut [f64]) {
    with_constant!(m, M in [1, 2, 3, 4, 5, 6] => backward_eliminated::<N>(f, M, x), { backward_eliminated::<N>(f, m, x) })
}

#[inline(always)]
fn backward_eliminated<const N: usize>(f: &[f64], m: usize, x: &mut [f64]) {
    let a = square_ref::<N>(f);
    let x: &mut [f64; N] = x.try_into().expect("N values");
    for e in (0..m.min(N)).rev() {
        let mut value = x[e];
        for i in e + 1..N {
            value -= a[i][e] * x[i];
        }
        x[e] = value;
    }
}

fn backward_dynamic(f: &[f64], size: usize, m: usize, x: &mut [f64]) {
    for e in (0..m).rev() {
        let mut value = x[e];
        for i in e + 1..size {
            value -= f[i * size + e] * x[i];
        }
        x[e] = value;
    }
}
