//! From the AST to a [`ga_codegen::AlgebraDeclaration`] the compiler accepts. Errors the macro can
//! see on its own (scalar names, number literals, operation and feature names, attributes) are
//! reported here, all at once; the algebra's own rules are left to [`ga_codegen::Algebra::new`],
//! whose errors [`locate`] turns into `syn::Error`s at the offending tokens.

use ga_codegen::emit::DERIVED_TRAITS;
use ga_codegen::features::mint_mapping;
use ga_codegen::{
    Algebra, AlgebraDeclaration, BasisVectorDeclaration, Error, ExpressionDeclaration, Feature, Layout, Location,
    Lowering, Operation, Parameter, Rational64, ScalarType, TypeDeclaration,
};
use quote::ToTokens;
use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{BinOp, Expr, ExprBinary, ExprLit, ExprUnary, Ident, Lit, LitInt, Meta, Path, Token, UnOp};

use crate::diagnostics::{both, collect};
use crate::parse::{AlgebraInput, BasisEntry, ExpressionItem, LayoutSyntax, MetricRow, OperationEntry, TypeEntry};

/// What the macro emits: the compiler's declaration and the opt-in features.
pub struct Validated {
    pub declaration: AlgebraDeclaration,
    pub features: Vec<Feature>,
}

/// The declaration written in `input`, checked by the compiler.
pub fn validate(input: &AlgebraInput) -> syn::Result<Validated> {
    let scalar = scalar_type(&input.scalar);
    let has_metric = input.metric.is_some();
    let basis = collect(input.basis.vectors.iter().map(|entry| basis_vector(entry, has_metric)));
    let metric = input
        .metric
        .as_ref()
        .map(|metric| collect(metric.rows.iter().map(metric_row)));
    let types = collect(input.types.iter().map(|entry| type_declaration(entry, &input.scalar)));
    let operations = input
        .ops
        .as_ref()
        .map(|entries| collect(entries.iter().map(|entry| operation(&entry.name))));
    let lowering =
        collect(lowered_entries(input).map(|(entry, lowering)| Ok((operation(&entry.name)?, lowering_of(lowering)?))));
    let features = input.features.as_ref().map(feature_list).transpose();
    let (metric, operations) = (metric.transpose(), operations.transpose());
    let ((((((scalar, basis), metric), types), operations), lowering), features) = both(
        both(
            both(both(both(both(scalar, basis), metric), types), operations),
            lowering,
        ),
        features,
    )?;
    let declaration = AlgebraDeclaration {
        scalar,
        basis,
        metric,
        types,
        operations,
        lowering,
        expressions: input.expressions.iter().map(expression_declaration).collect(),
    };
    // `generate` checks this too, but checking here makes every declaration that leaves this module
    // one the compiler accepts, which the tests can see without emitting any code.
    let algebra = Algebra::new(&declaration).map_err(|error| locate(input, &error))?;
    let features: Vec<Feature> = features
        .unwrap_or_default()
        .into_iter()
        .map(|(feature, _)| feature)
        .collect();
    if let Some(mint) = input.features.iter().flatten().find(|name| *name == "mint") {
        if !algebra.types.iter().any(|ty| mint_mapping(&algebra, ty).is_some()) {
            return Err(syn::Error::new(
                mint.span(),
                "no declared type maps to a `mint` type: `mint` converts types of 2, 3 or 4 grade-1 blades \
                 of orthonormal basis vectors (`mint::Vector2`, `Vector3`, `Vector4`) and rotors \
                 `blades(scalar, e12, e13, e23)` of three orthonormal basis vectors (`mint::Quaternion`)",
            ));
        }
    }
    Ok(Validated { declaration, features })
}

/// An expression item as the compiler's declaration: names as written (raw identifiers included, for
/// the compiler to refuse), the body as parsed.
fn expression_declaration(item: &ExpressionItem) -> ExpressionDeclaration {
    ExpressionDeclaration {
        name: item.name.to_string(),
        parameters: item
            .parameters
            .iter()
            .map(|parameter| Parameter {
                name: parameter.name.to_string(),
                type_name: parameter.ty.to_string(),
            })
            .collect(),
        result: item.result.as_ref().map(Ident::to_string),
        body: item.body.clone(),
        linear: item.linear.as_ref().map(Ident::to_string),
        doc: item.doc.clone(),
    }
}

