//! Reads the restart data of a results file (layout:
//! `hdf5_writer/restart.rs`): which increments can be continued from,
//! what case they fit, and the state of one of them.
use std::path::Path;

use fv_mesh::StateArrays;
use hdf5::types::VarLenUnicode;
use hdf5::{File, Group};

use super::OutputError;

/// What a results file offers to continue from.
#[derive(Debug, Clone, Default)]
pub struct RestartIndex {
    /// Increments with a restart state and their times, increasing.
    pub increments: Vec<(usize, f64)>,
    /// The `key = value` lines of the case the states fit (empty in a
    /// file written without restart data).
    pub case: Vec<String>,
    /// The increments with fields (`/increments`), increasing.
    pub written: Vec<usize>,
}

fn err(path: &Path, what: &str, source: hdf5::Error) -> OutputError {
    OutputError::Hdf5 {
        path: format!("{}:{what}", path.display()),
        source,
    }
}

fn open(path: &Path) -> Result<File, OutputError> {
    File::with_options()
        .with_fapl(|p| p.file_locking(false))
        .open(path)
        .map_err(|e| err(path, "", e))
}

/// The restart increments and case lines of `path`.
pub fn read_restart_index(path: &Path) -> Result<RestartIndex, OutputError> {
    let file = open(path)?;
    let mut index = RestartIndex::default();
    if file.link_exists("increments") {
        let ks: Vec<u64> = file
            .dataset("increments")
            .and_then(|d| d.read_raw())
            .map_err(|e| err(path, "/increments", e))?;
        index.written = ks.iter().map(|&k| k as usize).collect();
    }
    if !file.link_exists("restart") {
        return Ok(index);
    }
    let root = file
        .group("restart")
        .map_err(|e| err(path, "/restart", e))?;
    if let Ok(a) = root.attr("case") {
        let lines: Vec<VarLenUnicode> = a
            .read_raw()
            .map_err(|e| err(path, "/restart attribute case", e))?;
        index.case = lines.iter().map(|s| s.as_str().to_owned()).collect();
    }
    for name in root.member_names().map_err(|e| err(path, "/restart", e))? {
        let Ok(k) = name.parse::<usize>() else {
            continue;
        };
        let at = format!("/restart/{k} attribute time");
        let t: f64 = root
            .group(&name)
            .and_then(|g| g.attr("time"))
            .and_then(|a| a.read_scalar())
            .map_err(|e| err(path, &at, e))?;
        index.increments.push((k, t));
    }
    index.increments.sort_by_key(|&(k, _)| k);
    Ok(index)
}

/// Adds every dataset under `g` (recursively) to `out`, named by its
/// path below `base`.
fn collect(path: &Path, g: &Group, base: &str, out: &mut StateArrays) -> Result<(), OutputError> {
    let here = g.name();
    for ds in g.datasets().map_err(|e| err(path, &here, e))? {
        let full = ds.name();
        let values: Vec<f64> = ds.read_raw().map_err(|e| err(path, &full, e))?;
        let shape = ds.shape();
        let columns = if shape.len() == 2 { shape[1] } else { 1 };
        let name = full.strip_prefix(base).unwrap_or(&full).to_owned();
        out.put(name, columns.max(1), values);
    }
    for sub in g.groups().map_err(|e| err(path, &here, e))? {
        collect(path, &sub, base, out)?;
    }
    Ok(())
}

/// The state at the end of increment `k` (which [`read_restart_index`]
/// lists).
pub fn read_restart_state(path: &Path, k: usize) -> Result<StateArrays, OutputError> {
    let file = open(path)?;
    let kp = format!("/restart/{k}");
    let g = file.group(&kp).map_err(|e| err(path, &kp, e))?;
    let mut out = StateArrays::new();
    collect(path, &g, &format!("{kp}/"), &mut out)?;
    // a deformable body's cell displacement is its `displacement` field
    // where the state does not hold it (fields in double precision)
    if g.link_exists("body") {
        let bodies = g.group("body").map_err(|e| err(path, &kp, e))?;
        for name in bodies.member_names().map_err(|e| err(path, &kp, e))? {
            if out.has(&format!("body/{name}/momentum/u")) {
                continue;
            }
            let dp = format!("/time/{k}/{name}/displacement");
            let ds = file.dataset(&dp).map_err(|e| err(path, &dp, e))?;
            let values: Vec<f64> = ds.read_raw().map_err(|e| err(path, &dp, e))?;
            out.put(format!("body/{name}/momentum/u"), 3, values);
        }
    }
    Ok(out)
}
