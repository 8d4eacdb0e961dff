fn main() {
    println!("main job: not yet implemented (issue 6)");
}