/// The features listed in `features = [...]`, each at most once.
fn feature_list(names: &Punctuated<Ident, Token![,]>) -> syn::Result<Vec<(Feature, &Ident)>> {
    let listed: Vec<Option<Feature>> = names.iter().map(|name| Feature::from_name(&name.to_string())).collect();
    collect(
        names
            .iter()
            .zip(&listed)
            .enumerate()
            .map(|(index, (name, feature))| match feature {
                None => {
                    let valid: Vec<String> = Feature::ALL.iter().map(|f| format!("`{}`", f.name())).collect();
                    Err(syn::Error::new(
                        name.span(),
                        format!("unknown feature `{name}`: expected one of {}", valid.join(", ")),
                    ))
                }
                Some(feature) if listed[..index].contains(&Some(*feature)) => Err(syn::Error::new(
                    name.span(),
                    format!("feature `{name}` is listed twice: list each feature once"),
                )),
                Some(feature) => Ok((*feature, name)),
            }),
    )
}

/// The compiler's `error` as a `syn::Error` at the tokens of `input` it is about.
pub fn locate(input: &AlgebraInput, error: &Error) -> syn::Error {
    if let Error::Several(errors) = error {
        let mut located = errors.iter().map(|error| locate(input, error));
        let mut first = located.next().expect("`Several` holds at least two errors");
        located.for_each(|next| first.combine(next));
        return first;
    }
    let message = match error {
        // The fix is in the macro's syntax, which the compiler's message cannot name.
        Error::NoResultType { operation, .. } if listed_operation(input, operation).is_some() => {
            format!("{error}, or remove `{operation}` from `ops`")
        }
        Error::NoResultType { operation, .. } => {
            format!("{error}, or list only the operations you need in `ops = [...]`, without `{operation}`")
        }
        _ => error.to_string(),
    };
    syn::Error::new_spanned(offending_tokens(input, error), message)
}

/// The name of `operation` in the `ops` list, if the list names it.
fn listed_operation<'a>(input: &'a AlgebraInput, operation: &str) -> Option<&'a Ident> {
    input
        .ops
        .iter()
        .flatten()
        .map(|entry| &entry.name)
        .find(|name| *name == operation)
}

/// The `ops` entries that choose a lowering, with it, in order (the declaration's `lowering` list).
fn lowered_entries(input: &AlgebraInput) -> impl Iterator<Item = (&OperationEntry, &Ident)> {
    input
        .ops
        .iter()
        .flatten()
        .filter_map(|entry| entry.lowering.as_ref().map(|lowering| (entry, lowering)))
}

fn lowering_of(name: &Ident) -> syn::Result<Lowering> {
    match name.to_string().as_str() {
        "table" => Ok(Lowering::Table),
        "unrolled" => Ok(Lowering::Unrolled),
        _ => Err(syn::Error::new(
            name.span(),
            format!("unknown lowering `{name}`: expected `table` or `unrolled`"),
        )),
    }
}

fn offending_tokens<'a>(input: &'a AlgebraInput, error: &Error) -> &'a dyn ToTokens {
    let module_name = &input.name;
    // An operation whose result no type holds: where it is asked for (in `ops`), or else the type
    // it is emitted for.
    if let Error::NoResultType { operation, lhs, .. } = error {
        if let Some(name) = listed_operation(input, operation) {
            return name;
        }
        if let Some(entry) = input.types.iter().find(|entry| entry.name == lhs) {
            return &entry.name;
        }
    }
    match error.location() {
        // Errors about the basis as a whole read best next to the basis.
        Location::Algebra if matches!(error, Error::EmptyBasis | Error::TooManyBasisVectors { .. }) => &input.basis.key,
        Location::Algebra => module_name,
        Location::Basis(index) => match input.basis.vectors.get(index) {
            Some(BasisEntry {
                square: Some(square), ..
            }) if matches!(error, Error::InvalidSquare { .. }) => square,
            Some(vector) => &vector.name,
            None => module_name,
        },
        Location::Metric => match &input.metric {
            Some(metric) => &metric.key,
            None => module_name,
        },
        Location::MetricRow(row) => match input.metric.as_ref().and_then(|metric| metric.rows.get(row)) {
            Some(row) => row,
            None => module_name,
        },
        Location::MetricEntry { row, column } => {
            let row = input.metric.as_ref().and_then(|metric| metric.rows.get(row));
            match row.and_then(|row| row.entries.get(column)) {
                Some(entry) => entry,
                None => module_name,
            }
        }
        Location::Type(index) => match input.types.get(index) {
            Some(entry) => &entry.name,
            None => module_name,
        },
        Location::TypeItem { ty, item } => match input.types.get(ty) {
            Some(entry) => entry.layout.item(item).unwrap_or(&entry.name),
            None => module_name,
        },
        Location::Operation(index) => match input.ops.as_ref().and_then(|entries| entries.get(index)) {
            Some(entry) => &entry.name,
            None => module_name,
        },
        Location::Lowering(index) => match lowered_entries(input).nth(index) {
            Some((_, lowering)) => lowering,
            None => module_name,
        },
        Location::Expression(index) => match input.expressions.get(index) {
            // An error about the linear map is at the parameter `#[linear(…)]` names.
            Some(ExpressionItem {
                linear: Some(linear), ..
            }) if matches!(error, Error::NotLinear { .. } | Error::UnknownLinearParameter { .. }) => linear,
            Some(item) => &item.name,
            None => module_name,
        },
        Location::ExpressionParameter { expression, parameter } => {
            let Some(item) = input.expressions.get(expression) else {
                return module_name;
            };
            match item.parameters.get(parameter) {
                Some(parameter) if matches!(error, Error::UnknownExpressionType { .. }) => &parameter.ty,
                Some(parameter) => &parameter.name,
                None => &item.name,
            }
        }
        Location::ExpressionResult(index) => match input.expressions.get(index) {
            Some(ExpressionItem {
                result: Some(result), ..
            }) => result,
            Some(item) => &item.name,
            None => module_name,
        },
        Location::ExpressionNode { expression, node } => match input.expressions.get(expression) {
            Some(item) => item.heads.get(node).map_or(&item.name as &dyn ToTokens, |head| head),
            None => module_name,
        },
    }
}

