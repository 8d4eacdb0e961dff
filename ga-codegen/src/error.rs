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
    TypeItem {
        /// Index into `types`.
        ty: usize,
        /// Index into that type's layout list.
        item: usize,
    },
    /// `operations[index]`.
    Operation(usize),
    /// `lowering[index]`.
    Lowering(usize),
    /// The `metric` matrix as a whole.
    Metric,
    /// Row `row` of the `metric` matrix.
    MetricRow(usize),
    /// The entry `metric[row][column]`.
    MetricEntry {
        /// Row index (the first basis vector).
        row: usize,
        /// Column index (the second basis vector).
        column: usize,
    },
    /// `expressions[index]` as a whole (its name).
    Expression(usize),
    /// Parameter `parameter` of `expressions[expression]`.
    ExpressionParameter {
        /// Index into `expressions`.
        expression: usize,
        /// Index into its parameters.
        parameter: usize,
    },
    /// The declared result type of `expressions[index]`.
    ExpressionResult(usize),
    /// The node with id `node` in the body of `expressions[expression]` (ids are the front end's).
    ExpressionNode {
        /// Index into `expressions`.
        expression: usize,
        /// The node's [`id`](crate::expression::Expression::id).
        node: usize,
    },
}

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
/// A declaration the compiler rejects; [`Error::location`] says which part of it is at fault.
pub enum Error {
    #[error("an algebra needs at least one basis vector")]
    /// The declaration lists no basis vectors.
    EmptyBasis,
    #[error("{count} basis vectors declared; at most {max} are supported")]
    /// More basis vectors than blade bit masks can hold.
    TooManyBasisVectors {
        /// How many basis vectors were declared.
        count: usize,
        /// The limit, [`MAX_DIMENSION`](crate::blade::MAX_DIMENSION).
        max: usize,
    },
    #[error("basis vector `{name}` is declared twice")]
    /// Two basis vectors share a name.
    DuplicateBasisName {
        /// Index of the second occurrence in `basis`.
        index: usize,
        /// The repeated name.
        name: String,
    },
    #[error("basis vector `{name}` squares to {square}; a square must be 1, -1 or 0")]
    /// A basis vector (without a `metric` matrix) squares to something other than 1, −1 or 0.
    InvalidSquare {
        /// Index into `basis`.
        index: usize,
        /// The basis vector's name.
        name: String,
        /// The rejected square.
        square: i64,
    },
    #[error("the metric has {rows} rows, but the basis has {expected} vectors: it must be {expected}×{expected}")]
    /// The `metric` matrix does not have one row per basis vector.
    MetricSize {
        /// Rows the matrix has.
        rows: usize,
        /// Rows it needs: the number of basis vectors.
        expected: usize,
    },
    #[error("row {row} of the metric has {length} entries, but the metric is {expected}×{expected}")]
    /// A row of the `metric` matrix does not have one entry per basis vector.
    MetricRowLength {
        /// Index of the row.
        row: usize,
        /// Entries the row has.
        length: usize,
        /// Entries it needs: the number of basis vectors.
        expected: usize,
    },
    /// The `metric` matrix is not symmetric.
    #[error(
        "the metric is not symmetric: entry ({row}, {column}) is {value} but entry ({column}, {row}) is {transposed}; \
         a bilinear form B(eᵢ, eⱼ) = B(eⱼ, eᵢ) has a symmetric matrix"
    )]
    MetricNotSymmetric {
        /// Row of the offending entry.
        row: usize,
        /// Column of the offending entry.
        column: usize,
        /// The entry `metric[row][column]`, formatted.
        value: String,
        /// The mirrored entry `metric[column][row]`, formatted.
        transposed: String,
    },
    /// The metric's entries would overflow the exact 64-bit rational coefficients of the expansion.
    #[error(
        "the metric's entries are too large for exact 64-bit coefficients in {dimension} dimensions: \
         use smaller numerators and denominators, or fewer non-zero off-diagonal entries"
    )]
    MetricTooLarge {
        /// The number of basis vectors.
        dimension: usize,
    },
    /// A basis vector's name is not usable as a Rust identifier.
    #[error("basis vector name `{name}` {problem}")]
    InvalidBasisName {
        /// Index into `basis`.
        index: usize,
        /// The rejected name.
        name: String,
        /// Why the name is rejected.
        problem: NameProblem,
    },
    /// A basis vector's name contains `_`, which would make blade names ambiguous.
    #[error(
        "basis vector name `{name}` contains `_`, which joins the names of basis vectors into blade names \
         in this basis, so {}: name the basis vectors without `_`",
        match clash {
            Some(factors) => format!("`{name}` would also name the blade {}", wedge(factors)),
            None => "a blade name could be read in more than one way".to_string(),
        }
    )]
    SeparatorInBasisName {
        /// Index into `basis`.
        index: usize,
        /// The rejected name.
        name: String,
        /// The basis vectors (without `_`) of another blade that `name` would also name, if any.
        clash: Option<Vec<String>>,
    },
    /// A blade (in practice a basis vector) would be named `scalar`, the grade-0 blade's name.
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
    /// A blade's name, joined from its basis vector names, would be a Rust keyword.
    #[error(
        "the blade {} would be named `{blade}`, a Rust keyword, which cannot name its field: rename basis vector `{}`",
        wedge(factors),
        last(factors)
    )]
    KeywordBladeName {
        /// The last basis vector of the blade.
        index: usize,
        /// The blade name that is a keyword.
        blade: String,
        /// The basis vectors of the blade.
        factors: Vec<String>,
    },
    /// A type's name is not usable as a Rust identifier.
    #[error("type name `{name}` {problem}")]
    InvalidTypeName {
        /// Index into `types`.
        index: usize,
        /// The rejected name.
        name: String,
        /// Why the name is rejected.
        problem: NameProblem,
    },
    /// A type's name clashes with an item the emitted module defines itself.
    #[error("type name `{name}` clashes with {clash}: rename the type")]
    ReservedTypeName {
        /// Index into `types`.
        index: usize,
        /// The rejected name.
        name: String,
        /// What the emitted module already means by the name.
        clash: String,
    },
    /// Two type names have the same snake case, so their `const fn` method names would collide.
    #[error(
        "types `{other}` and `{name}` would both give methods named `{operation}_{method_suffix}` (the `const fn` \
         form of `{operation}` with that type on the right): both names are `{method_suffix}` in snake case; \
         rename one of them"
    )]
    TypeMethodCollision {
        /// The later type.
        index: usize,
        /// The later type's name.
        name: String,
        /// The earlier type with the same snake-case name.
        other: String,
        /// The snake-case name both types give.
        method_suffix: String,
        /// A binary operation the methods are emitted for.
        operation: String,
    },
    /// A `grades(…)` or `blades(…)` layout asks for more than [`MAX_TYPE_FIELDS`](crate::algebra::MAX_TYPE_FIELDS) blades.
    #[error(
        "type `{ty}` would have {fields} fields; a declared type may have at most {max} \
         (a full multivector in {max_dimension} dimensions): declare fewer grades or blades"
    )]
    TooManyFields {
        /// Index into `types`.
        ty_index: usize,
        /// The type's name.
        ty: String,
        /// The number of blades the layout asks for.
        fields: u64,
        /// The limit on fields per type.
        max: usize,
        /// The dimension whose full multivector has `max` blades.
        max_dimension: usize,
    },
    /// A blade name in a `blades(…)` layout is not usable as a Rust identifier.
    #[error("blade name `{blade}` in type `{ty}` {problem}")]
    InvalidBladeName {
        /// Index into `types`.
        ty_index: usize,
        /// Index into the type's blade list.
        item: usize,
        /// The type's name.
        ty: String,
        /// The rejected blade name.
        blade: String,
        /// Why the name is rejected.
        problem: NameProblem,
    },
    #[error("type `{name}` is declared twice")]
    /// Two types share a name.
    DuplicateTypeName {
        /// Index of the second occurrence in `types`.
        index: usize,
        /// The repeated name.
        name: String,
    },
    #[error("type `{name}` has no blades")]
    /// A type's layout selects no blades.
    EmptyType {
        /// Index into `types`.
        index: usize,
        /// The type's name.
        name: String,
    },
    /// A `blades(…)` layout names a blade that does not parse as basis vector names of this algebra.
    #[error("unknown blade `{blade}` in type `{ty}`: {reason}")]
    UnknownBlade {
        /// Index into `types`.
        ty_index: usize,
        /// Index into the type's blade list.
        item: usize,
        /// The type's name.
        ty: String,
        /// The unknown blade name.
        blade: String,
        /// Why the name does not parse, for the message.
        reason: String,
    },
    /// A type's layout lists the same blade (or grade) twice.
    #[error("blade `{blade}` appears twice in type `{ty}`")]
    DuplicateBlade {
        /// Index into `types`.
        ty_index: usize,
        /// Index of the second occurrence in the type's layout list.
        item: usize,
        /// The type's name.
        ty: String,
        /// The repeated blade (or grade), formatted.
        blade: String,
    },
    /// A `grades(…)` layout lists a grade above the dimension of the algebra.
    #[error("grade {grade} in type `{ty}` is out of range: this algebra has grades 0 to {max}")]
    GradeOutOfRange {
        /// Index into `types`.
        ty_index: usize,
        /// Index into the type's grade list.
        item: usize,
        /// The type's name.
        ty: String,
        /// The rejected grade.
        grade: u32,
        /// The highest grade: the number of basis vectors.
        max: u32,
    },
    /// A type declared `all` in an algebra above [`MAX_FULL_MULTIVECTOR_DIMENSION`](crate::algebra::MAX_FULL_MULTIVECTOR_DIMENSION) dimensions.
    #[error(
        "`{ty} = all` would have 2^{dimension} = {blades} coefficients and products with {products} terms; \
         full multivectors are limited to {max_dimension} dimensions: declare smaller types (grades or blades) instead"
    )]
    AllTooLarge {
        /// Index into `types`.
        ty_index: usize,
        /// The type's name.
        ty: String,
        /// The number of basis vectors.
        dimension: usize,
        /// Coefficients the full multivector would have (2ⁿ).
        blades: u64,
        /// Terms of a product of two full multivectors (4ⁿ).
        products: u64,
        /// The largest dimension allowed for `all`.
        max_dimension: usize,
    },
    #[error(
        "the functions of `{ty}` bring the declaration's code to {work} units of build work, over the {limit} that \
         build in under a minute (a table entry is one unit, an unrolled multiply {unrolled_multiply}): declare \
         only the operations you use (`ops = [...]`), or fewer or smaller types"
    )]
    /// The declaration's functions would take more than [`MAX_BUILD_WORK`](crate::functions::MAX_BUILD_WORK) to
    /// build: refused when the sum of [`build_work`](crate::functions::Function::build_work) crosses it.
    TooMuchCode {
        /// Index into `types`: the left operand of the function that crossed the limit.
        ty_index: usize,
        /// The type's name.
        ty: String,
        /// The work of the functions emitted so far, that one included.
        work: usize,
        /// [`MAX_BUILD_WORK`](crate::functions::MAX_BUILD_WORK).
        limit: usize,
        /// [`UNROLLED_MULTIPLY_WORK`](crate::functions::UNROLLED_MULTIPLY_WORK).
        unrolled_multiply: usize,
    },
    #[error("operation `{name}` is listed twice")]
    /// An operation is listed twice in `operations`.
    DuplicateOperation {
        /// Index of the second occurrence in `operations`.
        index: usize,
        /// The operation's name.
        name: String,
    },
    #[error("`{name}` is not a product: only binary operations can be lowered to tables")]
    /// A lowering is chosen for a unary operation.
    LoweringOfUnary {
        /// Index into `lowering`.
        index: usize,
        /// The operation's name.
        name: String,
    },
    #[error("a lowering is chosen for `{name}`, which is not emitted (it is missing from the operations)")]
    /// A lowering is chosen for an operation the declaration does not emit.
    LoweringNotEmitted {
        /// Index into `lowering`.
        index: usize,
        /// The operation's name.
        name: String,
    },
    #[error(
        "`{name}` of `{lhs}` and `{rhs}` is declared unrolled, but its expansion has {products} products, too many \
         to expand: declare it `table`"
    )]
    /// A product declared unrolled is too big to expand at all
    /// ([`MAX_EXACT_SANDWICH_PRODUCTS`](crate::table::MAX_EXACT_SANDWICH_PRODUCTS)).
    TooBigToUnroll {
        /// Index into `lowering`.
        index: usize,
        /// The operation's name.
        name: String,
        /// The left operand's type.
        lhs: String,
        /// The right operand's type.
        rhs: String,
        /// The products of its expansion.
        products: usize,
    },
    #[error("the lowering of `{name}` is chosen twice")]
    /// Two lowerings are chosen for one operation.
    DuplicateLowering {
        /// Index of the second choice in `lowering`.
        index: usize,
        /// The operation's name.
        name: String,
    },
    /// The result of an operation on two declared types fits no declared type.
    #[error(
        "no declared type holds the result of `{lhs}.{operation}({rhs})`: it needs the blades [{}]; \
         declare a type with them (or `Multivector = all`)", blades.join(", ")
    )]
    NoResultType {
        /// The operation's name.
        operation: String,
        /// The left operand's type.
        lhs: String,
        /// The right operand's type.
        rhs: String,
        /// The blades the result needs.
        blades: Vec<String>,
    },
    #[error("expression name `{name}` {problem}")]
    /// An expression's name cannot be a function name in the emitted code.
    InvalidExpressionName {
        /// Index into `expressions`.
        index: usize,
        /// The rejected name.
        name: String,
        /// Why it is rejected.
        problem: NameProblem,
    },
    #[error("expression `{name}` is declared twice")]
    /// Two expressions share a name.
    DuplicateExpression {
        /// Index of the second declaration in `expressions`.
        index: usize,
        /// The repeated name.
        name: String,
    },
    #[error("parameter name `{name}` of expression `{expression}` {problem}")]
    /// A parameter's name cannot be an identifier in the emitted code.
    InvalidParameterName {
        /// Index into `expressions`.
        index: usize,
        /// Index into its parameters.
        parameter: usize,
        /// The expression's name.
        expression: String,
        /// The rejected name.
        name: String,
        /// Why it is rejected.
        problem: NameProblem,
    },
    #[error("parameter `{name}` of expression `{expression}` is declared twice")]
    /// Two parameters of one expression share a name.
    DuplicateParameter {
        /// Index into `expressions`.
        index: usize,
        /// Index of the second occurrence in its parameters.
        parameter: usize,
        /// The expression's name.
        expression: String,
        /// The repeated name.
        name: String,
    },
    #[error("unknown type `{type_name}` in expression `{expression}`: expected a declared type or `{scalar}`")]
    /// A parameter or result type is neither a declared type nor the scalar type.
    UnknownExpressionType {
        /// Index into `expressions`.
        index: usize,
        /// The parameter with that type, or `None` for the result type.
        parameter: Option<usize>,
        /// The expression's name.
        expression: String,
        /// The unknown type name.
        type_name: String,
        /// The scalar type's name.
        scalar: String,
    },
    #[error("`{name}` in expression `{expression}` is neither a parameter nor a declared expression")]
    /// A name in an expression's body is not one of its parameters (or, called, not an expression).
    UnknownName {
        /// Index into `expressions`.
        index: usize,
        /// The node naming it.
        node: usize,
        /// The expression's name.
        expression: String,
        /// The unknown name.
        name: String,
    },
    #[error("expression `{expression}` calls `{name}`, which calls `{expression}` back: expressions cannot recurse")]
    /// A call that (directly or through other calls) reaches the expression it is in.
    RecursiveCall {
        /// Index into `expressions` of the expression holding the call.
        index: usize,
        /// The call's node.
        node: usize,
        /// The expression holding the call.
        expression: String,
        /// The called expression.
        name: String,
    },
    #[error("`{name}` takes {expected} arguments, but {found} are given")]
    /// A call with the wrong number of arguments.
    ArgumentCount {
        /// Index into `expressions` of the expression holding the call.
        index: usize,
        /// The call's node.
        node: usize,
        /// The called expression.
        name: String,
        /// Its parameter count.
        expected: usize,
        /// The arguments given.
        found: usize,
    },
    #[error(
        "argument `{parameter}` of `{name}` is a `{type_name}`, which has no blade {}: the argument does not fit",
        blades.join(", ")
    )]
    /// A call's argument has blades its parameter's type cannot hold.
    ArgumentDoesNotFit {
        /// Index into `expressions` of the expression holding the call.
        index: usize,
        /// The argument's node.
        node: usize,
        /// The called expression.
        name: String,
        /// The parameter.
        parameter: String,
        /// The parameter's type.
        type_name: String,
        /// The argument's blades outside that type.
        blades: Vec<String>,
    },
    #[error("`{operation}` cannot be fused: {reason}")]
    /// An operation that is not a polynomial of its operands' fields (`inverse` divides) or whose
    /// emitted meaning rests on an assumption the compiler cannot check (`transform`: a unit versor).
    NotFusable {
        /// Index into `expressions`.
        index: usize,
        /// The operation's node.
        node: usize,
        /// The operation's name.
        operation: String,
        /// Why, and what to write instead.
        reason: &'static str,
    },
    #[error("`{function}` takes exactly one parameter of the expression and must be its whole body, as in `fn {function}_b(b: Bivector) -> Motor = {function}(b);`: {reason}")]
    /// A call of `exp`, `log`, `sqrt` or `normalized` that is not the whole body of its expression, or whose
    /// argument is not one of the expression's parameters.
    TranscendentalUse {
        /// Index into `expressions`.
        index: usize,
        /// The call's node.
        node: usize,
        /// `exp`, `log`, `sqrt` or `normalized`.
        function: &'static str,
        /// What is wrong.
        reason: String,
    },
    #[error("no closed form is generated for `{function}` of `{type_name}`: {reason}")]
    /// A parameter type for which the closed form is not generated (see [`crate::transcendental`]).
    NoClosedForm {
        /// Index into `expressions`.
        index: usize,
        /// `exp`, `log`, `sqrt` or `normalized`.
        function: &'static str,
        /// The parameter's type.
        type_name: String,
        /// Why.
        reason: String,
    },
    #[error("grade {grade} is out of range: this algebra has grades 0 to {max}")]
    /// A grade selection beyond the algebra's dimension.
    ExpressionGradeOutOfRange {
        /// Index into `expressions`.
        index: usize,
        /// The selection's node.
        node: usize,
        /// The selected grade.
        grade: u32,
        /// The dimension.
        max: usize,
    },
    #[error(
        "expression `{expression}` is declared to return `{result}`, which has no blade {}: declare a type that \
         holds the result",
        blades.join(", ")
    )]
    /// The result has blades the declared result type cannot hold.
    ResultDoesNotFit {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The declared result type.
        result: String,
        /// The result's blades outside that type.
        blades: Vec<String>,
    },
    #[error("no declared type holds the result of expression `{expression}` (blades {}): declare one", blades.join(", "))]
    /// No declared type holds the result of an expression without a declared result type.
    NoExpressionResultType {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The result's blades.
        blades: Vec<String>,
    },
    #[error(
        "expression `{expression}` is identically zero (every term cancels), so no type follows from its blades: \
         declare its result type"
    )]
    /// An expression without a declared result type whose every term cancels.
    ZeroExpression {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
    },
    #[error(
        "expression `{expression}` expands to {terms} or more terms, above the limit of {max}: split it into \
         several expressions"
    )]
    /// An expansion bigger than [`MAX_UNROLLED_TERMS`](crate::table::MAX_UNROLLED_TERMS) (a fused
    /// expression is always unrolled).
    ExpressionTooBig {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The terms counted when the limit was passed.
        terms: usize,
        /// The limit.
        max: usize,
    },
    #[error(
        "`{expression}` is not linear in `{parameter}`: a linear map needs the parameter in every term of the \
         result exactly once"
    )]
    /// A linear map asked of an expression in a parameter it is not linear in.
    NotLinear {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The parameter.
        parameter: String,
    },
    #[error("`{parameter}` is not a parameter of `{expression}`: a linear map is taken in one of its parameters")]
    /// A linear map asked in a name that is not one of the expression's parameters.
    UnknownLinearParameter {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The name asked for.
        parameter: String,
    },
    #[error("the linear map of `{expression}` needs the name `{name}`, which {taken}: rename one of them")]
    /// A name emitted for an expression's linear map (its type `{Name}Map`, its function `{name}_map`) is
    /// taken: by a declared type, another expression, or another linear map.
    MapNameClash {
        /// Index into `expressions`.
        index: usize,
        /// The expression's name.
        expression: String,
        /// The name the map needs.
        name: String,
        /// What has it already.
        taken: String,
    },
    #[error("{}", several(.0))]
    /// Independent mistakes, each its own error (in different types, expressions or basis vectors), so that
    /// all of them are reported at once; never fewer than two.
    Several(Vec<Error>),
}

