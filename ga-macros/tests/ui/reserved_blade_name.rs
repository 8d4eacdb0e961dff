// `scalar` is the grade-0 blade's name.
ga_macros::algebra! {
    mod scalar_vector {
        scalar = f64;
        basis = [e1 = 1, scalar = 1];
        types {
            Multivector = all;
        }
    }
}

// `scal` + `a` + `r`: the blade of both basis vectors would be called `scalar`.
ga_macros::algebra! {
    mod scalar_blade {
        scalar = f64;
        basis = [scala = 1, scalr = 1];
        types {
            Multivector = all;
        }
    }
}

// `f` + `o` + `r`: a field named `for` cannot be declared.
ga_macros::algebra! {
    mod keyword_blade {
        scalar = f64;
        basis = [fo = 1, fr = 1];
        types {
            Multivector = all;
        }
    }
}

fn main() {}