fn scalar_type(name: &Ident) -> syn::Result<ScalarType> {
    ScalarType::from_name(&name.to_string()).ok_or_else(|| {
        syn::Error::new(
            name.span(),
            format!("unknown scalar type `{name}`: expected f32 or f64"),
        )
    })
}

/// A basis vector with its square, or — when a `metric` matrix gives the squares — its name alone.
fn basis_vector(entry: &BasisEntry, has_metric: bool) -> syn::Result<BasisVectorDeclaration> {
    let square = match (&entry.square, has_metric) {
        (Some(square), false) => {
            let magnitude: i64 = square.magnitude.base10_parse()?;
            if square.minus.is_some() {
                -magnitude
            } else {
                magnitude
            }
        }
        // Not read by the compiler: the metric's diagonal is the square.
        (None, true) => 0,
        (Some(square), true) => {
            return Err(syn::Error::new_spanned(
                square,
                format!(
                    "basis vector `{}` has a square, but the `metric` matrix gives the squares: \
                     with a metric, list only the names of the basis vectors",
                    entry.name
                ),
            ))
        }
        (None, false) => {
            return Err(syn::Error::new(
                entry.name.span(),
                format!(
                    "basis vector `{0}` has no square: write `{0} = 1`, `{0} = -1` or `{0} = 0`, \
                     or give every inner product in a `metric` matrix",
                    entry.name
                ),
            ))
        }
    };
    Ok(BasisVectorDeclaration {
        name: entry.name.to_string(),
        square,
    })
}

fn metric_row(row: &MetricRow) -> syn::Result<Vec<Rational64>> {
    collect(row.entries.iter().map(rational))
}

/// A metric entry: an integer or a fraction of integers, optionally negative (`1`, `-1`, `1/2`, `-1/2`).
fn rational(entry: &Expr) -> syn::Result<Rational64> {
    let (numerator, denominator) = match entry {
        Expr::Binary(ExprBinary {
            left,
            op: BinOp::Div(_),
            right,
            ..
        }) => (signed_integer(left, entry)?, integer(right, entry)?),
        _ => (signed_integer(entry, entry)?, 1),
    };
    if denominator == 0 {
        return Err(syn::Error::new_spanned(
            entry,
            "a metric entry cannot have a zero denominator",
        ));
    }
    Ok(Rational64::new(numerator, denominator))
}

/// `n` or `-n` for an integer literal `n`; any other expression is an error at `entry`, the whole
/// metric entry it belongs to.
fn signed_integer(expression: &Expr, entry: &Expr) -> syn::Result<i64> {
    match expression {
        Expr::Unary(ExprUnary {
            op: UnOp::Neg(_),
            expr: magnitude,
            ..
        }) => Ok(-integer(magnitude, entry)?),
        _ => integer(expression, entry),
    }
}

