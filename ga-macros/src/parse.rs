//! The syntax of the `algebra!` input, parsed into an AST that keeps every token a later error may
//! need to point at. Only the shape is checked here (which settings, in which form); what the values
//! mean (scalar names, squares, blade names, operations) is checked in [`crate::validate`].

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{braced, bracketed, parenthesized, token, Attribute, Expr, Ident, LitInt, Token, Visibility};

use crate::diagnostics::{both, combine};

/// The settings a module body accepts, as error messages list them.
const SETTING_KEYS: &str = "`scalar`, `basis`, `metric`, `types`, `ops` or `features`";

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
        // A repeated setting does not stop parsing, so that every repetition is reported at once.
        let mut repeated = Vec::new();
        while !body.is_empty() {
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
        })
    }
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
