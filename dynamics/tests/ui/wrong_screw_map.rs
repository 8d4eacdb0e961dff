// A CGA coordinate map that reads l₁ and l₃ swapped (e12 for l₁, e23 for l₃), consistently in both directions:
// a plausible slip that relabels the screws, which the compile-time check must reject.
use dynamics::cga::generated::Bivector;
use dynamics::cga::{bivector_coordinates, bivector_from_coordinates};

const fn from_swapped(c: [f64; 6]) -> Bivector {
    bivector_from_coordinates([c[2], c[1], c[0], c[3], c[4], c[5]])
}

const fn to_swapped(b: Bivector) -> [f64; 6] {
    let c = bivector_coordinates(b);
    [c[2], c[1], c[0], c[3], c[4], c[5]]
}

dynamics::assert_same_screw_algebra!(
    dynamics::pga::line_from_coordinates, dynamics::pga::generated::Line::commutator_line,
    dynamics::pga::wedge_pi, dynamics::pga::line_coordinates;
    from_swapped, Bivector::commutator_bivector, dynamics::cga::wedge_pi, to_swapped;
);

fn main() {}
