//! The syntax of the `algebra!` input, parsed into an AST that keeps every token a later error may
//! need to point at. Only the shape is checked here (which settings, in which form; the grammar of
//! expressions, with their methods and number literals); what the values mean (scalar names, squares,
//! blade names, operations, the names in expressions) is checked in [`crate::validate`] and by the
//! compiler.

use ga_codegen::{Expression, ExpressionKind, Operation, Rational64};
use proc_macro2::{TokenStream, TokenTree};
use quote::ToTokens;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{
    braced, bracketed, parenthesized, token, Attribute, Expr, ExprLit, Ident, Lit, LitInt, Meta, MetaNameValue, Token,
    Visibility,
};

use crate::diagnostics::{both, combine};

/// The settings a module body accepts, as error messages list them.
const SETTING_KEYS: &str = "`scalar`, `basis`, `metric`, `types`, `ops`, `features` or `fn` (a fused expression)";

/// `#[attributes] visibility mod name { settings }`.
pub struct AlgebraInput {
    /// Kept on the emitted module (doc comments, lint levels, cfgs).
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub mod_token: Token![mod],
    pub name: Ident,
    /// `scalar = f64;`
    pub scalar: Ident,
    /// `basis = [e0 = 0, e1 = 1];`, or names only (`basis = [n0, ninf];`) with a `metric`.
    pub basis: BasisSetting,
    /// `metric = [[0, -1], [-1, 0]];`, if present.
    pub metric: Option<MetricSetting>,
    /// `types { Motor = grades(0, 2, 4); … }`
    pub types: Vec<TypeEntry>,
    /// `ops = [geometric, reverse, sandwich(table)];`, if present.
    pub ops: Option<Punctuated<OperationEntry, Token![,]>>,
    /// `features = [display, approx, mint];`, if present.
    pub features: Option<Punctuated<Ident, Token![,]>>,
    /// `fn moved(m: Motor, p: Point) -> Point = m * p * ~m;`, in order.
    pub expressions: Vec<ExpressionItem>,
}

/// An operation in `ops`, optionally with how to lower it: `sandwich(table)`, `geometric(unrolled)`.
pub struct OperationEntry {
    pub name: Ident,
    pub lowering: Option<Ident>,
}

impl Parse for OperationEntry {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name = input.parse()?;
        let lowering = if input.peek(token::Paren) {
            let inner;
            parenthesized!(inner in input);
            let lowering = inner.parse()?;
            if !inner.is_empty() {
                return Err(inner.error("expected one lowering: `table` or `unrolled`"));
            }
            Some(lowering)
        } else {
            None
        };
        Ok(OperationEntry { name, lowering })
    }
}

/// The `basis` setting. Its key is kept as the place to report errors about the basis as a whole
/// (empty, too many vectors).
pub struct BasisSetting {
    pub key: Ident,
    pub vectors: Punctuated<BasisEntry, Token![,]>,
}

/// `name = square`, e.g. `e0 = 0` or `e4 = -1`; just `name` when a `metric` gives the squares.
pub struct BasisEntry {
    pub name: Ident,
    pub square: Option<SquareLiteral>,
}

/// The `metric` setting: the rows of B(eᵢ, eⱼ). Its key is where errors about the matrix as a whole
/// (its size, its magnitude) are reported.
pub struct MetricSetting {
    pub key: Ident,
    pub rows: Punctuated<MetricRow, Token![,]>,
}

/// One bracketed row of the metric. Entries are parsed as expressions so that anything that is not a
/// rational number (`0.5`, `x`) is reported at its own span by [`crate::validate`].
pub struct MetricRow {
    pub bracket: token::Bracket,
    pub entries: Punctuated<Expr, Token![,]>,
}

/// An integer literal with an optional minus sign; its tokens span both so that an error covers `-2`.
pub struct SquareLiteral {
    pub minus: Option<Token![-]>,
    pub magnitude: LitInt,
}

/// `Name = layout;` with the attributes (doc comments, derives, …) written before it.
pub struct TypeEntry {
    pub attrs: Vec<Attribute>,
    pub name: Ident,
    pub layout: LayoutSyntax,
}

/// How a type entry lists its blades.
pub enum LayoutSyntax {
    /// `grades(0, 2, 4)`
    Grades(Punctuated<LitInt, Token![,]>),
    /// `blades(scalar, e01, e02)`
    Blades(Punctuated<Ident, Token![,]>),
    /// `all`
    All,
}

impl LayoutSyntax {
    /// The tokens of the `index`-th grade or blade, if the layout lists that many.
    pub fn item(&self, index: usize) -> Option<&dyn ToTokens> {
        match self {
            LayoutSyntax::Grades(grades) => grades.get(index).map(|grade| grade as &dyn ToTokens),
            LayoutSyntax::Blades(blades) => blades.get(index).map(|blade| blade as &dyn ToTokens),
            LayoutSyntax::All => None,
        }
    }
}

impl Parse for AlgebraInput {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis = input.parse()?;
        let mod_token = input.parse()?;
        let name: Ident = input.parse()?;
        let body;
        braced!(body in input);

