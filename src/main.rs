//! The main job: `cargo run --release` runs every reference scene and writes the report (see `--help`).
fn main() -> std::process::ExitCode {
    report::cli::main()
}
