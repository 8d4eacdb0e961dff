//! The operations the compiler emits, with their user-facing names.

/// Every product and unary map the compiler can emit. The definitions follow the conventions of
/// clifford 1.5.1 as documented in `tests/data/refdata` (see [`crate::product`] for each rule).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Operation {
    // Binary.
    /// The geometric product `a b`.
    Geometric,
    /// The outer (wedge) product `a ∧ b`.
    Outer,
    /// The left contraction `a ⌋ b`: ⟨a_r b_s⟩_{s−r}, zero if s < r.
    LeftContraction,
    /// The right contraction `a ⌊ b`: ⟨a_r b_s⟩_{r−s}, zero if r < s.
    RightContraction,
    /// The scalar product ⟨a b⟩₀.
    ScalarProduct,
    /// The Hestenes inner product ⟨a_r b_s⟩_{|r−s|}, zero if either grade is 0.
    HestenesInner,
    /// The "fat dot" inner product ⟨a_r b_s⟩_{|r−s|}, scalars included.
    FatDot,
    /// The regressive product LC(RC(a) ∧ RC(b)), metric-free (the PGA join).
    Regressive,
    /// The commutator product (a b − b a)/2.
    Commutator,
    /// The sandwich `a x ~a`, for any `a`.
    Sandwich,
    /// The sandwich for unit versors (`a ~a = 1`), using that identity to do less work.
    Transform,
    // Unary.
    /// The reverse: grade k times (−1)^{k(k−1)/2}.
    Reverse,
    /// The grade involution: grade k times (−1)^k.
    Involute,
    /// The Clifford conjugate: grade k times (−1)^{k(k+1)/2}.
    Conjugate,
    /// The right complement, with `e_m ∧ RC(e_m) = I`.
    RightComplement,
    /// The left complement, with `LC(e_m) ∧ e_m = I`.
    LeftComplement,
    /// The polarity (metric dual) `a I⁻¹`; zero on a degenerate metric.
    Polarity,
    /// The projections onto each grade of a type (one `grade_k` method per grade).
    Grade,
    /// The squared norm ⟨a ~a⟩₀.
    NormSquared,
    /// The inverse `~a / (a ~a)`, for types where `a ~a` is a scalar.
    Inverse,
}

impl Operation {
    /// All operations, binary first.
    pub const ALL: [Operation; 20] = [
        Operation::Geometric,
        Operation::Outer,
        Operation::LeftContraction,
        Operation::RightContraction,
        Operation::ScalarProduct,
        Operation::HestenesInner,
        Operation::FatDot,
        Operation::Regressive,
        Operation::Commutator,
        Operation::Sandwich,
        Operation::Transform,
        Operation::Reverse,
        Operation::Involute,
        Operation::Conjugate,
        Operation::RightComplement,
        Operation::LeftComplement,
        Operation::Polarity,
        Operation::Grade,
        Operation::NormSquared,
        Operation::Inverse,
    ];

    /// The method name in emitted code (and in `ops = [...]`).
    pub fn name(self) -> &'static str {
        match self {
            Operation::Geometric => "geometric",
            Operation::Outer => "outer",
            Operation::LeftContraction => "left_contraction",
            Operation::RightContraction => "right_contraction",
            Operation::ScalarProduct => "scalar_product",
            Operation::HestenesInner => "hestenes_inner",
            Operation::FatDot => "fat_dot",
            Operation::Regressive => "regressive",
            Operation::Commutator => "commutator",
            Operation::Sandwich => "sandwich",
            Operation::Transform => "transform",
            Operation::Reverse => "reverse",
            Operation::Involute => "involute",
            Operation::Conjugate => "conjugate",
            Operation::RightComplement => "right_complement",
            Operation::LeftComplement => "left_complement",
            Operation::Polarity => "polarity",
            Operation::Grade => "grade",
            Operation::NormSquared => "norm_squared",
            Operation::Inverse => "inverse",
        }
    }

    /// Parses a method name.
    ///
    /// ```
    /// use ga_codegen::Operation;
    ///
    /// let operation = Operation::from_name("left_contraction");
    /// assert_eq!(operation, Some(Operation::LeftContraction));
    /// assert!(operation.unwrap().is_binary());
    /// assert_eq!(Operation::from_name("dot"), None); // the inner products are spelled out
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|op| op.name() == name)
    }

    /// Whether the operation takes two operands.
    pub fn is_binary(self) -> bool {
        matches!(
            self,
            Operation::Geometric
                | Operation::Outer
                | Operation::LeftContraction
                | Operation::RightContraction
                | Operation::ScalarProduct
                | Operation::HestenesInner
                | Operation::FatDot
                | Operation::Regressive
                | Operation::Commutator
                | Operation::Sandwich
                | Operation::Transform
        )
    }
}
