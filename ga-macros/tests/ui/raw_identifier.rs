// Raw identifiers are refused as type, basis and blade names: the emitted code forms other names
// from them (`geometric_r#type` is no identifier).
ga_macros::algebra! {
    mod raw_type {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            r#type = grades(1);
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    mod raw_basis {
        scalar = f64;
        basis = [e1 = 1, r#e2 = 1];
        types {
            Multivector = all;
        }
    }
}

ga_macros::algebra! {
    mod raw_blade {
        scalar = f64;
        basis = [e1 = 1, e2 = 1];
        types {
            Pair = blades(e1, r#e2);
            Multivector = all;
        }
    }
}

fn main() {}
