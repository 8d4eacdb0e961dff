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
    #[error("basis vector name `{name}` is not a valid identifier")]
    InvalidBasisName { index: usize, name: String },
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
            | Error::InvalidBasisName { index, .. } => Location::Basis(index),
            Error::DuplicateTypeName { index, .. } | Error::EmptyType { index, .. } => Location::Type(index),
            Error::AllTooLarge { ty_index, .. } => Location::Type(ty_index),
            Error::UnknownBlade { ty_index, item, .. }
            | Error::DuplicateBlade { ty_index, item, .. }
            | Error::GradeOutOfRange { ty_index, item, .. } => Location::TypeItem { ty: ty_index, item },
            Error::DuplicateOperation { index, .. } => Location::Operation(index),
            Error::MetricSize { .. } | Error::MetricTooLarge { .. } => Location::Metric,
            Error::MetricRowLength { row, .. } => Location::MetricRow(row),
            Error::MetricNotSymmetric { row, column, .. } => Location::MetricEntry { row, column },
        }
    }
}
