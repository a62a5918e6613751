//! Reading a results folder (CASE_FORMAT.md, "Results"): which files it
//! has, `history.csv`, the per-increment lines of `log.txt`, and the
//! datasets of the `.h5` the plots need.
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::PlotError;

/// The files of a results folder `<output>/<title>/`.
#[derive(Debug, Clone)]
pub struct ResultsFolder {
    /// The folder.
    pub dir: PathBuf,
    /// `history.csv`.
    pub history_csv: PathBuf,
    /// `<title>.h5`.
    pub h5: PathBuf,
    /// `summary.json`, parsed; `None` when the run was stopped before
    /// writing it.
    pub summary: Option<serde_json::Value>,
    /// `log.txt`, when present.
    pub log: Option<PathBuf>,
    /// The case title: `summary.json`'s, else the `.h5` file's name.
    pub title: String,
}

impl ResultsFolder {
    /// Finds the files of the results folder `dir`. Fails with
    /// [`PlotError::NotResults`] naming what is missing when `dir` does not
    /// exist, is not a folder, or lacks `history.csv` or the `.h5`.
    pub fn open(dir: &Path) -> Result<Self, PlotError> {
        let not_results = |reason: String| PlotError::NotResults {
            dir: dir.to_path_buf(),
            reason,
        };
        if !dir.exists() {
            return Err(not_results("it does not exist".into()));
        }
        if !dir.is_dir() {
            return Err(not_results("it is a file, not a folder".into()));
        }
        let summary_path = dir.join("summary.json");
        let summary = match std::fs::read_to_string(&summary_path) {
            Ok(text) => Some(
                serde_json::from_str::<serde_json::Value>(&text)
                    .map_err(|e| PlotError::read(&summary_path, e))?,
            ),
            Err(_) => None,
        };
        let summary_title = summary
            .as_ref()
            .and_then(|s| s.get("title"))
            .and_then(|t| t.as_str())
            .map(str::to_string);
        let h5 = find_h5(dir, summary_title.as_deref());
        let history_csv = dir.join("history.csv");
        let mut missing = Vec::new();
        if !history_csv.is_file() {
            missing.push("history.csv".to_string());
        }
        let h5 = match h5 {
            Ok(p) => Some(p),
            Err(what) => {
                missing.push(what);
                None
            }
        };
        if let (Some(h5), true) = (&h5, missing.is_empty()) {
            let title = summary_title.unwrap_or_else(|| {
                h5.file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default()
            });
            let log = Some(dir.join("log.txt")).filter(|p| p.is_file());
            return Ok(ResultsFolder {
                dir: dir.to_path_buf(),
                history_csv,
                h5: h5.clone(),
                summary,
                log,
                title,
            });
        }
        let mut reason = format!("no {}", missing.join(", no "));
        // `fvc run` writes to <output>/<title>/: the parent was given?
        let inside: Vec<String> = std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.is_dir() && p.join("history.csv").is_file())
            .map(|p| p.display().to_string())
            .collect();
        if !inside.is_empty() {
            reason.push_str(&format!(
                " (the results of `fvc run` are in <output>/<title>/: try {})",
                inside.join(" or ")
            ));
        }
        Err(not_results(reason))
    }

    /// Opens the `.h5` for reading (without HDF5 file locking, so that the
    /// file of a run still going can be read).
    pub fn open_h5(&self) -> Result<hdf5::File, PlotError> {
        hdf5::File::with_options()
            .with_fapl(|p| p.file_locking(false))
            .open(&self.h5)
            .map_err(|e| PlotError::read(&self.h5, e))
    }

    /// `summary.json`'s `contacts` as (master, slave) names.
    pub fn contact_pairs(&self) -> Vec<(String, String)> {
        let Some(list) = self
            .summary
            .as_ref()
            .and_then(|s| s.get("contacts"))
            .and_then(|c| c.as_array())
        else {
            return Vec::new();
        };
        list.iter()
            .filter_map(|c| {
                Some((
                    c.get("master")?.as_str()?.to_string(),
                    c.get("slave")?.as_str()?.to_string(),
                ))
            })
            .collect()
    }

    /// Whether `summary.json` says the run converged: `None` without it.
    pub fn converged(&self) -> Option<bool> {
        self.summary.as_ref()?.get("converged")?.as_bool()
    }
}