        let mut scalar = None;
        let mut basis = None;
        let mut metric = None;
        let mut types = None;
        let mut ops = None;
        let mut features = None;
        let mut expressions = Vec::new();
        // A repeated setting or a malformed expression does not stop parsing, so that every one is
        // reported at once.
        let mut repeated = Vec::new();
        while !body.is_empty() {
            if body.peek(Token![fn]) || body.peek(Token![#]) {
                match body.parse() {
                    Ok(expression) => expressions.push(expression),
                    Err(error) => {
                        repeated.push(error);
                        skip_past_semicolon(&body)?;
                    }
                }
                continue;
            }
            if !body.peek(Ident) {
                return Err(body.error(format!("expected a setting: {SETTING_KEYS}")));
            }
            let key: Ident = body.parse()?;
            let error = match key.to_string().as_str() {
                "scalar" => {
                    body.parse::<Token![=]>()?;
                    let value = body.parse()?;
                    body.parse::<Token![;]>()?;
                    store(&mut scalar, value, &key)
                }
                "basis" => {
                    let vectors = assigned_list(&body, BasisEntry::parse)?;
                    let setting = BasisSetting {
                        key: key.clone(),
                        vectors,
                    };
                    store(&mut basis, setting, &key)
                }
                "metric" => {
                    let rows = assigned_list(&body, MetricRow::parse)?;
                    let setting = MetricSetting { key: key.clone(), rows };
                    store(&mut metric, setting, &key)
                }
                "types" => {
                    let block;
                    braced!(block in body);
                    let mut entries = Vec::new();
                    while !block.is_empty() {
                        entries.push(block.parse()?);
                    }
                    store(&mut types, entries, &key)
                }
                "ops" => {
                    let names = assigned_list(&body, OperationEntry::parse)?;
                    store(&mut ops, names, &key)
                }
                "features" => {
                    let names = assigned_list(&body, Ident::parse)?;
                    store(&mut features, names, &key)
                }
                _ => {
                    return Err(syn::Error::new(
                        key.span(),
                        format!("unknown setting `{key}`: expected {SETTING_KEYS}"),
                    ))
                }
            };
            repeated.extend(error);
        }

        let scalar = required(scalar, &name, "scalar", "scalar = f64;");
        let basis = required(basis, &name, "basis", "basis = [e1 = 1, e2 = 1, e3 = 1];");
        let types = required(types, &name, "types", "types { Vector = grades(1); }");
        let (((scalar, basis), types), ()) = both(both(both(scalar, basis), types), combine(repeated))?;
        Ok(AlgebraInput {
            attrs,
            vis,
            mod_token,
            name,
            scalar,
            basis,
            metric,
            types,
            ops,
            features,
            expressions,
        })
    }
}

/// Skips the rest of an item that failed to parse, up to and including its `;`.
fn skip_past_semicolon(input: ParseStream) -> syn::Result<()> {
    input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tree, next)) = rest.token_tree() {
            rest = next;
            if matches!(&tree, TokenTree::Punct(punct) if punct.as_char() == ';') {
                break;
            }
        }
        Ok(((), rest))
    })
}

/// `= [item, item, …];`
fn assigned_list<T>(
    input: ParseStream,
    parse_item: fn(ParseStream) -> syn::Result<T>,
) -> syn::Result<Punctuated<T, Token![,]>> {
    input.parse::<Token![=]>()?;
    let list;
    bracketed!(list in input);
    let items = list.parse_terminated(parse_item, Token![,])?;
    input.parse::<Token![;]>()?;
    Ok(items)
}

/// Stores the first occurrence of a setting; a second one is an error at its key.
fn store<T>(slot: &mut Option<T>, value: T, key: &Ident) -> Option<syn::Error> {
    if slot.is_some() {
        return Some(syn::Error::new(
            key.span(),
            format!("`{key}` is set twice: each setting may appear only once"),
        ));
    }
    *slot = Some(value);
    None
}

fn required<T>(setting: Option<T>, module: &Ident, key: &str, example: &str) -> syn::Result<T> {
    setting.ok_or_else(|| {
        syn::Error::new(
            module.span(),
            format!("algebra `{module}` has no `{key}` setting: add one, e.g. `{example}`"),
        )
    })
}

impl Parse for BasisEntry {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name = input.parse()?;
        let square = if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            Some(input.parse()?)
        } else {
            None
        };
        Ok(BasisEntry { name, square })
    }
}

impl Parse for MetricRow {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let row;
        let bracket = bracketed!(row in input);
        let entries = row.parse_terminated(Expr::parse, Token![,])?;
        Ok(MetricRow { bracket, entries })
    }
}

impl ToTokens for MetricRow {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        self.bracket.surround(tokens, |inner| self.entries.to_tokens(inner));
    }
}

impl Parse for SquareLiteral {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        Ok(SquareLiteral {
            minus: input.parse()?,
            magnitude: input.parse()?,
        })
    }
}

impl ToTokens for SquareLiteral {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        self.minus.to_tokens(tokens);
        self.magnitude.to_tokens(tokens);
    }
}

impl Parse for TypeEntry {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let name = input.parse()?;
        input.parse::<Token![=]>()?;
        let layout = input.parse()?;
        input.parse::<Token![;]>()?;
        Ok(TypeEntry { attrs, name, layout })
    }
}

impl Parse for LayoutSyntax {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        const EXPECTED: &str = "expected a layout: `grades(…)`, `blades(…)` or `all`";
        if !input.peek(Ident) {
            return Err(input.error(EXPECTED));
        }
        let keyword: Ident = input.parse()?;
        match keyword.to_string().as_str() {
            "grades" => {
                let list;
                parenthesized!(list in input);
                Ok(LayoutSyntax::Grades(list.parse_terminated(LitInt::parse, Token![,])?))
            }
            "blades" => {
                let list;
                parenthesized!(list in input);
                Ok(LayoutSyntax::Blades(list.parse_terminated(Ident::parse, Token![,])?))
            }
            "all" => Ok(LayoutSyntax::All),
            _ => Err(syn::Error::new(keyword.span(), EXPECTED)),
        }
    }
}

