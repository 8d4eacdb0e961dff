//! Arrays of exactly `N` values, for serde: its own arrays read the first `N` and drop the rest.

use serde::Deserialize;

/// `[T; N]` from an array of exactly `N` values: serde's own arrays read the first `N` and let toml drop the rest
/// without a word (`body_point = [0.0, 0.0, 0.5, 9.0]` once meant `[0.0, 0.0, 0.5]`).
pub(crate) fn exactly<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    let values = Vec::<T>::deserialize(deserializer)?;
    let count = values.len();
    values
        .try_into()
        .map_err(|_| serde::de::Error::invalid_length(count, &format!("an array of {N}").as_str()))
}

/// [`exactly`] for an optional key.
pub(crate) fn maybe_exactly<'de, D, T, const N: usize>(deserializer: D) -> Result<Option<[T; N]>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de>,
{
    exactly(deserializer).map(Some)
}

/// `[[f64; 3]; N]`: `N` points of exactly three numbers each.
pub(crate) fn points<'de, D, const N: usize>(deserializer: D) -> Result<[[f64; 3]; N], D::Error>
where
    D: serde::Deserializer<'de>,
{
    let rows = Vec::<Vec<f64>>::deserialize(deserializer)?;
    let count = rows.len();
    let rows: Vec<[f64; 3]> = rows
        .into_iter()
        .map(|row| {
            let length = row.len();
            row.try_into()
                .map_err(|_| serde::de::Error::invalid_length(length, &"a point of 3 numbers"))
        })
        .collect::<Result<_, D::Error>>()?;
    rows.try_into()
        .map_err(|_| serde::de::Error::invalid_length(count, &format!("an array of {N} points").as_str()))
}
