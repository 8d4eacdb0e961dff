//! The operations the compiler emits, with their user-facing names.

/// Every product and unary map the compiler can emit. The definitions follow the conventions of
/// clifford 1.5.1 as documented in `tests/data/refdata` (see [`crate::product`] for each rule).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Operation {
    // Binary.
    Geometric,
    Outer,
    LeftContraction,
    RightContraction,
    ScalarProduct,
    HestenesInner,
    FatDot,
    Regressive,
    Commutator,
    Sandwich,
    /// The sandwich for unit versors (`a ~a = 1`), using that identity to do less work.
    Transform,
    // Unary.
    Reverse,
    Involute,
    Conjugate,
    RightComplement,
    LeftComplement,
    Polarity,
    Grade,
    NormSquared,
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
