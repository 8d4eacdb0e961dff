// A CGA coordinate map that reads l₁ and l₃ swapped (e1_e2 for l₁, e2_e3 for l₃), consistently in both directions:
// a plausible slip that relabels the screws, which the compile-time check must reject.
use dynamics::cga::generated::Screw;
use dynamics::cga::{screw_coordinates, screw_from_coordinates};

const fn from_swapped(c: [f64; 6]) -> Screw {
    screw_from_coordinates([c[2], c[1], c[0], c[3], c[4], c[5]])
}

const fn to_swapped(s: Screw) -> [f64; 6] {
    let c = screw_coordinates(s);
    [c[2], c[1], c[0], c[3], c[4], c[5]]
}

dynamics::assert_same_screw_algebra!(
    dynamics::pga::line_from_coordinates, dynamics::pga::generated::Line::commutator_line,
    dynamics::pga::wedge_pi, dynamics::pga::line_coordinates;
    from_swapped, Screw::commutator_screw, dynamics::cga::wedge_pi, to_swapped;
);

fn main() {}
