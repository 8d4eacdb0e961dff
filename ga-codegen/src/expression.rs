//! Named expressions over the declared types, e.g. `fn moved_line(m: Motor, l: Line) -> Line = m * l * ~m;`:
//! what a user declares to have the compiler fuse a whole formula into one function (see [`crate::fuse`]).
//!
//! The syntax tree is the compiler's own, independent of any front end; each node carries an id that the
//! front end chose, so that an error about a node (an unknown name, a call with the wrong arguments) can
//! point back at its tokens ([`crate::Location::ExpressionNode`]).

use num_rational::Rational64;

use crate::operation::Operation;

/// `fn name(parameter: Type, …) -> Result = body;`
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExpressionDeclaration {
    /// The emitted function's name.
    pub name: String,
    /// The parameters, in order.
    pub parameters: Vec<Parameter>,
    /// The declared result type (a type name, or the scalar type's name for a bare scalar); `None` takes
    /// the smallest declared type holding the result's blades.
    pub result: Option<String>,
    /// The formula.
    pub body: Expression,
    /// A parameter the formula is linear in, to also emit the formula as a matrix in it (see
    /// [`crate::fuse::linear_map`]): a type `{Name}Map` built by `{name}_map(other parameters)`, with `apply`.
    pub linear: Option<String>,
    /// The user's documentation of the function (`///` lines in `algebra!`), emitted above the generated notes.
    pub doc: Option<String>,
}

/// `name: Type`: a declared type's name, or the scalar type's (`t: f64`, a scalar on the blade `1`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The parameter's name.
    pub name: String,
    /// The name of its type.
    pub type_name: String,
}

/// A node of an expression with the front end's id for it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expression {
    /// Chosen by the front end, reported back in errors about this node.
    pub id: usize,
    /// What the node computes.
    pub kind: ExpressionKind,
}

/// What an expression node computes. Binary products are the blade-pair products of [`Operation`]
/// (`*` geometric, `^` outer, `&` regressive, `|` left contraction, or any product by name as a method);
/// every one is linear in each operand, so a whole expression is a polynomial in its parameters' fields.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ExpressionKind {
    /// A parameter.
    Parameter(String),
    /// A scalar constant (a literal, exact: `0.5` is 1/2).
    Scalar(Rational64),
    /// `-x`.
    Negate(Box<Expression>),
    /// `a + b`, or `a - b` when `subtract`.
    Sum {
        /// The left summand.
        lhs: Box<Expression>,
        /// The right summand.
        rhs: Box<Expression>,
        /// Whether `rhs` is subtracted.
        subtract: bool,
    },
    /// A unary operation: `~x` (reverse), `x.involute()`, `x.norm_squared()`, … (not `inverse`: it divides).
    Unary(Operation, Box<Expression>),
    /// `x.grade_k()`: the grade-`k` part.
    Grade(u32, Box<Expression>),
    /// A binary operation: `a * b`, `a.sandwich(x)`, … (not `transform`, which assumes a unit versor).
    Binary(Operation, Box<Expression>, Box<Expression>),
    /// A call of another declared expression (by name), its body inlined.
    Call(String, Vec<Expression>),
}

impl Expression {
    /// A node with id 0: for building expressions in code, where no front end needs the ids.
    ///
    /// ```
    /// use ga_codegen::expression::{Expression, ExpressionKind};
    /// use ga_codegen::Operation;
    ///
    /// let name = |n: &str| Expression::new(ExpressionKind::Parameter(n.into()));
    /// // m * l * ~m
    /// let reverse = Expression::new(ExpressionKind::Unary(Operation::Reverse, Box::new(name("m"))));
    /// let left = Expression::new(ExpressionKind::Binary(Operation::Geometric, Box::new(name("m")), Box::new(name("l"))));
    /// let moved = Expression::new(ExpressionKind::Binary(Operation::Geometric, Box::new(left), Box::new(reverse)));
    /// assert_eq!(moved.to_string(), "m * l * ~m");
    /// ```
    pub fn new(kind: ExpressionKind) -> Self {
        Expression { id: 0, kind }
    }

    /// The node's operands, left to right.
    pub fn children(&self) -> Vec<&Expression> {
        match &self.kind {
            ExpressionKind::Parameter(_) | ExpressionKind::Scalar(_) => Vec::new(),
            ExpressionKind::Negate(x) | ExpressionKind::Unary(_, x) | ExpressionKind::Grade(_, x) => vec![x],
            ExpressionKind::Sum { lhs, rhs, .. } | ExpressionKind::Binary(_, lhs, rhs) => vec![lhs, rhs],
            ExpressionKind::Call(_, arguments) => arguments.iter().collect(),
        }
    }

    /// How tightly the node binds when printed, as in Rust: operands of a weaker operator get parentheses.
    fn precedence(&self) -> u8 {
        match &self.kind {
            ExpressionKind::Binary(Operation::LeftContraction, ..) => 1,
            ExpressionKind::Binary(Operation::Outer, ..) => 2,
            ExpressionKind::Binary(Operation::Regressive, ..) => 3,
            ExpressionKind::Sum { .. } => 4,
            ExpressionKind::Binary(Operation::Geometric, ..) => 5,
            ExpressionKind::Negate(_) | ExpressionKind::Unary(Operation::Reverse, _) => 6,
            _ => 7,
        }
    }
}

