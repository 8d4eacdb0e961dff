//! Errors of the compiler, each with the location of the offending declaration so that a front end
//! (the `algebra!` macro) can point at the exact token.

/// Which part of the [`AlgebraDeclaration`](crate::AlgebraDeclaration) an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// The whole algebra.
    Algebra,
    /// `basis[index]`.
    Basis(usize),
    /// `types[index]` as a whole (its name).
    Type(usize),
    /// Item `item` (a grade or a blade name) of `types[ty]`'s layout.
    TypeItem { ty: usize, item: usize },
    /// `operations[index]`.
    Operation(usize),
    /// The `metric` matrix as a whole.
    Metric,
    /// Row `row` of the `metric` matrix.
    MetricRow(usize),
    /// The entry `metric[row][column]`.
    MetricEntry { row: usize, column: usize },
}

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    #[error("an algebra needs at least one basis vector")]
    EmptyBasis,
    #[error("{count} basis vectors declared; at most {max} are supported")]
    TooManyBasisVectors { count: usize, max: usize },
    #[error("basis vector `{name}` is declared twice")]
    DuplicateBasisName { index: usize, name: String },
    #[error("basis vector `{name}` squares to {square}; a square must be 1, -1 or 0")]
    InvalidSquare { index: usize, name: String, square: i64 },
    #[error("the metric has {rows} rows, but the basis has {expected} vectors: it must be {expected}×{expected}")]
    MetricSize { rows: usize, expected: usize },
    #[error("row {row} of the metric has {length} entries, but the metric is {expected}×{expected}")]
    MetricRowLength { row: usize, length: usize, expected: usize },
    #[error(
        "the metric is not symmetric: entry ({row}, {column}) is {value} but entry ({column}, {row}) is {transposed}; \
         a bilinear form B(eᵢ, eⱼ) = B(eⱼ, eᵢ) has a symmetric matrix"
    )]
    MetricNotSymmetric {
        row: usize,
        column: usize,
        value: String,
        transposed: String,
    },
    #[error(
        "the metric's entries are too large for exact 64-bit coefficients in {dimension} dimensions: \
         use smaller numerators and denominators, or fewer non-zero off-diagonal entries"
    )]
    MetricTooLarge { dimension: usize },
    #[error("basis vector name `{name}` {problem}")]
    InvalidBasisName {
        index: usize,
        name: String,
        problem: NameProblem,
    },
    #[error(
        "basis vector name `{name}` contains `_`, which joins the names of basis vectors into blade names \
         in this basis, so {}: name the basis vectors without `_`",
        match clash {
            Some(factors) => format!("`{name}` would also name the blade {}", wedge(factors)),
            None => "a blade name could be read in more than one way".to_string(),
        }
    )]
    SeparatorInBasisName {
        index: usize,
        name: String,
        /// The basis vectors (without `_`) of another blade that `name` would also name, if any.
        clash: Option<Vec<String>>,
    },
    #[error(
        "`scalar` names the grade-0 blade, so it cannot also name {}: rename {}",
        describe_blade(factors),
        if factors.len() == 1 { "it".to_string() } else { format!("basis vector `{}`", last(factors)) }
    )]
    ScalarBladeName {
        /// The last basis vector of the blade.
        index: usize,
        /// The basis vectors of the blade that would be called `scalar`.
        factors: Vec<String>,
    },
    #[error(
        "the blade {} would be named `{blade}`, a Rust keyword, which cannot name its field: rename basis vector `{}`",
        wedge(factors),
        last(factors)
    )]
    KeywordBladeName {
        /// The last basis vector of the blade.
        index: usize,
        blade: String,
        factors: Vec<String>,
    },
    #[error("type name `{name}` {problem}")]
    InvalidTypeName {
        index: usize,
        name: String,
        problem: NameProblem,
    },
    #[error("type name `{name}` clashes with {clash}: rename the type")]
    ReservedTypeName {
        index: usize,
        name: String,
        /// What the emitted module already means by the name.
        clash: String,
    },
    #[error(
        "types `{other}` and `{name}` would both give methods named `{operation}_{method_suffix}` (the `const fn` \
         form of `{operation}` with that type on the right): both names are `{method_suffix}` in snake case; \
         rename one of them"
    )]
    TypeMethodCollision {
        /// The later type.
        index: usize,
        name: String,
        /// The earlier type with the same snake-case name.
        other: String,
        /// The snake-case name both types give.
        method_suffix: String,
        /// A binary operation the methods are emitted for.
        operation: String,
    },
    #[error(
        "type `{ty}` would have {fields} fields; a declared type may have at most {max} \
         (a full multivector in {max_dimension} dimensions): declare fewer grades or blades"
    )]
    TooManyFields {
        ty_index: usize,
        ty: String,
        /// The number of blades the layout asks for.
        fields: u64,
        max: usize,
        max_dimension: usize,
    },
    #[error("blade name `{blade}` in type `{ty}` {problem}")]
    InvalidBladeName {
        ty_index: usize,
        item: usize,
        ty: String,
        blade: String,
        problem: NameProblem,
    },
    #[error("type `{name}` is declared twice")]
    DuplicateTypeName { index: usize, name: String },
    #[error("type `{name}` has no blades")]
    EmptyType { index: usize, name: String },
    #[error("unknown blade `{blade}` in type `{ty}`: {reason}")]
    UnknownBlade {
        ty_index: usize,
        item: usize,
        ty: String,
        blade: String,
        reason: String,
    },
    #[error("blade `{blade}` appears twice in type `{ty}`")]
    DuplicateBlade {
        ty_index: usize,
        item: usize,
        ty: String,
        blade: String,
    },
    #[error("grade {grade} in type `{ty}` is out of range: this algebra has grades 0 to {max}")]
    GradeOutOfRange {
        ty_index: usize,
        item: usize,
        ty: String,
        grade: u32,
        max: u32,
    },
    #[error(
        "`{ty} = all` would have 2^{dimension} = {blades} coefficients and products with {products} terms; \
         full multivectors are limited to {max_dimension} dimensions: declare smaller types (grades or blades) instead"
    )]
    AllTooLarge {
        ty_index: usize,
        ty: String,
        dimension: usize,
        blades: u64,
        products: u64,
        max_dimension: usize,
    },
    #[error("operation `{name}` is listed twice")]
    DuplicateOperation { index: usize, name: String },
    #[error(
        "no declared type holds the result of `{lhs}.{operation}({rhs})`: it needs the blades [{}]; \
         declare a type with them (or `Multivector = all`)", blades.join(", ")
    )]
    NoResultType {
        operation: String,
        lhs: String,
        rhs: String,
        blades: Vec<String>,
    },
}