/// `fn name(parameter: Type, …) [-> Type] = body;`: a named expression, fused by the compiler into one
/// function. The body is parsed into the compiler's own syntax tree; every node's id indexes `heads`.
pub struct ExpressionItem {
    /// From `#[linear(l)]`: the parameter to also emit the expression's matrix in.
    pub linear: Option<Ident>,
    /// The `///` lines above the expression, one per line, for the emitted function.
    pub doc: Option<String>,
    pub name: Ident,
    pub parameters: Punctuated<ParameterSyntax, Token![,]>,
    /// The declared result type, if any.
    pub result: Option<Ident>,
    pub body: Expression,
    /// By node id: the token that heads the node (its operator, method name, literal or name), where
    /// an error about the node points.
    pub heads: Vec<TokenStream>,
}

/// `name: Type`, the type being a declared type's name or the scalar type.
pub struct ParameterSyntax {
    pub name: Ident,
    pub ty: Ident,
}

impl Parse for ParameterSyntax {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name = input.parse()?;
        input.parse::<Token![:]>()?;
        if !input.peek(Ident) {
            return Err(input.error("expected a type: a declared type's name or the scalar type"));
        }
        let ty = input.parse()?;
        Ok(ParameterSyntax { name, ty })
    }
}

impl Parse for ExpressionItem {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let mut linear = None;
        let mut doc: Vec<String> = Vec::new();
        for attribute in input.call(Attribute::parse_outer)? {
            let refused = || {
                syn::Error::new_spanned(
                    &attribute,
                    "an expression accepts `///` documentation and one attribute, `#[linear(parameter)]` (emit its \
                     matrix in that parameter)",
                )
            };
            if let Meta::NameValue(MetaNameValue {
                path,
                value: Expr::Lit(ExprLit {
                    lit: Lit::Str(text), ..
                }),
                ..
            }) = &attribute.meta
            {
                if path.is_ident("doc") {
                    let line = text.value();
                    doc.push(line.strip_prefix(' ').unwrap_or(&line).to_owned());
                    continue;
                }
            }
            if !attribute.path().is_ident("linear") || linear.is_some() {
                return Err(refused());
            }
            linear = Some(attribute.parse_args::<Ident>().map_err(|_| refused())?);
        }
        if !input.peek(Token![fn]) {
            return Err(input.error("expected `fn`: attributes in an algebra are only accepted on expressions"));
        }
        input.parse::<Token![fn]>()?;
        let name = input.parse()?;
        let list;
        parenthesized!(list in input);
        let parameters = list.parse_terminated(ParameterSyntax::parse, Token![,])?;
        let result = if input.peek(Token![->]) {
            input.parse::<Token![->]>()?;
            if !input.peek(Ident) {
                return Err(input.error("expected the result type: a declared type's name or the scalar type"));
            }
            Some(input.parse()?)
        } else {
            None
        };
        if input.peek(token::Brace) {
            return Err(input.error("an expression's body follows `=`, without braces: `fn f(a: T) -> T = a * a;`"));
        }
        input.parse::<Token![=]>()?;
        let mut parser = BodyParser::default();
        let body = parser.expression(input, 0)?;
        input.parse::<Token![;]>()?;
        Ok(ExpressionItem {
            linear,
            doc: (!doc.is_empty()).then(|| doc.join("\n")),
            name,
            parameters,
            result,
            body,
            heads: parser.heads,
        })
    }
}

/// The operators an expression accepts, as error messages list them.
const OPERATORS: &str = "`*`, `^`, `&`, `|`, `+`, `-` or `/`";

/// Operators of Rust that are not operators of expressions, though they begin with one.
const COMPOUND_OPERATORS: [&str; 10] = ["||", "&&", "|=", "&=", "^=", "+=", "-=", "*=", "/=", "->"];

/// A binary operator of expressions, with its precedence (higher binds tighter; all associate to
/// the left): Rust's, so that an expression means what the same text means with the emitted
/// operator impls.
#[derive(Clone, Copy)]
enum BinaryOperator {
    /// `|`, the left contraction.
    LeftContraction,
    /// `^`, the outer product.
    Outer,
    /// `&`, the regressive product.
    Regressive,
    /// `+`.
    Add,
    /// `-`.
    Subtract,
    /// `*`, the geometric product.
    Geometric,
    /// `/`, by a number literal only: the product with its reciprocal.
    Divide,
}

impl BinaryOperator {
    fn precedence(self) -> u8 {
        match self {
            BinaryOperator::LeftContraction => 1,
            BinaryOperator::Outer => 2,
            BinaryOperator::Regressive => 3,
            BinaryOperator::Add | BinaryOperator::Subtract => 4,
            BinaryOperator::Geometric | BinaryOperator::Divide => 5,
        }
    }
}

/// Builds an expression's syntax tree, numbering its nodes in the order of their head tokens.
#[derive(Default)]
struct BodyParser {
    heads: Vec<TokenStream>,
    /// By node id: the depth of the subtree the node heads.
    depths: Vec<usize>,
    /// How many recursive calls of the parser are open.
    nesting: usize,
}

/// The deepest an expression may nest, in levels of the parser's recursion or of the syntax tree: every
/// pass of the compiler walks the tree recursively, and a proc macro runs on rustc's stack (8 MiB). A
/// debug build of the macro takes 8–16 KiB per level, so 128 levels use at most a quarter of it; sums of any
/// length nest only log₂ n levels (see `balanced_sum`).
pub const MAX_NESTING: usize = 128;

/// A term of a sum after its first, with the `+` or `-` before it (`id` is the operator's node).
struct Summand {
    id: usize,
    subtract: bool,
    term: Expression,
}