fn integer(expression: &Expr, entry: &Expr) -> syn::Result<i64> {
    match expression {
        Expr::Lit(ExprLit { lit: Lit::Int(int), .. }) => int.base10_parse(),
        _ => Err(syn::Error::new_spanned(
            entry,
            "a metric entry must be a rational number: an integer or a fraction such as `1/2` or `-1/2`",
        )),
    }
}

fn type_declaration(entry: &TypeEntry, scalar: &Ident) -> syn::Result<TypeDeclaration> {
    let attributes = collect(
        entry
            .attrs
            .iter()
            .map(|attribute| type_attribute(&attribute.meta, scalar)),
    );
    let layout = match &entry.layout {
        LayoutSyntax::Grades(grades) => collect(grades.iter().map(|grade| grade.base10_parse())).map(Layout::Grades),
        LayoutSyntax::Blades(blades) => Ok(Layout::Blades(blades.iter().map(Ident::to_string).collect())),
        LayoutSyntax::All => Ok(Layout::All),
    };
    let (_, layout) = both(attributes, layout)?;
    Ok(TypeDeclaration {
        name: entry.name.to_string(),
        layout,
    })
}

/// Standard traits a struct of floating-point fields cannot derive.
const NOT_DERIVABLE: [&str; 3] = ["Eq", "Ord", "Hash"];

/// An attribute on a type declaration goes onto the emitted struct, except those that cannot work
/// there: `cfg` (it would remove the struct but not the operations emitted for it with the other
/// types), a derive of a trait the struct already derives or that floating-point fields cannot
/// derive, and a `repr` other than `C` (always emitted) and `align(N)`. Inside `cfg_attr`, the same
/// rules apply to each attribute it adds. Any other attribute (doc comments, derives such as
/// `serde::Serialize`, derive helpers, lint levels) is passed through for rustc to check.
fn type_attribute(meta: &Meta, scalar: &Ident) -> syn::Result<()> {
    let path = meta.path();
    if path.is_ident("cfg") {
        Err(syn::Error::new_spanned(
            meta,
            "`cfg` is not allowed on a type declaration: it would remove the struct but not the \
             operations emitted for it with the other types; put the `cfg` on the module",
        ))
    } else if path.is_ident("cfg_attr") {
        let added = meta.require_list()?.parse_args_with(|input: ParseStream| {
            input.parse::<Meta>()?;
            input.parse::<Token![,]>()?;
            Punctuated::<Meta, Token![,]>::parse_terminated(input)
        })?;
        collect(added.iter().map(|meta| type_attribute(meta, scalar))).map(drop)
    } else if path.is_ident("derive") {
        let traits = meta
            .require_list()?
            .parse_args_with(Punctuated::<Path, Token![,]>::parse_terminated)?;
        collect(traits.iter().map(|path| derived_trait(path, scalar))).map(drop)
    } else if path.is_ident("repr") {
        let hints = meta
            .require_list()?
            .parse_args_with(Punctuated::<Meta, Token![,]>::parse_terminated)?;
        collect(hints.iter().map(representation)).map(drop)
    } else {
        Ok(())
    }
}

/// A derived trait: anything but a standard trait the struct already derives or cannot derive.
fn derived_trait(path: &Path, scalar: &Ident) -> syn::Result<()> {
    let standard = path.segments.len() == 1
        || ["core", "std", "alloc"]
            .iter()
            .any(|root| path.segments.first().is_some_and(|first| first.ident == root));
    let Some(last) = path.segments.last().filter(|_| standard) else {
        return Ok(());
    };
    let name = last.ident.to_string();
    if DERIVED_TRAITS.contains(&name.as_str()) {
        Err(syn::Error::new_spanned(
            path,
            format!(
                "`{name}` is already derived for every emitted type ({}): remove it from the derive",
                DERIVED_TRAITS.map(|derived| format!("`{derived}`")).join(", ")
            ),
        ))
    } else if NOT_DERIVABLE.contains(&name.as_str()) {
        Err(syn::Error::new_spanned(
            path,
            format!("`{name}` cannot be derived: the coefficients are `{scalar}`, which does not implement `{name}`"),
        ))
    } else {
        Ok(())
    }
}

