//! Combining errors, so that one expansion reports every independent mistake in the input, each at
//! its own span, instead of only the first.

/// Both values, or every error among the two.
pub fn both<A, B>(first: syn::Result<A>, second: syn::Result<B>) -> syn::Result<(A, B)> {
    match (first, second) {
        (Ok(first), Ok(second)) => Ok((first, second)),
        (Err(mut first), Err(second)) => {
            first.combine(second);
            Err(first)
        }
        (Err(error), Ok(_)) | (Ok(_), Err(error)) => Err(error),
    }
}

/// Every value, or every error. Unlike `Iterator::collect`, keeps going after the first error.
pub fn collect<T>(results: impl IntoIterator<Item = syn::Result<T>>) -> syn::Result<Vec<T>> {
    let mut values = Vec::new();
    let mut errors: Option<syn::Error> = None;
    for result in results {
        match (result, &mut errors) {
            (Ok(value), _) => values.push(value),
            (Err(error), Some(all)) => all.combine(error),
            (Err(error), None) => errors = Some(error),
        }
    }
    errors.map_or(Ok(values), Err)
}

/// `Ok` if there are no errors, otherwise all of them.
pub fn combine(errors: impl IntoIterator<Item = syn::Error>) -> syn::Result<()> {
    collect(errors.into_iter().map(Err::<(), _>)).map(drop)
}