impl BodyParser {
    /// A fresh node id, for the node headed by `head`.
    fn id(&mut self, head: &dyn ToTokens) -> usize {
        self.heads.push(head.to_token_stream());
        self.heads.len() - 1
    }

    /// An expression whose binary operators all bind at least as tightly as `min_precedence`
    /// (precedence climbing); it ends before `;`, `,` or the end of its group.
    fn expression(&mut self, input: ParseStream, min_precedence: u8) -> syn::Result<Expression> {
        let mut lhs = self.nested(input, Self::prefix)?;
        // The terms of a run of `+` and `-` after `lhs`, summed as a balanced tree when the run ends.
        let mut summands = Vec::new();
        while let Some(operator) = peek_binary_operator(input)? {
            if operator.precedence() < min_precedence {
                break;
            }
            let head: TokenTree = input.parse()?;
            let id = self.id(&head);
            if let BinaryOperator::Add | BinaryOperator::Subtract = operator {
                summands.push(Summand {
                    id,
                    subtract: matches!(operator, BinaryOperator::Subtract),
                    term: self.expression(input, operator.precedence() + 1)?,
                });
                continue;
            }
            // Every operator binding tighter than `+` went into the last summand: this one binds looser.
            lhs = self.balanced_sum(lhs, std::mem::take(&mut summands))?;
            let kind = match operator {
                BinaryOperator::Divide => {
                    let divisor = self.divisor(input)?;
                    ExpressionKind::Binary(Operation::Geometric, Box::new(lhs), Box::new(divisor))
                }
                _ => {
                    let rhs = Box::new(self.expression(input, operator.precedence() + 1)?);
                    let lhs = Box::new(lhs);
                    match operator {
                        BinaryOperator::LeftContraction => ExpressionKind::Binary(Operation::LeftContraction, lhs, rhs),
                        BinaryOperator::Outer => ExpressionKind::Binary(Operation::Outer, lhs, rhs),
                        BinaryOperator::Regressive => ExpressionKind::Binary(Operation::Regressive, lhs, rhs),
                        BinaryOperator::Geometric => ExpressionKind::Binary(Operation::Geometric, lhs, rhs),
                        BinaryOperator::Add | BinaryOperator::Subtract | BinaryOperator::Divide => {
                            unreachable!("handled above")
                        }
                    }
                }
            };
            lhs = self.node(id, kind)?;
        }
        self.balanced_sum(lhs, summands)
    }

    /// `first ± summands[0] ± …` as a balanced tree of [`ExpressionKind::Sum`], so that a sum of n terms nests
    /// log₂ n levels deep, not n. The value is the same (the compiler's arithmetic is exact): the right half
    /// is added or subtracted as a whole, as its first term was, its other signs flipped when subtracted.
    fn balanced_sum(&mut self, first: Expression, mut summands: Vec<Summand>) -> syn::Result<Expression> {
        if summands.is_empty() {
            return Ok(first);
        }
        let mut right = summands.split_off(summands.len() / 2);
        let Summand { id, subtract, term } = right.remove(0);
        for summand in &mut right {
            summand.subtract ^= subtract;
        }
        let lhs = Box::new(self.balanced_sum(first, summands)?);
        let rhs = Box::new(self.balanced_sum(term, right)?);
        self.node(id, ExpressionKind::Sum { lhs, rhs, subtract })
    }

    /// The node `kind` headed by node id `id`; refused when it nests more than [`MAX_NESTING`] levels deep,
    /// so that the tree's depth stays bounded while it is built (even dropping a deeper tree recurses).
    fn node(&mut self, id: usize, kind: ExpressionKind) -> syn::Result<Expression> {
        let node = Expression { id, kind };
        let depth = 1 + node
            .children()
            .iter()
            .map(|child| self.depths[child.id])
            .max()
            .unwrap_or(0);
        if depth > MAX_NESTING {
            return Err(syn::Error::new_spanned(
                &self.heads[id],
                format!(
                    "expression nested more than {MAX_NESTING} operations deep (a chain of `*`, `^`, `&`, `|` or \
                     method calls nests one level per operation): split it into declared expressions that call \
                     each other"
                ),
            ));
        }
        self.depths.resize(self.heads.len(), 0);
        self.depths[id] = depth;
        Ok(node)
    }

    /// `parse(input)`, one level deeper in the parser's recursion: refused beyond [`MAX_NESTING`] levels,
    /// where the compiler's own recursion over the tree would overflow rustc's stack.
    fn nested(
        &mut self,
        input: ParseStream,
        parse: fn(&mut Self, ParseStream) -> syn::Result<Expression>,
    ) -> syn::Result<Expression> {
        if self.nesting == MAX_NESTING {
            return Err(input.error(format!(
                "expression nested more than {MAX_NESTING} levels deep (parentheses, prefix operators, call \
                 arguments): split it into declared expressions that call each other"
            )));
        }
        self.nesting += 1;
        let parsed = parse(self, input);
        self.nesting -= 1;
        parsed
    }

    /// `-x`, `~x` (the reverse) or a postfix expression.
    fn prefix(&mut self, input: ParseStream) -> syn::Result<Expression> {
        if input.peek(Token![-]) {
            let minus: Token![-] = input.parse()?;
            let id = self.id(&minus);
            let operand = self.nested(input, Self::prefix)?;
            self.node(id, ExpressionKind::Negate(Box::new(operand)))
        } else if input.peek(Token![~]) {
            let tilde: Token![~] = input.parse()?;
            let id = self.id(&tilde);
            let operand = self.nested(input, Self::prefix)?;
            self.node(id, ExpressionKind::Unary(Operation::Reverse, Box::new(operand)))
        } else {
            self.postfix(input)
        }
    }

