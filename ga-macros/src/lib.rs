//! The `algebra!` macro (placeholder until the front end lands).
use proc_macro::TokenStream;

#[proc_macro]
pub fn algebra(input: TokenStream) -> TokenStream {
    input
}