/// The errors, one per line.
fn several(errors: &[Error]) -> String {
    errors.iter().map(Error::to_string).collect::<Vec<_>>().join("\n")
}

/// `Ok` without errors, the error itself for one, [`Error::Several`] for more.
pub(crate) fn all(mut errors: Vec<Error>) -> Result<(), Error> {
    match errors.len() {
        0 => Ok(()),
        1 => Err(errors.remove(0)),
        _ => Err(Error::Several(errors)),
    }
}

/// The values, or every error among the results (see [`all`]).
pub(crate) fn collect<T>(results: impl IntoIterator<Item = Result<T, Error>>) -> Result<Vec<T>, Error> {
    let (values, errors): (Vec<_>, Vec<_>) = results.into_iter().partition(Result::is_ok);
    all(errors.into_iter().filter_map(Result::err).collect())?;
    Ok(values.into_iter().filter_map(Result::ok).collect())
}

impl Error {
    /// Where in the declaration the error is.
    pub fn location(&self) -> Location {
        match *self {
            Error::EmptyBasis | Error::TooManyBasisVectors { .. } | Error::NoResultType { .. } | Error::Several(_) => {
                Location::Algebra
            }
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
            Error::AllTooLarge { ty_index, .. }
            | Error::TooManyFields { ty_index, .. }
            | Error::TooMuchCode { ty_index, .. } => Location::Type(ty_index),
            Error::UnknownBlade { ty_index, item, .. }
            | Error::InvalidBladeName { ty_index, item, .. }
            | Error::DuplicateBlade { ty_index, item, .. }
            | Error::GradeOutOfRange { ty_index, item, .. } => Location::TypeItem { ty: ty_index, item },
            Error::DuplicateOperation { index, .. } => Location::Operation(index),
            Error::LoweringOfUnary { index, .. }
            | Error::LoweringNotEmitted { index, .. }
            | Error::DuplicateLowering { index, .. }
            | Error::TooBigToUnroll { index, .. } => Location::Lowering(index),
            Error::MetricSize { .. } | Error::MetricTooLarge { .. } => Location::Metric,
            Error::MetricRowLength { row, .. } => Location::MetricRow(row),
            Error::MetricNotSymmetric { row, column, .. } => Location::MetricEntry { row, column },
            Error::InvalidExpressionName { index, .. }
            | Error::DuplicateExpression { index, .. }
            | Error::NoExpressionResultType { index, .. }
            | Error::ZeroExpression { index, .. }
            | Error::ExpressionTooBig { index, .. }
            | Error::NotLinear { index, .. }
            | Error::UnknownLinearParameter { index, .. }
            | Error::MapNameClash { index, .. }
            | Error::NoClosedForm { index, .. } => Location::Expression(index),
            Error::InvalidParameterName { index, parameter, .. }
            | Error::DuplicateParameter { index, parameter, .. }
            | Error::UnknownExpressionType {
                index,
                parameter: Some(parameter),
                ..
            } => Location::ExpressionParameter {
                expression: index,
                parameter,
            },
            Error::UnknownExpressionType { index, .. } | Error::ResultDoesNotFit { index, .. } => {
                Location::ExpressionResult(index)
            }
            Error::UnknownName { index, node, .. }
            | Error::RecursiveCall { index, node, .. }
            | Error::ArgumentCount { index, node, .. }
            | Error::ArgumentDoesNotFit { index, node, .. }
            | Error::NotFusable { index, node, .. }
            | Error::TranscendentalUse { index, node, .. }
            | Error::ExpressionGradeOutOfRange { index, node, .. } => Location::ExpressionNode {
                expression: index,
                node,
            },
        }
    }
}

/// Why a name cannot be used in the emitted code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum NameProblem {
    /// Not a valid Rust identifier.
    #[error("is not a valid identifier")]
    NotAnIdentifier,
    /// A Rust keyword (strict or reserved).
    #[error("is a Rust keyword")]
    Keyword,
    /// A raw identifier (`r#…`).
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
    /// A dense slice does not have 2ⁿ coefficients, one per blade.
    #[error(
        "the {operand} has {got} coefficients, but a dense multivector of this algebra has 2^n = {expected}, \
         one per blade"
    )]
    DenseLength {
        /// Which argument: `"left operand"`, `"right operand"` or `"operand"`.
        operand: &'static str,
        /// The length it needs: 2ⁿ.
        expected: usize,
        /// The length it has.
        got: usize,
    },
}