    /// A primary expression followed by method calls: `x.grade_2()`, `x.involute()`, `a.outer(b)`.
    fn postfix(&mut self, input: ParseStream) -> syn::Result<Expression> {
        let mut receiver = self.primary(input)?;
        while input.peek(Token![.]) && !input.peek(Token![..]) {
            input.parse::<Token![.]>()?;
            if !input.peek(Ident) {
                return Err(input.error("expected a method name after `.`, such as `grade_2`, `reverse` or `outer`"));
            }
            let method: Ident = input.parse()?;
            let id = self.id(&method);
            if !input.peek(token::Paren) {
                return Err(syn::Error::new(
                    method.span(),
                    format!("expected a method call `.{method}(…)`: expressions have no fields"),
                ));
            }
            let list;
            parenthesized!(list in input);
            let arguments = self.arguments(&list)?;
            receiver = self.node(id, method_call(&method, receiver, arguments)?)?;
        }
        Ok(receiver)
    }

    /// A number, a parameter, a call of another expression or a parenthesised expression.
    fn primary(&mut self, input: ParseStream) -> syn::Result<Expression> {
        if input.peek(token::Paren) {
            let inner;
            parenthesized!(inner in input);
            let expression = self.expression(&inner, 0)?;
            if !inner.is_empty() {
                return Err(inner.error("expected `)`: parentheses hold one expression"));
            }
            Ok(expression)
        } else if input.peek(Lit) {
            let (literal, value) = number(input)?;
            let id = self.id(&literal);
            self.node(id, ExpressionKind::Scalar(value))
        } else if input.peek(Ident) {
            let name: Ident = input.parse()?;
            let id = self.id(&name);
            let kind = if input.peek(token::Paren) {
                let list;
                parenthesized!(list in input);
                ExpressionKind::Call(name.to_string(), self.arguments(&list)?)
            } else {
                ExpressionKind::Parameter(name.to_string())
            };
            self.node(id, kind)
        } else if input.peek(Token![!]) {
            Err(input.error("`!` is not an operator of expressions: the reverse is `~x`, the negation `-x`"))
        } else if input.is_empty() || input.peek(Token![;]) || input.peek(Token![,]) {
            Err(input.error("expected an expression"))
        } else {
            Err(input.error("expected an expression: a parameter, a number, a call `f(…)`, `(…)`, `-x` or `~x`"))
        }
    }

    /// The arguments of a call or method call: expressions separated by commas.
    fn arguments(&mut self, list: ParseStream) -> syn::Result<Vec<Expression>> {
        let mut arguments = Vec::new();
        while !list.is_empty() {
            arguments.push(self.expression(list, 0)?);
            if list.is_empty() {
                break;
            }
            list.parse::<Token![,]>()?;
        }
        Ok(arguments)
    }

