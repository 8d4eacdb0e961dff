//! The charts render to PNG files with text (axis labels, legends) from the embedded font.
use report::plot::{chart, figure, Labels, Panel, Series};

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
    chart(
        &dir.join("wp.png"),
        &Panel::new(labels.clone(), vec![curve, mujoco]).log_x().log_y(),
    )
    .unwrap();
    let drift = Series::line("drift", vec![(0.0, 1e-16), (5.0, 1e-12), (10.0, 1e-10)]);
    chart(
        &dir.join("drift.png"),
        &Panel::new(labels.clone(), vec![drift.clone()]).log_y(),
    )
    .unwrap();
    let circle: Vec<(f64, f64)> = (0..100)
        .map(|k| (k as f64 * 0.0628).cos())
        .zip((0..100).map(|k| (k as f64 * 0.0628).sin()))
        .collect();
    let path = Panel::new(labels.clone(), vec![Series::line("rod end", circle)]).equal_aspect();
    chart(&dir.join("path.png"), &path).unwrap();
    figure(
        &dir.join("figure.png"),
        "Two panels",
        &[path, Panel::new(labels, vec![drift]).log_y()],
    )
    .unwrap();
    for name in ["wp.png", "drift.png", "path.png", "figure.png"] {
        let size = std::fs::metadata(dir.join(name)).unwrap().len();
        assert!(size > 10_000, "{name} is {size} bytes");
    }
}