impl Expression {
    /// A sum as its terms with their signs, `a - b + c`, however the tree groups them (front ends balance long
    /// sums): `negated` when the terms are subtracted, `first` for the sum's first term (written without `+`).
    fn write_terms(&self, f: &mut std::fmt::Formatter<'_>, negated: bool, first: bool) -> std::fmt::Result {
        if let ExpressionKind::Sum { lhs, rhs, subtract } = &self.kind {
            lhs.write_terms(f, negated, first)?;
            return rhs.write_terms(f, negated != *subtract, false);
        }
        match (first, negated) {
            (true, false) => {}
            (true, true) => write!(f, "-")?,
            (false, _) => write!(f, " {} ", if negated { '-' } else { '+' })?,
        }
        // A term binding looser than a sum, or a negated first term binding looser than negation, is grouped.
        let bound = if first && negated { 6 } else { 4 };
        match self.precedence() < bound {
            true => write!(f, "({self})"),
            false => write!(f, "{self}"),
        }
    }
}

/// The operator that writes `operation` in an expression, if any.
pub fn operator(operation: Operation) -> Option<&'static str> {
    match operation {
        Operation::Geometric => Some("*"),
        Operation::Outer => Some("^"),
        Operation::Regressive => Some("&"),
        Operation::LeftContraction => Some("|"),
        _ => None,
    }
}

/// The functions generated in closed form ([`crate::transcendental`]), which an [`ExpressionKind::Call`] may name
/// besides the declared expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    /// `exp(b)` of a bivector.
    Exp,
    /// `log(m)` of a unit even element.
    Log,
    /// `sqrt(m)` of a unit even element.
    Sqrt,
    /// `normalized(m)`: `m` scaled so that `m ~m = 1`.
    Normalized,
}

impl Function {
    /// All of them.
    pub const ALL: [Function; 4] = [Function::Exp, Function::Log, Function::Sqrt, Function::Normalized];

    /// The name used in expressions.
    pub fn name(self) -> &'static str {
        match self {
            Function::Exp => "exp",
            Function::Log => "log",
            Function::Sqrt => "sqrt",
            Function::Normalized => "normalized",
        }
    }

    /// The function called `name`, if any.
    ///
    /// ```
    /// use ga_codegen::expression::Function;
    ///
    /// assert_eq!(Function::named("exp"), Some(Function::Exp));
    /// assert_eq!(Function::named("sin"), None);
    /// ```
    pub fn named(name: &str) -> Option<Function> {
        Function::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// The function an expression's whole body calls, if its body is a call of one of [`Function::ALL`].
pub fn called(declared: &ExpressionDeclaration) -> Option<Function> {
    match &declared.body.kind {
        ExpressionKind::Call(name, _) => Function::named(name),
        _ => None,
    }
}

impl std::fmt::Display for Expression {
    /// Rust syntax with Rust's precedence (left-associative binary operators), parenthesised only
    /// where needed: the formula a fused function's documentation quotes.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let operand = |f: &mut std::fmt::Formatter<'_>, child: &Expression, tighter: bool| {
            let own = self.precedence();
            if child.precedence() < own || (tighter && child.precedence() == own) {
                write!(f, "({child})")
            } else {
                write!(f, "{child}")
            }
        };
        match &self.kind {
            ExpressionKind::Parameter(name) => write!(f, "{name}"),
            ExpressionKind::Scalar(value) => match value.is_integer() {
                true => write!(f, "{}.0", value.numer()),
                false => write!(f, "({}.0 / {}.0)", value.numer(), value.denom()),
            },
            ExpressionKind::Negate(x) => {
                write!(f, "-")?;
                operand(f, x, false)
            }
            ExpressionKind::Unary(Operation::Reverse, x) => {
                write!(f, "~")?;
                operand(f, x, false)
            }
            ExpressionKind::Unary(operation, x) => {
                operand(f, x, false)?;
                write!(f, ".{}()", operation.name())
            }
            ExpressionKind::Grade(k, x) => {
                operand(f, x, false)?;
                write!(f, ".grade_{k}()")
            }
            ExpressionKind::Sum { .. } => self.write_terms(f, false, true),
            ExpressionKind::Binary(operation, lhs, rhs) => match operator(*operation) {
                Some(symbol) => {
                    operand(f, lhs, false)?;
                    write!(f, " {symbol} ")?;
                    operand(f, rhs, true)
                }
                None => {
                    operand(f, lhs, false)?;
                    write!(f, ".{}({rhs})", operation.name())
                }
            },
            ExpressionKind::Call(name, arguments) => {
                write!(f, "{name}(")?;
                for (index, argument) in arguments.iter().enumerate() {
                    if index > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{argument}")?;
                }
                write!(f, ")")
            }
        }
    }
}
