// Every grade of 11 dimensions is the 2048 blades `all` is refused for there.
ga_macros::algebra! {
    mod big {
        scalar = f64;
        basis = [e0 = 1, e1 = 1, e2 = 1, e3 = 1, e4 = 1, e5 = 1, e6 = 1, e7 = 1, e8 = 1, e9 = 1, ea = 1];
        types {
            Vector = grades(1);
            Everything = grades(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11);
        }
        ops = [geometric];
    }
}

// 601 080 390 fields: refused at once, from their count.
ga_macros::algebra! {
    mod huge {
        scalar = f64;
        basis = [
            a0 = 1, a1 = 1, a2 = 1, a3 = 1, a4 = 1, a5 = 1, a6 = 1, a7 = 1, a8 = 1, a9 = 1, aa = 1,
            ab = 1, ac = 1, ad = 1, ae = 1, af = 1, ag = 1, ah = 1, ai = 1, aj = 1, ak = 1, al = 1,
            am = 1, an = 1, ao = 1, ap = 1, aq = 1, ar = 1, at = 1, au = 1, av = 1, aw = 1,
        ];
        types {
            Middle = grades(16);
        }
        ops = [reverse];
    }
}

fn main() {}
