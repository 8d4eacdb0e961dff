//! Basis blades as bitmasks over the user's basis vectors, their canonical order and their names.
//!
//! Bit `i` set means basis vector `i` (in declaration order) is a factor; the blade is the product of
//! its vectors in increasing bit order (`e13`, never `e31`), as in the reference data.

/// A basis blade: bit `i` set means basis vector `i` is a factor.
pub type BladeMask = u32;

/// At most this many basis vectors: blades are `u32` masks.
pub const MAX_DIMENSION: usize = 32;

/// The grade (number of vector factors) of a blade.
pub fn grade(blade: BladeMask) -> u32 {
    blade.count_ones()
}

/// The sign from reordering the product of blades `a` and `b` into canonical (increasing) order:
/// (−1) to the number of pairs (i ∈ a, j ∈ b) with i > j.
pub fn reorder_sign(a: BladeMask, b: BladeMask) -> i64 {
    let mut swaps = 0;
    let mut shifted = a >> 1;
    while shifted != 0 {
        swaps += (shifted & b).count_ones();
        shifted >>= 1;
    }
    if swaps.is_multiple_of(2) {
        1
    } else {
        -1
    }
}

/// All blades of an `n`-dimensional algebra in canonical order: by grade, then lexicographically by
/// the indices of their factors (e.g. `1, e0, e1, e2, e01, e02, e12, e012` for n = 3).
pub fn canonical_blades(n: usize) -> Vec<BladeMask> {
    let mut blades = Vec::with_capacity(1 << n);
    for k in 0..=n as u32 {
        blades.extend(blades_of_grade(n, k));
    }
    blades
}

/// The blades of grade `k` in lexicographic order of their factor indices.
pub fn blades_of_grade(n: usize, k: u32) -> Vec<BladeMask> {
    fn extend(out: &mut Vec<BladeMask>, n: usize, first: usize, remaining: u32, mask: BladeMask) {
        if remaining == 0 {
            out.push(mask);
            return;
        }
        for index in first..n {
            extend(out, n, index + 1, remaining - 1, mask | (1 << index));
        }
    }
    let mut out = Vec::new();
    extend(&mut out, n, 0, k, 0);
    out
}

/// How blade names are formed from basis vector names.
///
/// If every basis name is a common alphabetic prefix followed by one character (`e0`, `e1`, …),
/// a blade joins the characters: `e01`, `e123`. If the suffixes are longer (`e1`, …, `e12`, or
/// `e1`, `einf`), they are joined with `_`: `e1_12`, `e1_inf`. Without a common prefix the whole
/// names are joined with `_`: `n0_ninf`. The grade-0 blade is called `scalar`.
#[derive(Clone, Debug)]
pub struct BladeNaming {
    prefix: String,
    /// The part of each basis name after the prefix (the whole name when the prefix is empty).
    suffixes: Vec<String>,
    separator: &'static str,
}

/// The name of the grade-0 blade.
pub const SCALAR_NAME: &str = "scalar";

impl BladeNaming {
    /// The naming for basis vectors with these names, in bit order: finds their common alphabetic prefix and the separator.
    ///
    /// ```
    /// use ga_codegen::blade::BladeNaming;
    ///
    /// // One character after the common prefix `e`: factors are joined directly.
    /// let euclidean = BladeNaming::new(&["e1", "e2", "e3"].map(String::from));
    /// assert_eq!(euclidean.name(0b101), "e13");
    /// assert_eq!(euclidean.parse("e31"), Ok((0b101, -1))); // e31 = −e13
    ///
    /// // Longer suffixes (`inf`) are joined with `_`.
    /// let conformal = BladeNaming::new(&["e1", "e2", "e3", "eo", "einf"].map(String::from));
    /// assert_eq!(conformal.name(0b10001), "e1_inf");
    /// assert_eq!(conformal.name(0), "scalar");
    /// ```
    pub fn new(basis_names: &[String]) -> Self {
        // The longest alphabetic prefix shared by every name that leaves each a non-empty suffix.
        let mut prefix: String = match basis_names.first() {
            Some(first) => first.chars().take_while(|c| c.is_ascii_alphabetic()).collect(),
            None => String::new(),
        };
        while !basis_names
            .iter()
            .all(|name| name.starts_with(&prefix) && name.len() > prefix.len())
        {
            prefix.pop();
        }
        let suffixes: Vec<String> = basis_names
            .iter()
            .map(|name| name[prefix.len()..].to_string())
            .collect();
        let single_characters = !prefix.is_empty() && suffixes.iter().all(|s| s.chars().count() == 1);
        BladeNaming {
            prefix,
            suffixes,
            separator: if single_characters { "" } else { "_" },
        }
    }

    /// The canonical name of a blade (`scalar`, `e0`, `e01`, …).
    pub fn name(&self, blade: BladeMask) -> String {
        if blade == 0 {
            return SCALAR_NAME.to_string();
        }
        let parts: Vec<&str> = (0..self.suffixes.len())
            .filter(|i| blade & (1 << i) != 0)
            .map(|i| self.suffixes[i].as_str())
            .collect();
        format!("{}{}", self.prefix, parts.join(self.separator))
    }