/// The `.h5` of the folder: `<title>.h5` when the title is known, else the
/// only `.h5` there (or the one named like the folder). `Err` says what is
/// missing.
fn find_h5(dir: &Path, title: Option<&str>) -> Result<PathBuf, String> {
    if let Some(t) = title {
        let p = dir.join(format!("{t}.h5"));
        return if p.is_file() {
            Ok(p)
        } else {
            Err(format!("{t}.h5"))
        };
    }
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == "h5"))
        .collect();
    found.sort();
    match found.len() {
        0 => Err(".h5 file".into()),
        1 => Ok(found.remove(0)),
        _ => {
            let by_dir = dir
                .file_name()
                .map(|n| dir.join(format!("{}.h5", n.to_string_lossy())));
            match by_dir.filter(|p| p.is_file()) {
                Some(p) => Ok(p),
                None => Err(format!(
                    "single .h5 file (found {}; without summary.json the title is unknown)",
                    found
                        .iter()
                        .filter_map(|p| p.file_name())
                        .map(|n| n.to_string_lossy().into_owned())
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            }
        }
    }
}

/// `history.csv`: one row per increment.
#[derive(Debug, Clone, Default)]
pub struct History {
    /// Column names, as in the header.
    pub columns: Vec<String>,
    /// Rows (one per increment, in order), as many values as columns.
    pub rows: Vec<Vec<f64>>,
    /// Set when the last line was cut short (a run killed while writing
    /// it) and left out: says so.
    pub dropped_line: Option<String>,
}

impl History {
    /// Reads `history.csv`. A malformed last line is left out (and said in
    /// [`History::dropped_line`]); a malformed line before it is an error.
    pub fn read(path: &Path) -> Result<Self, PlotError> {
        let text = std::fs::read_to_string(path).map_err(|e| PlotError::read(path, e))?;
        Self::parse(&text).map_err(|m| PlotError::read(path, m))
    }

    /// Parses the text of `history.csv`; `Err` says which line is wrong.
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((_, header)) = lines.next() else {
            return Err("empty (no header line)".into());
        };
        let columns: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
        if columns.first().map(String::as_str) != Some("time") {
            return Err(format!(
                "line 1: the header should start with \"time\", found {:?}",
                columns.first().map(String::as_str).unwrap_or("")
            ));
        }
        let body: Vec<(usize, &str)> = lines.collect();
        let mut h = History {
            columns,
            ..Default::default()
        };
        for (i, &(n, line)) in body.iter().enumerate() {
            let parsed: Result<Vec<f64>, _> =
                line.split(',').map(|v| v.trim().parse::<f64>()).collect();
            match parsed {
                Ok(row) if row.len() == h.columns.len() => h.rows.push(row),
                _ if i + 1 == body.len() => {
                    h.dropped_line = Some(format!(
                        "history.csv line {}: incomplete (the run was stopped while writing it); left out",
                        n + 1
                    ));
                }
                Ok(row) => {
                    return Err(format!(
                        "line {}: {} values for {} columns",
                        n + 1,
                        row.len(),
                        h.columns.len()
                    ))
                }
                Err(e) => return Err(format!("line {}: {e}", n + 1)),
            }
        }
        Ok(h)
    }

    /// Index of the column `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// The values of column `name`, one per row.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let i = self.index(name)?;
        Some(self.rows.iter().map(|r| r[i]).collect())
    }

    /// The `time` column.
    pub fn times(&self) -> Vec<f64> {
        self.rows.iter().map(|r| r[0]).collect()
    }

    /// Columns whose name ends in `:<suffix>` for one of `suffixes`, as
    /// (column index, the part before the last `:`, the suffix).
    pub fn columns_ending(&self, suffixes: &[&str]) -> Vec<(usize, String, String)> {
        self.columns
            .iter()
            .enumerate()
            .filter_map(|(i, c)| {
                let (name, q) = c.rsplit_once(':')?;
                suffixes
                    .contains(&q)
                    .then(|| (i, name.to_string(), q.to_string()))
            })
            .collect()
    }

    /// The history label of every contact pair (`<slave>` or
    /// `<slave>@<master>`), from the `:normal_force` columns.
    pub fn contact_labels(&self) -> Vec<String> {
        self.columns_ending(&["normal_force"])
            .into_iter()
            .map(|(_, name, _)| name)
            .collect()
    }
}

/// Linear iterations per increment from the lines of `log.txt` that
/// `fvc run` writes after every increment (`increment k/n t = …: … outer
/// iterations, residual …, L linear iterations, 0.42 s`): increment k → L;
/// a run continued from its results (`--restart`) repeats the increments
/// after its start, and the later lines count.
pub fn linear_iterations_from_log(text: &str) -> BTreeMap<usize, usize> {
    let mut out = BTreeMap::new();
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("increment ") else {
            continue;
        };
        let Some((k, rest)) = rest.split_once('/') else {
            continue;
        };
        let Ok(k) = k.parse::<usize>() else {
            continue;
        };
        // "1 linear iteration", "45 linear iterations"
        let Some(head) = rest.split(" linear iteration").next() else {
            continue;
        };
        if head.len() == rest.len() {
            continue; // no "linear iteration(s)" on this line
        }
        if let Some(l) = head
            .rsplit([' ', ','])
            .next()
            .and_then(|w| w.parse::<usize>().ok())
        {
            out.insert(k, l);
        }
    }
    out
}