impl Error {
    /// Where in the declaration the error is.
    pub fn location(&self) -> Location {
        match *self {
            Error::EmptyBasis | Error::TooManyBasisVectors { .. } | Error::NoResultType { .. } => Location::Algebra,
            Error::DuplicateBasisName { index, .. }
            | Error::InvalidSquare { index, .. }
            | Error::InvalidBasisName { index, .. }
            | Error::SeparatorInBasisName { index, .. }
            | Error::ScalarBladeName { index, .. }
            | Error::KeywordBladeName { index, .. } => Location::Basis(index),
            Error::DuplicateTypeName { index, .. }
            | Error::EmptyType { index, .. }
            | Error::InvalidTypeName { index, .. }
            | Error::ReservedTypeName { index, .. }
            | Error::TypeMethodCollision { index, .. } => Location::Type(index),
            Error::AllTooLarge { ty_index, .. } | Error::TooManyFields { ty_index, .. } => Location::Type(ty_index),
            Error::UnknownBlade { ty_index, item, .. }
            | Error::InvalidBladeName { ty_index, item, .. }
            | Error::DuplicateBlade { ty_index, item, .. }
            | Error::GradeOutOfRange { ty_index, item, .. } => Location::TypeItem { ty: ty_index, item },
            Error::DuplicateOperation { index, .. } => Location::Operation(index),
            Error::MetricSize { .. } | Error::MetricTooLarge { .. } => Location::Metric,
            Error::MetricRowLength { row, .. } => Location::MetricRow(row),
            Error::MetricNotSymmetric { row, column, .. } => Location::MetricEntry { row, column },
        }
    }
}

/// Why a name cannot be used in the emitted code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum NameProblem {
    #[error("is not a valid identifier")]
    NotAnIdentifier,
    #[error("is a Rust keyword")]
    Keyword,
    #[error("is a raw identifier, which is not supported here: choose a name that needs no `r#`")]
    Raw,
}

/// "the basis vector \`e1\`" or "the blade \`e1\` ∧ \`e2\`".
fn describe_blade(factors: &[String]) -> String {
    match factors {
        [vector] => format!("the basis vector `{vector}`"),
        _ => format!("the blade {}", wedge(factors)),
    }
}

/// "\`e1\` ∧ \`e2\`".
fn wedge(factors: &[String]) -> String {
    let quoted: Vec<String> = factors.iter().map(|factor| format!("`{factor}`")).collect();
    quoted.join(" ∧ ")
}

/// The last basis vector of a blade: the one its error points at.
fn last(factors: &[String]) -> &str {
    factors.last().map_or("", String::as_str)
}

/// A dense multivector of the wrong length given to the [`Evaluator`](crate::Evaluator).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EvaluatorError {
    #[error(
        "the {operand} has {got} coefficients, but a dense multivector of this algebra has 2^n = {expected}, \
         one per blade"
    )]
    DenseLength {
        /// Which argument: `"left operand"`, `"right operand"` or `"operand"`.
        operand: &'static str,
        expected: usize,
        got: usize,
    },
}