    /// The string between the names of two basis vectors in a blade name: empty (`e12`) or `_`.
    pub fn separator(&self) -> &'static str {
        self.separator
    }

    /// Parses a blade name, possibly with its factors permuted (`e31`), into the canonical blade and
    /// the sign such that `name = sign · canonical blade`.
    pub fn parse(&self, name: &str) -> Result<(BladeMask, i64), String> {
        if name == SCALAR_NAME {
            return Ok((0, 1));
        }
        let indices = self.factors(name)?;
        let mut mask: BladeMask = 0;
        for &index in &indices {
            mask |= 1 << index;
        }
        // The sign of the permutation that sorts the factors: (−1)^(number of inversions).
        let inversions = (0..indices.len())
            .flat_map(|i| (i + 1..indices.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| indices[i] > indices[j]);
        let sign = if inversions.count().is_multiple_of(2) { 1 } else { -1 };
        Ok((mask, sign))
    }

    /// The basis vectors (indices, in written order, none repeated) whose outer product `name`
    /// names, reading it without the special case of `scalar`.
    pub fn factors(&self, name: &str) -> Result<Vec<usize>, String> {
        let Some(rest) = name.strip_prefix(self.prefix.as_str()) else {
            return Err(format!("blade names start with `{}`", self.prefix));
        };
        let pieces: Vec<String> = if self.separator.is_empty() {
            rest.chars().map(String::from).collect()
        } else {
            rest.split(self.separator).map(String::from).collect()
        };
        if pieces.is_empty() || pieces.iter().any(String::is_empty) {
            return Err(self.expected());
        }
        let mut indices: Vec<usize> = Vec::with_capacity(pieces.len());
        for piece in &pieces {
            match self.suffixes.iter().position(|s| s == piece) {
                Some(index) => indices.push(index),
                None => {
                    return Err(format!(
                        "`{}{piece}` is not a basis vector; {}",
                        self.prefix,
                        self.expected()
                    ))
                }
            }
        }
        for (position, &index) in indices.iter().enumerate() {
            if indices[..position].contains(&index) {
                return Err(format!(
                    "it repeats the basis vector `{}{}`",
                    self.prefix, self.suffixes[index]
                ));
            }
        }
        Ok(indices)
    }

    /// The non-zero blade whose canonical name is exactly `name`, if any (`e12` but not `e21`).
    /// Names no blade should have (`scalar`, keywords) are looked up this way, without listing 2ⁿ
    /// names.
    pub fn canonical_blade(&self, name: &str) -> Option<BladeMask> {
        let indices = self.factors(name).ok()?;
        let mask = indices.iter().fold(0, |mask, &index| mask | (1 << index));
        (self.name(mask) == name).then_some(mask)
    }

    fn expected(&self) -> String {
        let examples: Vec<String> = (0..self.suffixes.len().min(3)).map(|i| self.name(1 << i)).collect();
        let pair = if self.suffixes.len() >= 2 {
            format!(", `{}`", self.name(3))
        } else {
            String::new()
        };
        format!(
            "expected `{SCALAR_NAME}` or factors of the basis, e.g. `{}`{pair}",
            examples.join("`, `")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn canonical_order_is_grade_then_lexicographic() {
        let naming = BladeNaming::new(&names(&["e0", "e1", "e2", "e3"]));
        let listed: Vec<String> = canonical_blades(4).into_iter().map(|b| naming.name(b)).collect();
        assert_eq!(
            listed,
            [
                "scalar", "e0", "e1", "e2", "e3", "e01", "e02", "e03", "e12", "e13", "e23", "e012", "e013", "e023",
                "e123", "e0123"
            ]
        );
    }

    #[test]
    fn permuted_names_carry_the_permutation_sign() {
        let naming = BladeNaming::new(&names(&["e1", "e2", "e3"]));
        assert_eq!(naming.parse("e31"), Ok((0b101, -1)));
        assert_eq!(naming.parse("e312"), Ok((0b111, 1)));
        assert_eq!(naming.parse("e213"), Ok((0b111, -1)));
        assert!(naming.parse("e11").unwrap_err().contains("repeats"));
        assert!(naming.parse("e4").is_err());
    }

    #[test]
    fn long_suffixes_are_joined_with_underscores() {
        let naming = BladeNaming::new(&names(&["e1", "e2", "e3", "eo", "einf"]));
        assert_eq!(naming.name(0b10001), "e1_inf");
        assert_eq!(naming.parse("einf_1"), Ok((0b10001, -1)));
        let unrelated = BladeNaming::new(&names(&["x", "n0"]));
        assert_eq!(unrelated.name(0b11), "x_n0");
        // The shared prefix is found even when the first name has more letters.
        let letters = BladeNaming::new(&names(&["ea", "eb", "en", "ec"]));
        assert_eq!(letters.name(0b1011), "eabc");
        assert_eq!(letters.parse("eba"), Ok((0b11, -1)));
    }

    #[test]
    fn reorder_sign_counts_swaps() {
        // e2 e1 = −e12; e12 e1 = −e1 e12... = −e2 (after contracting e1e1): the swap count is 1.
        assert_eq!(reorder_sign(0b10, 0b01), -1);
        assert_eq!(reorder_sign(0b01, 0b10), 1);
        assert_eq!(reorder_sign(0b011, 0b001), -1);
    }
}