/// A file-name-safe form of `name`: letters, digits, `-`, `_` and `.`
/// kept, anything else replaced by `_`.
pub fn file_stem(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The increments written to `/time`, in increasing order.
pub fn increments(file: &hdf5::File) -> Vec<usize> {
    let mut ks: Vec<usize> = file
        .group("time")
        .and_then(|g| g.member_names())
        .unwrap_or_default()
        .iter()
        .filter_map(|n| n.parse().ok())
        .collect();
    ks.sort_unstable();
    ks
}

/// The last increment written to `/time`, if any.
pub fn last_increment(file: &hdf5::File) -> Option<usize> {
    increments(file).last().copied()
}

/// The time attribute of increment `k`.
pub fn increment_time(file: &hdf5::File, k: usize) -> hdf5::Result<f64> {
    file.group(&format!("time/{k}"))?
        .attr("time")?
        .read_scalar::<f64>()
}

/// A dataset of `n × width` values read as rows (`width` 1: one value per
/// row); `Err` when absent or of another shape.
pub fn read_rows<const W: usize>(file: &hdf5::File, name: &str) -> Result<Vec<[f64; W]>, String> {
    let ds = file.dataset(name).map_err(|e| format!("{name}: {e}"))?;
    let shape = ds.shape();
    let ok = match shape.as_slice() {
        [_] => W == 1,
        [_, w] => *w == W,
        _ => false,
    };
    if !ok {
        return Err(format!("{name}: shape {shape:?}, expected n×{W}"));
    }
    let flat = ds.read_raw::<f64>().map_err(|e| format!("{name}: {e}"))?;
    Ok(flat
        .chunks_exact(W)
        .map(|c| {
            let mut a = [0.0; W];
            a.copy_from_slice(c);
            a
        })
        .collect())
}

/// A one-dimensional dataset of `f64`.
pub fn read_f64(file: &hdf5::File, name: &str) -> Result<Vec<f64>, String> {
    Ok(read_rows::<1>(file, name)?
        .into_iter()
        .map(|[v]| v)
        .collect())
}

/// A one-dimensional dataset of `u64`.
pub fn read_u64(file: &hdf5::File, name: &str) -> Result<Vec<u64>, String> {
    file.dataset(name)
        .and_then(|d| d.read_raw::<u64>())
        .map_err(|e| format!("{name}: {e}"))
}

/// Polygons in CSR form (`offsets`, `connectivity`) as point-index lists,
/// checked against `n_points`.
pub fn polygons(
    offsets: &[u64],
    connectivity: &[u64],
    n_points: usize,
) -> Result<Vec<Vec<usize>>, String> {
    let mut out = Vec::with_capacity(offsets.len().saturating_sub(1));
    for w in offsets.windows(2) {
        let (a, b) = (w[0] as usize, w[1] as usize);
        let ids = connectivity
            .get(a..b)
            .ok_or_else(|| format!("offsets {a}..{b} beyond {} indices", connectivity.len()))?;
        let ids: Vec<usize> = ids.iter().map(|&p| p as usize).collect();
        if let Some(p) = ids.iter().find(|&&p| p >= n_points) {
            return Err(format!("point {p} out of range ({n_points} points)"));
        }
        out.push(ids);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn history_parses_and_drops_a_cut_last_line() {
        let text = "time,outer_iterations,residual,a/b:Fx,c/d:normal_force\n\
                    1.0e-1,5,1e-7,2.5,3.0\n2.0e-1,6,2e-7,NaN,4.0\n3.0e-1,7";
        let h = History::parse(text).unwrap();
        assert_eq!(h.rows.len(), 2);
        assert_eq!(h.column("c/d:normal_force").unwrap(), [3.0, 4.0]);
        assert!(h.column("a/b:Fx").unwrap()[1].is_nan());
        assert!(h.dropped_line.as_deref().unwrap().contains("line 4"));
        assert_eq!(h.contact_labels(), ["c/d"]);
        assert_eq!(
            h.columns_ending(&["Fx", "Fy"])[0],
            (3, "a/b".into(), "Fx".into())
        );
        let bad = "time,x\n1,2\n1\n3,4\n";
        assert!(History::parse(bad).unwrap_err().contains("line 3"));
        assert!(History::parse("").is_err());
        assert!(History::parse("x,y\n").unwrap_err().contains("time"));
    }

    #[test]
    fn linear_iterations_come_from_the_increment_lines() {
        let log = "case hertz\n\
            increment 1/2 t = 5.000000e-1: 6 outer iterations, residual 7.252e-8, 45 linear iterations\n\
            increment 1: something else\n\
            increment 2/3 t = 1: 3 outer iterations, residual 1.0e-8, 12 linear iterations, 0.42 s (NOT converged)\n\
            increment 3/3 t = 1.5: 1 outer iteration, residual 1.0e-8, 1 linear iteration, 0.01 s\n\
            continued from increment 1 (t = 0.5)\n\
            increment 2/3 t = 1: 2 outer iterations, residual 1.0e-8, 9 linear iterations, 0.30 s\n\
            cost: 4.954 µs per cell per outer iteration; 6.0 outer iterations per increment; 45 linear iterations in all\n";
        let m = linear_iterations_from_log(log);
        assert_eq!(m.into_iter().collect::<Vec<_>>(), [(1, 45), (2, 9), (3, 1)]);
    }

    #[test]
    fn file_stems_are_safe() {
        assert_eq!(file_stem("cylinder-curved"), "cylinder-curved");
        assert_eq!(file_stem("a/b@c d"), "a_b_c_d");
    }
}