    /// What follows `/`: a number literal, optionally negative, as its reciprocal.
    fn divisor(&mut self, input: ParseStream) -> syn::Result<Expression> {
        let minus: Option<Token![-]> = input.parse()?;
        if !input.peek(Lit) {
            return Err(input.error(
                "`/` divides only by a number literal, such as `x / 2.0`: a division by anything else \
                 would not be a polynomial in the parameters, which is what an expression fuses",
            ));
        }
        let (literal, value) = number(input)?;
        let head = quote::quote!(#minus #literal);
        if value == Rational64::from(0) {
            return Err(syn::Error::new_spanned(&head, "division by zero"));
        }
        let reciprocal = if minus.is_some() { -value.recip() } else { value.recip() };
        let id = self.id(&head);
        self.node(id, ExpressionKind::Scalar(reciprocal))
    }
}

/// The binary operator `input` starts with, if it starts with one; `None` at the end of an
/// expression (`;`, `,` or the end of a group); an error at any other token.
fn peek_binary_operator(input: ParseStream) -> syn::Result<Option<BinaryOperator>> {
    if input.is_empty() || input.peek(Token![;]) || input.peek(Token![,]) {
        return Ok(None);
    }
    if let Some((text, tokens)) = compound_operator(input) {
        return Err(syn::Error::new_spanned(
            tokens,
            format!("`{text}` is not an operator of expressions: expected an operator {OPERATORS}"),
        ));
    }
    let operator = if input.peek(Token![|]) {
        BinaryOperator::LeftContraction
    } else if input.peek(Token![^]) {
        BinaryOperator::Outer
    } else if input.peek(Token![&]) {
        BinaryOperator::Regressive
    } else if input.peek(Token![+]) {
        BinaryOperator::Add
    } else if input.peek(Token![-]) {
        BinaryOperator::Subtract
    } else if input.peek(Token![*]) {
        BinaryOperator::Geometric
    } else if input.peek(Token![/]) {
        BinaryOperator::Divide
    } else {
        return Err(input.error(format!("expected an operator {OPERATORS}")));
    };
    Ok(Some(operator))
}

/// The two-character Rust operator (`&&`, `||`, `+=`, …) `input` starts with, if any, and its tokens.
fn compound_operator(input: ParseStream) -> Option<(&'static str, TokenStream)> {
    let (first, rest) = input.cursor().punct()?;
    let (second, _) = rest.punct()?;
    if first.spacing() != proc_macro2::Spacing::Joint {
        return None;
    }
    let text = format!("{}{}", first.as_char(), second.as_char());
    let compound = COMPOUND_OPERATORS.into_iter().find(|operator| *operator == text)?;
    Some((compound, quote::quote!(#first #second)))
}

/// The node of a method call `receiver.method(arguments)`.
fn method_call(method: &Ident, receiver: Expression, mut arguments: Vec<Expression>) -> syn::Result<ExpressionKind> {
    let name = method.to_string();
    let receiver = Box::new(receiver);
    let given = match arguments.len() {
        1 => "1 is given".to_string(),
        count => format!("{count} are given"),
    };
    let count_error =
        |expected: &str| syn::Error::new(method.span(), format!("`{name}` takes {expected}, but {given}"));
    if let Some(grade) = name.strip_prefix("grade_").and_then(grade_number) {
        return match arguments.is_empty() {
            true => Ok(ExpressionKind::Grade(grade, receiver)),
            false => Err(count_error("no argument")),
        };
    }
    match Operation::from_name(&name).filter(|operation| *operation != Operation::Grade) {
        Some(operation) if operation.is_binary() => match (arguments.pop(), arguments.is_empty()) {
            (Some(argument), true) => Ok(ExpressionKind::Binary(operation, receiver, Box::new(argument))),
            _ => Err(count_error("one argument")),
        },
        Some(operation) if arguments.is_empty() => Ok(ExpressionKind::Unary(operation, receiver)),
        Some(_) => Err(count_error("no argument")),
        None => {
            let methods: Vec<String> = Operation::ALL
                .iter()
                .filter(|operation| **operation != Operation::Grade)
                .map(|operation| match operation.is_binary() {
                    true => format!("`{}(x)`", operation.name()),
                    false => format!("`{}()`", operation.name()),
                })
                .collect();
            Err(syn::Error::new(
                method.span(),
                format!(
                    "unknown method `{name}`: expected `grade_k()` (e.g. `grade_2()`) or one of {}",
                    methods.join(", ")
                ),
            ))
        }
    }
}

/// `k` in `grade_k`: decimal digits only.
fn grade_number(digits: &str) -> Option<u32> {
    match digits.bytes().all(|byte| byte.is_ascii_digit()) {
        true => digits.parse().ok(),
        false => None,
    }
}

/// An integer or float literal (no suffix) as the exact rational it writes: `0.5` is 1/2, `1e-3`
/// is 1/1000.
fn number(input: ParseStream) -> syn::Result<(Lit, Rational64)> {
    let literal: Lit = input.parse()?;
    let (digits, suffix) = match &literal {
        Lit::Int(int) => (int.base10_digits(), int.suffix()),
        Lit::Float(float) => (float.base10_digits(), float.suffix()),
        _ => {
            return Err(syn::Error::new_spanned(
                &literal,
                "expected a number: expressions take integer and decimal literals, such as `2` or `0.5`",
            ))
        }
    };
    if !suffix.is_empty() {
        return Err(syn::Error::new_spanned(
            &literal,
            format!("remove the suffix `{suffix}`: a number in an expression has the scalar type"),
        ));
    }
    let value = exact_rational(digits).ok_or_else(|| {
        syn::Error::new_spanned(
            &literal,
            "this number is not exactly a rational with a 64-bit numerator and denominator: \
             use fewer significant digits or a smaller exponent",
        )
    })?;
    Ok((literal, value))
}

/// The exact value of decimal digits such as `12`, `0.5`, `1.25e-3` or `2e10`, if its reduced
/// numerator and denominator fit in an `i64`.
fn exact_rational(digits: &str) -> Option<Rational64> {
    let (mantissa, exponent) = match digits.find(['e', 'E']) {
        Some(at) => (&digits[..at], digits[at + 1..].parse::<i32>().ok()?),
        None => (digits, 0),
    };
    let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let significant = format!("{whole}{fraction}");
    let significant = significant.trim_start_matches('0');
    if significant.is_empty() {
        return Some(Rational64::from(0));
    }
    // Trailing zeros move into the exponent, so that `0.50` or `1000e-3` need no large numbers.
    let trimmed = significant.trim_end_matches('0');
    let scale = i64::from(exponent) - fraction.len() as i64 + (significant.len() - trimmed.len()) as i64;
    let numerator: u128 = trimmed.parse().ok()?;
    let power = |exponent: i64| 10u128.checked_pow(u32::try_from(exponent).ok()?);
    let (mut numerator, mut denominator) = match scale >= 0 {
        true => (numerator.checked_mul(power(scale)?)?, 1),
        false => (numerator, power(-scale)?),
    };
    let divisor = gcd(numerator, denominator);
    numerator /= divisor;
    denominator /= divisor;
    Some(Rational64::new(
        i64::try_from(numerator).ok()?,
        i64::try_from(denominator).ok()?,
    ))
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn item(source: &str) -> syn::Result<ExpressionItem> {
        syn::parse_str(source)
    }

    /// The body of `fn f(…) = <body>;` fully parenthesised, in prefix form.
    fn tree(body: &str) -> String {
        let item = item(&format!("fn f() = {body};")).unwrap();
        prefix_form(&item.body)
    }

    fn prefix_form(expression: &Expression) -> String {
        match &expression.kind {
            ExpressionKind::Parameter(name) => name.clone(),
            ExpressionKind::Scalar(value) => value.to_string(),
            ExpressionKind::Negate(x) => format!("(neg {})", prefix_form(x)),
            ExpressionKind::Sum { lhs, rhs, subtract } => {
                let operator = if *subtract { "-" } else { "+" };
                format!("({operator} {} {})", prefix_form(lhs), prefix_form(rhs))
            }
            ExpressionKind::Unary(operation, x) => format!("({} {})", operation.name(), prefix_form(x)),
            ExpressionKind::Grade(k, x) => format!("(grade_{k} {})", prefix_form(x)),
            ExpressionKind::Binary(operation, lhs, rhs) => {
                format!("({} {} {})", operation.name(), prefix_form(lhs), prefix_form(rhs))
            }
            ExpressionKind::Call(name, arguments) => {
                let arguments: Vec<String> = arguments.iter().map(prefix_form).collect();
                format!("({name} {})", arguments.join(" "))
            }
        }
    }

    fn error(body: &str) -> String {
        match item(&format!("fn f(a: V, b: V) = {body};")) {
            Ok(item) => panic!("expected an error, got {}", prefix_form(&item.body)),
            Err(error) => error.to_string(),
        }
    }

    #[test]
    fn binary_operators_have_rusts_precedence_and_products_associate_to_the_left() {
        assert_eq!(
            tree("a | b ^ c & d + e * f"),
            "(left_contraction a (outer b (regressive c (+ d (geometric e f)))))"
        );
        assert_eq!(
            tree("a * b + c & d ^ e | f"),
            "(left_contraction (outer (regressive (+ (geometric a b) c) d) e) f)"
        );
        // Sums are balanced (see `long_sums_nest_logarithmically_…`): the same value as `((a - b) + c) - d`.
        assert_eq!(tree("a - b + c - d"), "(+ (- a b) (- c d))");
        assert_eq!(tree("a ^ b ^ c"), "(outer (outer a b) c)");
        assert_eq!(tree("a * (b + c)"), "(geometric a (+ b c))");
        assert_eq!(tree("a | (b | c)"), "(left_contraction a (left_contraction b c))");
    }

    #[test]
    fn prefix_operators_bind_tighter_than_binary_ones_and_methods_tighter_still() {
        assert_eq!(tree("-a * ~b"), "(geometric (neg a) (reverse b))");
        assert_eq!(tree("m * l * ~m"), "(geometric (geometric m l) (reverse m))");
        assert_eq!(tree("-a.grade_2()"), "(neg (grade_2 a))");
        assert_eq!(tree("~-a"), "(reverse (neg a))");
        assert_eq!(tree("a - -b"), "(- a (neg b))");
        assert_eq!(tree("(a + b).grade_0()"), "(grade_0 (+ a b))");
        assert_eq!(
            tree("a.outer(b + c).norm_squared().involute()"),
            "(involute (norm_squared (outer a (+ b c))))"
        );
        assert_eq!(tree("a.sandwich(b).transform(c)"), "(transform (sandwich a b) c)");
        assert_eq!(tree("a.inverse()"), "(inverse a)");
        assert_eq!(tree("2.0.grade_0()"), "(grade_0 2)");
    }

    #[test]
    fn division_is_by_a_literal_and_multiplies_by_its_reciprocal() {
        assert_eq!(tree("a * b / 2"), "(geometric (geometric a b) 1/2)");
        assert_eq!(tree("a / -0.25 + b"), "(+ (geometric a -4) b)");
        assert_eq!(tree("a + b / 4 * c"), "(+ a (geometric (geometric b 1/4) c))");
        assert!(error("a / b").starts_with("`/` divides only by a number literal"));
        assert!(error("a / (2.0)").starts_with("`/` divides only by a number literal"));
        assert_eq!(error("a / 0"), "division by zero");
    }

    #[test]
    fn calls_take_any_number_of_arguments() {
        assert_eq!(tree("f(a, g(b), h())"), "(f a (g b) (h ))");
        assert_eq!(tree("f(a,)"), "(f a)");
    }

    #[test]
    fn literals_are_exact_rationals() {
        let value = |literal: &str| tree(literal);
        assert_eq!(value("2"), "2");
        assert_eq!(value("0.5"), "1/2");
        assert_eq!(value("1e-3"), "1/1000");
        assert_eq!(value("2.5E2"), "250");
        assert_eq!(value("12.50"), "25/2");
        assert_eq!(value("1_000.000_1"), "10000001/10000");
        assert_eq!(value("0.0"), "0");
        assert_eq!(value("0e-400"), "0");
        assert_eq!(value("0x10"), "16");
        assert_eq!(value("9223372036854775807"), "9223372036854775807");
        assert_eq!(value("1e18"), "1000000000000000000");
        assert_eq!(value("1e-18"), "1/1000000000000000000");
        assert_eq!(value("0.500000000000000000000000000000000000000000"), "1/2");
        assert_eq!(value("1000000000000000000000e-20"), "10");
        for inexact in ["9223372036854775808", "1e19", "1e-19", "0.1234567890123456789", "1e400"] {
            assert!(
                error(inexact).starts_with("this number is not exactly a rational"),
                "{inexact}"
            );
        }
        assert!(error("2.0f32").starts_with("remove the suffix `f32`"));
        assert!(error("\"2\"").starts_with("expected a number"));
        assert!(error("true").starts_with("expected a number"));
    }

    #[test]
    fn other_rust_operators_and_bad_methods_are_refused_at_their_tokens() {
        for operator in ["&&", "||", "+=", "*=", "->"] {
            assert_eq!(
                error(&format!("a {operator} b")),
                format!("`{operator}` is not an operator of expressions: expected an operator `*`, `^`, `&`, `|`, `+`, `-` or `/`")
            );
        }
        for token in ["%", "==", "<", ".."] {
            assert_eq!(
                error(&format!("a {token} b")),
                "expected an operator `*`, `^`, `&`, `|`, `+`, `-` or `/`",
                "{token}"
            );
        }
        assert!(error("!a").starts_with("`!` is not an operator of expressions"));
        assert!(error("*a").starts_with("expected an expression: a parameter"));
        assert_eq!(error("a +"), "expected an expression");
        assert!(error("a.dual()").starts_with("unknown method `dual`: expected `grade_k()`"));
        assert!(error("a.grade()").starts_with("unknown method `grade`"));
        assert!(error("a.grade_x()").starts_with("unknown method `grade_x`"));
        assert_eq!(error("a.reverse(b)"), "`reverse` takes no argument, but 1 is given");
        assert_eq!(error("a.grade_1(b, b)"), "`grade_1` takes no argument, but 2 are given");
        assert_eq!(error("a.outer()"), "`outer` takes one argument, but 0 are given");
        assert_eq!(error("a.outer(b, b)"), "`outer` takes one argument, but 2 are given");
        assert!(error("a.e1").starts_with("expected a method call `.e1(…)`"));
        assert!(error("(a, b)").starts_with("expected `)`"));
    }

    #[test]
    fn node_ids_follow_the_head_tokens_in_source_order() {
        let item = item("fn moved(m: Motor, l: Line) -> Line = m * l * ~m.grade_2();").unwrap();
        let heads: Vec<String> = item.heads.iter().map(ToString::to_string).collect();
        assert_eq!(heads, ["m", "*", "l", "*", "~", "m", "grade_2"]);
        // The root is the second `*`; every id indexes its own head.
        assert_eq!(item.body.id, 3);
        let mut ids = Vec::new();
        let mut pending = vec![&item.body];
        while let Some(node) = pending.pop() {
            ids.push(node.id);
            match &node.kind {
                ExpressionKind::Negate(x) | ExpressionKind::Unary(_, x) | ExpressionKind::Grade(_, x) => {
                    pending.push(x)
                }
                ExpressionKind::Sum { lhs, rhs, .. } | ExpressionKind::Binary(_, lhs, rhs) => {
                    pending.extend([lhs.as_ref(), rhs.as_ref()])
                }
                ExpressionKind::Call(_, arguments) => pending.extend(arguments),
                ExpressionKind::Parameter(_) | ExpressionKind::Scalar(_) => {}
            }
        }
        ids.sort_unstable();
        assert_eq!(ids, (0..heads.len()).collect::<Vec<_>>());
        let names: Vec<String> = item
            .parameters
            .iter()
            .map(|p| format!("{}: {}", p.name, p.ty))
            .collect();
        assert_eq!(names, ["m: Motor", "l: Line"]);
        assert_eq!(item.result.unwrap(), "Line");
    }

    #[test]
    fn the_result_type_is_optional() {
        let item = item("fn moved(m: Motor, p: Point) = m * p * ~m;").unwrap();
        assert!(item.result.is_none());
        assert_eq!(item.body.to_string(), "m * p * ~m");
    }

    #[test]
    fn every_malformed_expression_is_reported_and_the_settings_still_parse() {
        let errors = match syn::parse_str::<AlgebraInput>(
            "mod vga {
                fn f(a: V) -> V = a && a;
                scalar = f64;
                fn g(a: V) -> V = a / a;
                fn h(a: V) -> V = a;
                basis = [e1 = 1];
                types { V = grades(1); }
                fn k(a: V) -> V = a.dual();
            }",
        ) {
            Ok(_) => panic!("expected errors"),
            Err(errors) => errors.into_iter().map(|error| error.to_string()).collect::<Vec<_>>(),
        };
        assert_eq!(errors.len(), 3, "{errors:?}");
        assert!(errors[0].starts_with("`&&` is not an operator"));
        assert!(errors[1].starts_with("`/` divides only by a number literal"));
        assert!(errors[2].starts_with("unknown method `dual`"));
    }

    fn depth(expression: &Expression) -> usize {
        1 + expression.children().into_iter().map(depth).max().unwrap_or(0)
    }

    #[test]
    fn long_sums_nest_logarithmically_and_keep_their_terms_and_signs() {
        for body in ["a - b + c - d - e + f", "-a - (b - c) + d * e - f | g", "a + b - c"] {
            let item = item(&format!("fn f() = {body};")).unwrap();
            assert_eq!(item.body.to_string(), body.replace("(b - c)", "b + c"));
        }
        assert_eq!(tree("a - b - c + d"), "(- (- a b) (- c d))");
        let terms: Vec<String> = (0..100_000).map(|i| format!("a{}", i % 7)).collect();
        let item = item(&format!("fn f() = {};", terms.join(" - "))).unwrap();
        assert_eq!(depth(&item.body), 18);
        assert_eq!(item.body.to_string(), terms.join(" - "));
    }

    #[test]
    fn expressions_nested_too_deep_are_refused_at_the_token_that_goes_too_deep() {
        let chain = |operator: &str, count: usize| vec!["a"; count].join(operator);
        let at_limit = item(&format!("fn f() = {};", chain(" * ", MAX_NESTING / 2 + 1))).unwrap();
        assert_eq!(depth(&at_limit.body), MAX_NESTING / 2 + 1);
        let long = 1 + MAX_NESTING;
        for body in [
            chain(" * ", long + 1),
            chain(" | ", long + 1),
            format!("a{}", ".reverse()".repeat(long)),
            format!("{}a", "-".repeat(1000)),
            format!("{}a{}", "(".repeat(1000), ")".repeat(1000)),
            format!("{}a{}", "f(".repeat(1000), ")".repeat(1000)),
        ] {
            let message = item(&format!("fn f() = {body};")).err().expect("refused").to_string();
            assert!(
                message.starts_with(&format!("expression nested more than {MAX_NESTING}")),
                "{message}"
            );
        }
    }
}
