//! `fvc plot`: the plots of a small contact run (a rigid punch pressed into
//! a plane-strain block), the data they are drawn from checked against the
//! run's own numbers, an interrupted run, and folders that are not results.
use std::path::{Path, PathBuf};

use solver_app::plot::pressure::{Abscissa, PatchPressure};
use solver_app::plot::{History, ResultsFolder};

/// A rigid punch 0.4 wide pressed 0.01 into a 1 × 0.5 plane-strain block
/// (10 × 5 cells, 0.1 thick) in three increments; small strain, so the
/// contact force is integrated over the initial face areas.
const PUNCH: &str = r#"title = "punch"
[time]
end = 1.0
steps = 3
[solver]
tolerance = 1e-8
[[body]]
name = "base"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 0.5, 0.1], cells = [10, 5, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "punch"
rigid = true
mesh = { generator = "box", min = [0.3, 0.5, 0], max = [0.7, 0.7, 0.1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymax]
type = "displacement"
value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.01, 0]]] }
[[contact]]
master = "punch/ymin"
slave = "base/ymax"
coupling = "implicit"
"#;

use crate::cli::fvc;

/// Runs [`PUNCH`] in `dir`; returns its results folder.
fn run_punch(dir: &Path) -> PathBuf {
    let case = dir.join("case.toml");
    std::fs::write(&case, PUNCH).unwrap();
    let out = dir.join("out");
    let (code, _, err) = fvc(&[
        "run",
        case.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    out.join("punch")
}

/// Width and height of a PNG, decoding the whole image.
fn png_size(path: &Path) -> (u32, u32) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    // not a blank image: text and lines make many non-white pixels
    let dark = buf.chunks(3).filter(|p| p.iter().any(|&c| c < 128)).count();
    assert!(dark > 1000, "{}: {dark} dark pixels", path.display());
    (info.width, info.height)
}

fn plot(dir: &Path) -> (i32, Vec<String>, String) {
    let (code, out, err) = fvc(&["plot", dir.to_str().unwrap()]);
    (code, out.lines().map(str::to_string).collect(), err)
}

#[test]
fn plots_of_a_punch_run_and_the_numbers_behind_them() {
    let tmp = tempfile::tempdir().unwrap();
    let res = run_punch(tmp.path());
    let (code, lines, err) = plot(&res);
    assert_eq!(code, 0, "{err}");
    let plots = res.join("plots");
    let expected = [
        ("forces.png", (1200, 80 + 420 * 2)),
        ("iterations.png", (1200, 80 + 360 * 3)),
        ("contact_pressure_base-ymax.png", (1200, 760)),
        ("field_von_mises.png", (1200, 0)),
    ];
    assert_eq!(
        lines,
        expected
            .iter()
            .map(|(f, _)| plots.join(f).display().to_string())
            .collect::<Vec<_>>(),
        "one line per file written"
    );
    for (f, (w, h)) in expected {
        let size = png_size(&plots.join(f));
        // the field plot's height follows the model's aspect ratio
        let h = if h == 0 { size.1 } else { h };
        assert_eq!(size, (w, h), "{f}");
    }

    // the numbers: history columns
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("summary.json")).unwrap()).unwrap();
    let fn_summary = summary["contacts"][0]["normal_force"].as_f64().unwrap();
    let h = History::read(&res.join("history.csv")).unwrap();
    assert_eq!(h.rows.len(), 3);
    let times = h.times();
    for (t, e) in times.iter().zip([1.0 / 3.0, 2.0 / 3.0, 1.0]) {
        assert!((t - e).abs() < 1e-9, "{times:?}");
    }
    assert_eq!(h.contact_labels(), ["base/ymax"]);
    let fn_hist = h.column("base/ymax:normal_force").unwrap();
    assert!((fn_hist[2] - fn_summary).abs() <= 1e-9 * fn_summary);
    // linear in the load: the force grows with the indentation
    assert!(fn_hist[0] > 0.0 && fn_hist[1] > fn_hist[0] && fn_hist[2] > fn_hist[1]);
    // the punch reaction balances the block's
    let fy_base = h.column("base/ymin:Fy").unwrap()[2];
    let fy_punch = h.column("punch/ymax:Fy").unwrap()[2];
    assert!((fy_base + fy_punch).abs() < 1e-6 * fy_base.abs());

    // the numbers: pressure along the patch at the last increment
    let folder = ResultsFolder::open(&res).unwrap();
    let file = folder.open_h5().unwrap();
    let pp = PatchPressure::read_last(&file, "base", "ymax")
        .unwrap()
        .unwrap();
    assert_eq!((pp.increment, pp.abscissa), (3, Abscissa::ArcLength));
    assert!((pp.time - 1.0).abs() < 1e-12);
    assert_eq!(pp.faces.len(), 10);
    // Σ p A over the initial face areas is the contact normal force (the
    // master is rigid: the force is the slave side's, small strain), to
    // the rounding of the pressures the file holds in single precision
    // (2⁻²⁴ relative, all of one sign)
    let total = pp.force_initial_areas();
    let single = f64::from(f32::EPSILON) / 2.0;
    assert!(
        (total - fn_summary).abs() <= (single + 1e-12) * fn_summary,
        "Σ p A = {total}, summary {fn_summary}"
    );
    for f in &pp.faces {
        assert!((f.initial_area - 0.01).abs() < 1e-12, "{}", f.initial_area);
    }
    // the 4 faces under the punch (x in 0.3..0.7) carry the pressure (the
    // next ones a little, at the punch's corners), none further out; and
    // the pressure is symmetric: the position is x − 0.5, but for the arc
    // length along the indented surface being a little longer than its
    // width
    let max_p = summary["contacts"][0]["max_pressure"].as_f64().unwrap();
    let peak = pp.peak().unwrap().0;
    assert!(
        (peak - max_p).abs() <= (single + 1e-12) * max_p,
        "{peak} vs {max_p}"
    );
    for f in &pp.faces {
        let x = f.centre[0];
        assert!((f.position - (x - 0.5)).abs() < 1e-3, "{x}: {}", f.position);
        let d = (x - 0.5).abs();
        assert_eq!(f.pressure > 0.0, d < 0.3, "x = {x}: p = {}", f.pressure);
        assert!(
            d < 0.2 || f.pressure < 0.05 * peak,
            "x = {x}: p = {}",
            f.pressure
        );
    }
    let (lo, hi) = pp.contact_extent().unwrap();
    assert!(
        (lo + 0.25).abs() < 1e-3 && (hi - 0.25).abs() < 1e-3,
        "{lo} {hi}"
    );
    // (from face centres at x ≈ 0.25 and 0.75, each rounded to single
    // precision in the file: at most 0.75 · 2⁻²⁴ apiece)
    assert!(
        (lo + hi).abs() < 1.5 * single + 1e-12,
        "symmetric about the pressure centre"
    );
    let profile = pp.profile();
    assert!(profile.windows(2).all(|w| w[0].0 <= w[1].0));

    // the field plot's model: plane (thickness along z), the block's 50
    // cells as quadrilaterals, the punch rigid, both contact patches
    let model = solver_app::plot::field::read_last_plane_model(&file)
        .unwrap()
        .unwrap();
    assert_eq!((model.increment, model.normal_axis), (3, 2));
    let base = model.bodies.iter().find(|b| b.name == "base").unwrap();
    let punch = model.bodies.iter().find(|b| b.name == "punch").unwrap();
    assert_eq!(base.cells.len(), 50);
    assert!(base.cells.iter().all(|c| c.len() == 4));
    assert!(!base.rigid && punch.rigid);
    assert!(base.von_mises.iter().all(|v| *v > 0.0));
    assert_eq!(base.patches.len(), 1);
    assert_eq!(
        (base.patches[0].0.as_str(), base.patches[0].1.len()),
        ("ymax", 10)
    );
    assert_eq!(
        (punch.patches[0].0.as_str(), punch.patches[0].1.len()),
        ("ymin", 1)
    );
    // the punch's bottom moved down by the indentation (the points in
    // single precision)
    let seg = punch.patches[0].1[0];
    let near = |y: f64| (y - 0.49).abs() < 0.49 * single + 1e-12;
    assert!(near(seg[0].1) && near(seg[1].1), "{seg:?}");
}

