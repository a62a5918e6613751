//! `forces.png`: the force columns of `history.csv` against time, one
//! panel each for the reaction forces of the reported patches
//! (`<body>/<patch>:Fx|Fy|Fz`), the contact forces (`<contact>:…force…`,
//! the normal force of every pair) and, when present, the moments of
//! rotating `rigid-motion` patches (`:Mx|My|Mz`).
use std::path::Path;

use super::chart::{colour, draw_figure, Panel, Series};
use super::data::{History, ResultsFolder};
use super::PlotError;

/// Components smaller than this fraction of the panel's largest value at
/// every increment are left out (zero by symmetry or plane strain).
const NEGLIGIBLE: f64 = 1e-9;

/// The series of one panel: the columns given, as (time, value), with the
/// columns that are negligible throughout left out. Returns the series and
/// how many columns were left out.
pub(crate) fn force_series(history: &History, columns: &[(usize, String)]) -> (Vec<Series>, usize) {
    let times = history.times();
    let largest = columns
        .iter()
        .flat_map(|(i, _)| history.rows.iter().map(move |r| r[*i].abs()))
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let mut out = Vec::new();
    let mut left_out = 0;
    for (i, label) in columns {
        let values: Vec<f64> = history.rows.iter().map(|r| r[*i]).collect();
        let peak = values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        if peak <= NEGLIGIBLE * largest {
            left_out += 1;
            continue;
        }
        let c = colour(out.len());
        out.push(Series::curve(
            label.clone(),
            times.iter().copied().zip(values).collect(),
            c,
        ));
    }
    (out, left_out)
}

/// The panels of `forces.png`.
pub(crate) fn panels(history: &History) -> Vec<Panel> {
    let t_max = history
        .times()
        .into_iter()
        .filter(|t| t.is_finite())
        .fold(0.0f64, f64::max);
    let x_range = Some((0.0, if t_max > 0.0 { 1.02 * t_max } else { 1.0 }));
    let label = |name: &str, q: &str| format!("{name} {q}");
    let groups: [(&str, &[&str], &str); 3] = [
        (
            "Reaction forces ∫σ·n dA on the reported patches",
            &["Fx", "Fy", "Fz"],
            "force",
        ),
        (
            "Contact forces (from the pressure on the contact faces)",
            &[
                "normal_force",
                "tangential_force",
                "Ftx",
                "Fty",
                "Ftz",
                "friction_force",
            ],
            "force",
        ),
        (
            "Moments about the rotation origin",
            &["Mx", "My", "Mz"],
            "moment",
        ),
    ];
    let mut panels = Vec::new();
    for (i, (title, suffixes, unit)) in groups.iter().enumerate() {
        let cols: Vec<(usize, String)> = history
            .columns_ending(suffixes)
            .into_iter()
            .map(|(c, name, q)| (c, label(&name, &q)))
            .collect();
        if cols.is_empty() && i == 2 {
            continue; // no rotating patches: no moment panel
        }
        let (series, left_out) = force_series(history, &cols);
        let mut title = title.to_string();
        if left_out > 0 {
            title.push_str(&format!(" ({left_out} zero throughout not shown)"));
        }
        let empty_text = series.is_empty().then(|| {
            if cols.is_empty() {
                "no such columns in history.csv".to_string()
            } else {
                "all zero".to_string()
            }
        });
        panels.push(Panel {
            title,
            x_label: "time (case time unit)".into(),
            y_label: format!("{unit} (case units)"),
            series,
            x_range,
            y_zero: true,
            empty_text,
            legend: true,
            ..Default::default()
        });
    }
    panels
}

/// Writes `forces.png`.
pub fn plot(folder: &ResultsFolder, history: &History, path: &Path) -> Result<(), PlotError> {
    let panels = panels(history);
    let caption = format!(
        "{}: forces against time{}",
        folder.title,
        run_state(folder, history)
    );
    let height = 80 + 420 * panels.len() as u32;
    draw_figure(path, (1200, height), &caption, &panels)
}

/// ", 12 increments", with "(stopped: no summary.json)" or "(not
/// converged)" when so.
pub(crate) fn run_state(folder: &ResultsFolder, history: &History) -> String {
    let n = history.rows.len();
    let state = match folder.converged() {
        None => " — stopped before the end (no summary.json)",
        Some(false) => " — not converged",
        Some(true) => "",
    };
    format!(", {n} increment{}{state}", if n == 1 { "" } else { "s" })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_panels_take_the_force_columns_and_leave_out_zero_ones() {
        let h = History::parse(
            "time,outer_iterations,residual,a/top:Fx,a/top:Fy,a/top:Fz,a/c:normal_force,a/c:contact_area\n\
             0.5,3,1e-8,1e-14,-2.0,0.0,2.0,0.1\n\
             1.0,4,1e-8,-1e-14,-4.5,0.0,4.5,0.2\n",
        )
        .unwrap();
        let p = panels(&h);
        assert_eq!(p.len(), 2, "no moment columns: no moment panel");
        // Fx (1e-14 of Fy) and Fz are left out
        assert_eq!(p[0].series.len(), 1);
        assert_eq!(p[0].series[0].label, "a/top Fy");
        assert_eq!(p[0].series[0].points, [(0.5, -2.0), (1.0, -4.5)]);
        assert!(p[0].title.contains("2 zero throughout"), "{}", p[0].title);
        // the contact panel has the normal force, not the area
        assert_eq!(p[1].series.len(), 1);
        assert_eq!(p[1].series[0].label, "a/c normal_force");
        assert_eq!(p[1].series[0].points, [(0.5, 2.0), (1.0, 4.5)]);
        assert_eq!(p[0].x_range, Some((0.0, 1.02)));
    }

    #[test]
    fn a_history_without_forces_gives_empty_panels_saying_so() {
        let h = History::parse("time,outer_iterations,residual\n1,2,1e-9\n").unwrap();
        let p = panels(&h);
        assert_eq!(p.len(), 2);
        assert!(p.iter().all(|p| p.series.is_empty()));
        assert_eq!(
            p[0].empty_text.as_deref(),
            Some("no such columns in history.csv")
        );
    }
}