/// A `repr` hint: `C` (the struct always has it) or `align(N)`.
fn representation(hint: &Meta) -> syn::Result<()> {
    let path = hint.path();
    let name = path.to_token_stream().to_string();
    if path.is_ident("C") && matches!(hint, Meta::Path(_)) {
        Ok(())
    } else if path.is_ident("align") {
        let align = hint.require_list()?;
        align
            .parse_args_with(|input: ParseStream| input.parse::<LitInt>())
            .map(drop)
    } else if path.is_ident("packed") {
        Err(syn::Error::new_spanned(
            hint,
            "`repr(packed)` is refused: every field has the same scalar type, so the struct (always \
             `repr(C)`) has no padding to remove; packing would only lower its alignment and make \
             references to its fields (`&v.e1`) an error",
        ))
    } else if path.is_ident("transparent") {
        Err(syn::Error::new_spanned(
            hint,
            "`repr(transparent)` is refused: the emitted struct has one field per blade and is always `repr(C)`",
        ))
    } else {
        Err(syn::Error::new_spanned(
            hint,
            format!(
                "`repr({name})` does not apply to the emitted struct, which is always `repr(C)`: \
                 only `repr(C)` and `repr(align(N))` are accepted"
            ),
        ))
    }
}

fn operation(name: &Ident) -> syn::Result<Operation> {
    Operation::from_name(&name.to_string()).ok_or_else(|| {
        let valid: Vec<String> = Operation::ALL.iter().map(|op| format!("`{}`", op.name())).collect();
        syn::Error::new(
            name.span(),
            format!("unknown operation `{name}`: expected one of {}", valid.join(", ")),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn declaration(source: &str) -> syn::Result<AlgebraDeclaration> {
        validate(&syn::parse_str(source)?).map(|validated| validated.declaration)
    }

    fn messages(source: &str) -> Vec<String> {
        match declaration(source) {
            Ok(declaration) => panic!("expected errors, got {declaration:?}"),
            Err(errors) => errors.into_iter().map(|error| error.to_string()).collect(),
        }
    }

    #[test]
    fn settings_map_to_the_declaration_in_any_order() {
        let declaration = declaration(
            "pub mod pga {
                ops = [geometric, reverse];
                types {
                    /// A rigid motion.
                    Motor = grades(0, 2, 4);
                    Translator = blades(scalar, e01, e02, e03);
                    Multivector = all;
                }
                basis = [e0 = 0, e1 = 1, e2 = 1, e3 = -1];
                scalar = f32;
            }",
        )
        .unwrap();
        assert_eq!(
            declaration,
            AlgebraDeclaration {
                scalar: ScalarType::F32,
                basis: [("e0", 0), ("e1", 1), ("e2", 1), ("e3", -1)]
                    .map(|(name, square)| BasisVectorDeclaration {
                        name: name.to_string(),
                        square
                    })
                    .to_vec(),
                metric: None,
                types: vec![
                    TypeDeclaration {
                        name: "Motor".to_string(),
                        layout: Layout::Grades(vec![0, 2, 4]),
                    },
                    TypeDeclaration {
                        name: "Translator".to_string(),
                        layout: Layout::Blades(["scalar", "e01", "e02", "e03"].map(String::from).to_vec()),
                    },
                    TypeDeclaration {
                        name: "Multivector".to_string(),
                        layout: Layout::All,
                    },
                ],
                operations: Some(vec![Operation::Geometric, Operation::Reverse]),
                lowering: vec![],
                expressions: vec![],
            }
        );
    }

    #[test]
    fn permuted_blade_names_pass_through_unchanged() {
        let declaration = declaration(
            "mod vga { scalar = f64; basis = [e1 = 1, e2 = 1, e3 = 1]; types { Bivector = blades(e23, e31, e12); } }",
        )
        .unwrap();
        assert_eq!(
            declaration.types[0].layout,
            Layout::Blades(["e23", "e31", "e12"].map(String::from).to_vec())
        );
        assert_eq!(declaration.operations, None);
    }

    #[test]
    fn a_metric_gives_rational_entries_and_leaves_the_basis_names_only() {
        let declaration = declaration(
            "mod null {
                scalar = f64;
                basis = [e1, n0, ninf];
                metric = [[1, 0, 0], [0, 0, -1/2], [0, -1 / 2, 0]];
                types { Vector = grades(1); }
            }",
        )
        .unwrap();
        let (zero, one, half) = (Rational64::from(0), Rational64::from(1), Rational64::new(1, 2));
        assert_eq!(
            declaration.metric,
            Some(vec![
                vec![one, zero, zero],
                vec![zero, zero, -half],
                vec![zero, -half, zero]
            ])
        );
        let names: Vec<&str> = declaration.basis.iter().map(|v| v.name.as_str()).collect();
        assert_eq!(names, ["e1", "n0", "ninf"]);
    }

    #[test]
    fn independent_mistakes_are_reported_together() {
        let errors = messages(
            "mod bad {
                scalar = f16;
                basis = [e1 = 99999999999999999999];
                types { #[derive(Clone)] Vector = grades(1); }
                ops = [geometric, wedge];
            }",
        );
        assert_eq!(errors.len(), 4, "{errors:?}");
        assert_eq!(errors[0], "unknown scalar type `f16`: expected f32 or f64");
        assert_eq!(errors[1], "number too large to fit in target type");
        assert_eq!(
            errors[2],
            "`Clone` is already derived for every emitted type (`Clone`, `Copy`, `Debug`, `PartialEq`, \
             `Default`): remove it from the derive"
        );
        assert!(errors[3].starts_with("unknown operation `wedge`: expected one of `geometric`, `outer`"));
    }

    #[test]
    fn compiler_errors_keep_their_message() {
        let errors = messages("mod vga { scalar = f64; basis = [e1 = 1, e2 = -2]; types { Vector = grades(1); } }");
        assert_eq!(errors, ["basis vector `e2` squares to -2; a square must be 1, -1 or 0"]);
    }

    #[test]
    fn compiler_errors_point_at_the_offending_tokens() {
        let input: AlgebraInput = syn::parse_str(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = -2];
                types { Vector = grades(1); Pair = blades(e1, e3); Empty = grades(); }
                ops = [outer, reverse];
            }",
        )
        .unwrap();
        let tokens = |error: Error| offending_tokens(&input, &error).to_token_stream().to_string();
        let invalid_square = Error::InvalidSquare {
            index: 1,
            name: "e2".to_string(),
            square: -2,
        };
        assert_eq!(tokens(invalid_square), "- 2");
        let duplicate_name = Error::DuplicateBasisName {
            index: 1,
            name: "e2".to_string(),
        };
        assert_eq!(tokens(duplicate_name), "e2");
        let unknown_blade = Error::UnknownBlade {
            ty_index: 1,
            item: 1,
            ty: "Pair".to_string(),
            blade: "e3".to_string(),
            reason: String::new(),
        };
        assert_eq!(tokens(unknown_blade), "e3");
        let empty = Error::EmptyType {
            index: 2,
            name: "Empty".to_string(),
        };
        assert_eq!(tokens(empty), "Empty");
        let duplicate_operation = Error::DuplicateOperation {
            index: 1,
            name: "reverse".to_string(),
        };
        assert_eq!(tokens(duplicate_operation), "reverse");
        assert_eq!(tokens(Error::EmptyBasis), "basis");
        let no_result = Error::NoResultType {
            operation: "geometric".to_string(),
            lhs: "Vector".to_string(),
            rhs: "Vector".to_string(),
            blades: Vec::new(),
        };
        // Not the module: the type the operation is emitted for.
        assert_eq!(tokens(no_result), "Vector");
    }

    #[test]
    fn expressions_map_to_the_declaration() {
        let declaration = declaration(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = 1];
                types { Vector = grades(1); Rotor = grades(0, 2); }
                fn turned(r: Rotor, v: Vector) -> Vector = r * v * ~r;
                fn scaled(v: Vector, t: f64) = t * v / 2;
            }",
        )
        .unwrap();
        let [turned, scaled] = &declaration.expressions[..] else {
            panic!("expected two expressions: {:?}", declaration.expressions);
        };
        let parameters = |expression: &ExpressionDeclaration| -> Vec<(String, String)> {
            let named = expression.parameters.iter();
            named.map(|p| (p.name.clone(), p.type_name.clone())).collect()
        };
        assert_eq!(turned.name, "turned");
        assert_eq!(
            parameters(turned),
            [("r".into(), "Rotor".into()), ("v".into(), "Vector".into())]
        );
        assert_eq!(turned.result.as_deref(), Some("Vector"));
        assert_eq!(turned.body.to_string(), "r * v * ~r");
        assert_eq!(scaled.name, "scaled");
        assert_eq!(
            parameters(scaled),
            [("v".into(), "Vector".into()), ("t".into(), "f64".into())]
        );
        assert_eq!(scaled.result, None);
        assert_eq!(scaled.body.to_string(), "t * v * (1.0 / 2.0)");
    }

    #[test]
    fn expression_errors_point_at_the_name_parameter_result_or_node() {
        let input: AlgebraInput = syn::parse_str(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = 1];
                types { Vector = grades(1); }
                fn squared(a: Vector, b: Bivector) -> Rotor = a * b.grade_2() + c(a);
                fn plain(a: Vector) = a;
            }",
        )
        .unwrap();
        let tokens = |error: Error| offending_tokens(&input, &error).to_token_stream().to_string();
        let name = |index| (index, if index == 0 { "squared" } else { "plain" }.to_string());
        let (index, expression) = name(0);
        assert_eq!(
            tokens(Error::DuplicateExpression {
                index,
                name: expression.clone()
            }),
            "squared"
        );
        let unknown_type = |parameter| Error::UnknownExpressionType {
            index,
            parameter,
            expression: expression.clone(),
            type_name: String::new(),
            scalar: "f64".to_string(),
        };
        assert_eq!(tokens(unknown_type(Some(1))), "Bivector");
        assert_eq!(tokens(unknown_type(None)), "Rotor");
        let duplicate = Error::DuplicateParameter {
            index,
            parameter: 1,
            expression: expression.clone(),
            name: "b".to_string(),
        };
        assert_eq!(tokens(duplicate), "b");
        let does_not_fit = Error::ResultDoesNotFit {
            index,
            expression: expression.clone(),
            result: "Rotor".to_string(),
            blades: vec![],
        };
        assert_eq!(tokens(does_not_fit), "Rotor");
        // Heads in source order: a, *, b, grade_2, +, c.
        let node = |node| Error::UnknownName {
            index,
            node,
            expression: expression.clone(),
            name: String::new(),
        };
        let heads: Vec<String> = (0..6).map(|id| tokens(node(id))).collect();
        assert_eq!(heads, ["a", "*", "b", "grade_2", "+", "c"]);
        let (index, expression) = name(1);
        let too_big = Error::ExpressionTooBig {
            index,
            expression: expression.clone(),
            terms: 0,
            max: 0,
        };
        assert_eq!(tokens(too_big), "plain");
        // Without a declared result type, a result error is at the expression's name.
        let no_type = Error::NoExpressionResultType {
            index,
            expression,
            blades: vec![],
        };
        assert_eq!(tokens(no_type), "plain");
    }

    #[test]
    fn attributes_that_work_on_the_struct_pass_through() {
        let validated = validate(
            &syn::parse_str(
                "mod vga {
                    scalar = f32;
                    basis = [e1 = 1, e2 = 1];
                    types {
                        /// A direction.
                        #[derive(serde::Serialize, serde::Deserialize, bytemuck::Pod, PartialOrd)]
                        #[repr(C, align(8))]
                        #[serde(rename_all = \"UPPERCASE\")]
                        #[cfg_attr(feature = \"x\", derive(bytemuck::Zeroable), repr(C))]
                        #[allow(clippy::all)]
                        Vector = grades(1);
                    }
                }",
            )
            .unwrap(),
        );
        assert!(validated.is_ok());
    }

    #[test]
    fn attributes_that_cannot_work_are_refused_at_their_tokens() {
        let input: AlgebraInput = syn::parse_str(
            "mod vga {
                scalar = f64;
                basis = [e1 = 1, e2 = 1];
                types {
                    #[derive(serde::Serialize, std::fmt::Debug, Eq, Hash)]
                    #[repr(C, packed)]
                    #[repr(transparent)]
                    #[repr(u8)]
                    #[cfg(test)]
                    #[cfg_attr(test, derive(Default))]
                    Vector = grades(1);
                }
            }",
        )
        .unwrap();
        let errors: Vec<(String, String)> = match validate(&input) {
            Ok(_) => panic!("expected errors"),
            Err(errors) => errors
                .into_iter()
                .map(|error| {
                    let message = error.to_string();
                    (message.split(':').next().unwrap_or_default().to_string(), message)
                })
                .collect(),
        };
        let heads: Vec<&str> = errors.iter().map(|(head, _)| head.as_str()).collect();
        assert_eq!(
            heads,
            [
                "`Debug` is already derived for every emitted type (`Clone`, `Copy`, `Debug`, `PartialEq`, `Default`)",
                "`Eq` cannot be derived",
                "`Hash` cannot be derived",
                "`repr(packed)` is refused",
                "`repr(transparent)` is refused",
                "`repr(u8)` does not apply to the emitted struct, which is always `repr(C)`",
                "`cfg` is not allowed on a type declaration",
                "`Default` is already derived for every emitted type (`Clone`, `Copy`, `Debug`, `PartialEq`, `Default`)",
            ],
            "{errors:#?}"
        );
        assert_eq!(
            errors[1].1,
            "`Eq` cannot be derived: the coefficients are `f64`, which does not implement `Eq`"
        );
    }

    #[test]
    fn features_are_named_once_and_mint_needs_a_type_to_map() {
        let validated = validate(
            &syn::parse_str(
                "mod vga { scalar = f64; basis = [e1 = 1, e2 = 1, e3 = 1]; types { V = grades(1); }
                 features = [mint, display, approx]; }",
            )
            .unwrap(),
        )
        .unwrap();
        assert_eq!(validated.features, [Feature::Mint, Feature::Display, Feature::Approx]);
        assert_eq!(
            messages("mod vga { scalar = f64; basis = [e1 = 1]; types { V = grades(1); } features = [serde, display, display]; }"),
            [
                "unknown feature `serde`: expected one of `display`, `approx`, `mint`",
                "feature `display` is listed twice: list each feature once",
            ]
        );
        let pga = messages(
            "mod pga { scalar = f64; basis = [e0 = 0, e1 = 1, e2 = 1, e3 = 1]; types { Plane = grades(1); }
             features = [mint]; }",
        );
        assert_eq!(pga.len(), 1);
        assert!(pga[0].starts_with("no declared type maps to a `mint` type"), "{pga:?}");
    }

    #[test]
    fn a_missing_result_type_points_at_the_operation_or_the_type() {
        let source = |ops: &str| {
            format!(
                "mod vga {{ scalar = f64; basis = [e1 = 1, e2 = 1]; types {{ Scalar = blades(scalar); Vector = grades(1); }} {ops} }}"
            )
        };
        let no_result = Error::NoResultType {
            operation: "geometric".to_string(),
            lhs: "Vector".to_string(),
            rhs: "Vector".to_string(),
            blades: vec!["scalar".to_string(), "e12".to_string()],
        };
        let listed: AlgebraInput = syn::parse_str(&source("ops = [reverse, geometric];")).unwrap();
        let error = locate(&listed, &no_result);
        assert_eq!(
            offending_tokens(&listed, &no_result).to_token_stream().to_string(),
            "geometric"
        );
        assert!(
            error.to_string().ends_with(", or remove `geometric` from `ops`"),
            "{error}"
        );
        let unlisted: AlgebraInput = syn::parse_str(&source("")).unwrap();
        let error = locate(&unlisted, &no_result);
        assert_eq!(
            offending_tokens(&unlisted, &no_result).to_token_stream().to_string(),
            "Vector"
        );
        assert!(
            error
                .to_string()
                .ends_with(", or list only the operations you need in `ops = [...]`, without `geometric`"),
            "{error}"
        );
    }

    /// Mistakes in different types, expressions or basis vectors are all reported, each at its own tokens,
    /// whether the macro or the compiler finds them.
    #[test]
    fn independent_mistakes_in_different_items_are_reported_together() {
        let algebra = |items: &str| format!("mod a {{ scalar = f64; basis = [e1 = 1, e2 = 1]; {items} }}");
        let cases: [(&str, &[&str]); 4] = [
            (
                "types { V = blades(e5); W = blades(e6); }",
                &["unknown blade `e5`", "unknown blade `e6`"],
            ),
            (
                "types { V = grades(1); } fn f(a: X) -> V = a; fn g(a: Y) -> V = a;",
                &["unknown type `X`", "unknown type `Y`"],
            ),
            (
                "types { V = grades(1); } fn f(a: V) -> V = a; fn f(a: V) -> V = a; fn g(a: V, a: V) -> V = a;",
                &[
                    "expression `f` is declared twice",
                    "parameter `a` of expression `g` is declared twice",
                ],
            ),
            ("types { V = grades(3); W = grades(1, 1); }", &["grade 3", "`grade 1`"]),
        ];
        for (items, expected) in cases {
            let found = messages(&algebra(items));
            assert_eq!(found.len(), expected.len(), "{found:?}");
            for (message, part) in found.iter().zip(expected) {
                assert!(message.contains(part), "{message} should name {part}");
            }
        }
        // Found while emitting: unknown names in two bodies.
        let input: AlgebraInput = syn::parse_str(&algebra(
            "ops = [reverse]; types { V = grades(1); } fn f(a: V) -> V = b; fn g(a: V) -> V = c;",
        ))
        .unwrap();
        let errors = crate::expand::expand(&input, &validate(&input).unwrap()).unwrap_err();
        let found: Vec<String> = errors.into_iter().map(|error| error.to_string()).collect();
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].contains("`b`") && found[1].contains("`c`"), "{found:?}");
    }
}
