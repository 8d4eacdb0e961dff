//! What a user declares: basis vectors with their squares (or a full metric matrix), the scalar type,
//! the sparse types and (optionally) which operations to emit. This is the compiler's input;
//! `Algebra::new` validates it.

use num_rational::Rational64;

use crate::expression::ExpressionDeclaration;
use crate::operation::Operation;

/// The floating-point type of every emitted coefficient.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScalarType {
    /// Single precision, `f32`.
    F32,
    /// Double precision, `f64`.
    F64,
}

impl ScalarType {
    /// The Rust type name (`f32` or `f64`).
    pub fn name(self) -> &'static str {
        match self {
            ScalarType::F32 => "f32",
            ScalarType::F64 => "f64",
        }
    }

    /// Parses `f32` or `f64`.
    ///
    /// ```
    /// use ga_codegen::ScalarType;
    ///
    /// assert_eq!(ScalarType::from_name("f64"), Some(ScalarType::F64));
    /// assert_eq!(ScalarType::from_name("f32").map(ScalarType::name), Some("f32"));
    /// assert_eq!(ScalarType::from_name("f16"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "f32" => Some(ScalarType::F32),
            "f64" => Some(ScalarType::F64),
            _ => None,
        }
    }
}

/// One basis vector: its name and its square (+1, −1 or 0). Vectors are listed in bit order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BasisVectorDeclaration {
    /// The basis vector's name, e.g. `e1` or `ninf`; blade names are formed from it.
    pub name: String,
    /// Not read when the algebra has a [`metric`](AlgebraDeclaration::metric) matrix, whose diagonal
    /// gives the squares.
    pub square: i64,
}

/// How a declared type chooses its blades.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Every blade of the listed grades, in canonical order (grade, then lexicographic).
    Grades(Vec<u32>),
    /// Exactly these blades, in this order. `scalar` names the grade-0 blade; a permuted name such as
    /// `e31` means the blade `e13` with its sign flipped.
    Blades(Vec<String>),
    /// Every blade of the algebra (the full multivector), in canonical order.
    All,
}

/// A declared sparse type, e.g. `Motor = grades(0, 2, 4)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TypeDeclaration {
    /// The type's name, e.g. `Motor`: a Rust identifier.
    pub name: String,
    /// Which blades the type stores, and in what order.
    pub layout: Layout,
}

/// The whole input of the compiler.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AlgebraDeclaration {
    /// The floating-point type of the emitted coefficients.
    pub scalar: ScalarType,
    /// The basis vectors, in bit order.
    pub basis: Vec<BasisVectorDeclaration>,
    /// A general symmetric bilinear form, `metric[i][j]` = B(eᵢ, eⱼ) (e.g. a null basis with
    /// `n0 · ninf = −1`); `None` for the orthogonal basis whose squares `basis` lists.
    pub metric: Option<Vec<Vec<Rational64>>>,
    /// The sparse types to emit, in order.
    pub types: Vec<TypeDeclaration>,
    /// Emit only these operations (for big algebras); `None` emits all of them.
    pub operations: Option<Vec<Operation>>,
    /// How to lower a product, per operation; an operation not listed is unrolled up to
    /// [`MAX_UNROLLED_TERMS`](crate::table::MAX_UNROLLED_TERMS) monomials and
    /// [`MAX_UNROLLED_LOCALS`](crate::table::MAX_UNROLLED_LOCALS) hoisted locals, and table-driven beyond.
    pub lowering: Vec<(Operation, Lowering)>,
    /// Named expressions to fuse into one function each (see [`crate::fuse`]).
    pub expressions: Vec<ExpressionDeclaration>,
}

/// How the functions of a product (a binary operation) are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lowering {
    /// Straight-line code, one sum per output blade: the fastest at run time, but its source (and rustc's
    /// time) grows with the expansion's term count.
    Unrolled,
    /// Constant tables of products and a loop (see [`crate::table`]): compact source for products of
    /// thousands of terms, slower at run time.
    Table,
}
