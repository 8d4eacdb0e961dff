//! The charts render to PNG files with text (axis labels, legends) from the embedded font.
use report::plot::{linear_log, log_log, path_view, Labels, Series};

#[test]
fn charts_render() {
    let dir = std::env::temp_dir().join("report-plot-smoke");
    std::fs::create_dir_all(&dir).unwrap();
    let curve = Series {
        markers: true,
        ..Series::line("RK4, PGA", vec![(1e-3, 1e-6), (1e-2, 1e-10), (1e-1, 1e-14)])
    };
    let mujoco = Series {
        markers_only: true,
        ..Series::line("MuJoCo RK4", vec![(4e-3, 2e-10)])
    };
    let labels = Labels {
        title: "Scene 1: work-precision",
        x: "CPU per simulated second (s)",
        y: "orientation error at T (rad)",
    };
    log_log(&dir.join("wp.png"), &labels, &[curve.clone(), mujoco]).unwrap();
    linear_log(
        &dir.join("drift.png"),
        &labels,
        &[Series::line("drift", vec![(0.0, 1e-16), (5.0, 1e-12), (10.0, 1e-10)])],
    )
    .unwrap();
    let circle: Vec<(f64, f64)> = (0..100)
        .map(|k| (k as f64 * 0.0628).cos())
        .zip((0..100).map(|k| (k as f64 * 0.0628).sin()))
        .collect();
    path_view(&dir.join("path.png"), &labels, &[Series::line("rod end", circle)]).unwrap();
    for name in ["wp.png", "drift.png", "path.png"] {
        let size = std::fs::metadata(dir.join(name)).unwrap().len();
        assert!(size > 10_000, "{name} is {size} bytes");
    }
}
