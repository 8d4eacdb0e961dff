// A general even element of Cl(4,1) has an `m ~m` whose 4-vector part need not square to a scalar or commute with
// m, so `normalized` (and `sqrt`, which is `normalized(1 + m)`) has no closed form there; `exp` and `log` do.
ga_macros::algebra! {
    mod conformal {
        scalar = f64;
        basis = [e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = -1];
        types { Bivector = grades(2); Even = grades(0, 2, 4); Multivector = all; }
        ops = [geometric];
        fn exp_bivector(b: Bivector) -> Even = exp(b);
        fn normalized_even(m: Even) -> Even = normalized(m);
    }
}

fn main() {}