#[test]
fn an_interrupted_run_is_plotted_up_to_where_it_got() {
    let tmp = tempfile::tempdir().unwrap();
    let res = run_punch(tmp.path());
    // as if killed while writing the third history row: no summary.json,
    // a cut line at the end of history.csv
    std::fs::remove_file(res.join("summary.json")).unwrap();
    let text = std::fs::read_to_string(res.join("history.csv")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    let cut = &lines[3][..10];
    lines[3] = cut;
    std::fs::write(res.join("history.csv"), lines.join("\n")).unwrap();
    let (code, out, err) = plot(&res);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.len(), 4, "{out:?}");
    assert!(err.contains("history.csv line 4: incomplete"), "{err}");
    let h = History::read(&res.join("history.csv")).unwrap();
    assert_eq!(h.rows.len(), 2);
    let folder = ResultsFolder::open(&res).unwrap();
    assert_eq!(folder.title, "punch"); // from the .h5's name
    assert!(folder.summary.is_none());
}

#[test]
fn a_folder_that_is_not_a_results_folder_is_refused_with_exit_2() {
    let tmp = tempfile::tempdir().unwrap();
    let empty = tmp.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let (code, out, err) = plot(&empty);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty());
    let shown = empty.display().to_string();
    for piece in [
        shown.as_str(),
        "not a results folder",
        "no history.csv",
        ".h5",
    ] {
        assert!(err.contains(piece), "stderr lacks {piece:?}: {err}");
    }
    assert!(!empty.join("plots").exists(), "nothing written");

    // history.csv alone: the .h5 is named as missing
    std::fs::write(empty.join("history.csv"), "time,outer_iterations\n").unwrap();
    let (code, _, err) = plot(&empty);
    assert_eq!(code, 2);
    assert!(
        err.contains("no .h5 file") && !err.contains("no history.csv"),
        "{err}"
    );

    // a folder that does not exist, a file
    let (code, _, err) = plot(&tmp.path().join("nowhere"));
    assert_eq!(code, 2);
    assert!(err.contains("does not exist"), "{err}");
    let file = empty.join("history.csv");
    let (code, _, err) = plot(&file);
    assert_eq!(code, 2);
    assert!(err.contains("not a folder"), "{err}");

    // the --output folder instead of <output>/<title>: pointed to it
    let res = run_punch(tmp.path());
    let parent = res.parent().unwrap();
    let (code, _, err) = plot(parent);
    assert_eq!(code, 2);
    assert!(err.contains(&format!("try {}", res.display())), "{err}");
}

/// A new run into a folder that an earlier run's `fvc plot` filled: the
/// old PNGs showed the earlier run beside the new results (found by a
/// probe, 2026-12-01). They go; a user's own file in `plots/` stays.
#[test]
fn a_new_run_takes_away_the_plots_of_the_last() {
    let tmp = tempfile::tempdir().unwrap();
    let res = run_punch(tmp.path());
    let (code, _, err) = plot(&res);
    assert_eq!(code, 0, "{err}");
    let plots = res.join("plots");
    let pngs = |d: &Path| {
        std::fs::read_dir(d)
            .map(|r| {
                r.flatten()
                    .filter(|e| e.path().extension().is_some_and(|x| x == "png"))
                    .count()
            })
            .unwrap_or(0)
    };
    assert!(pngs(&plots) > 0);
    std::fs::write(plots.join("notes.txt"), "mine").unwrap();
    run_punch(tmp.path());
    assert_eq!(pngs(&plots), 0);
    assert!(plots.join("notes.txt").exists());
}
