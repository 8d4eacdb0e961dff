// A body can only be made by a checked constructor: a struct literal with a negative mass does not compile.
use dynamics::Body;
use nalgebra::Vector3;

fn main() {
    let _ = Body {
        mass: -1.0,
        moments: Vector3::new(-1.0, 2.0, 3.0),
    };
}
