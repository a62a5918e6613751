//! Restart data in the results file (`fvc run --restart`, issue 45):
//!
//! ```text
//! /restart                 attr case (strings): what the state fits (bodies, meshes, pairs)
//! /restart/<k>             attr time; the state at the end of increment k
//! /restart/<k>/<a>/<b>/…   one dataset per state array (n_rows × columns, or n_rows)
//! ```
//! A deformable body's cell displacement (`body/<name>/momentum/u`) is
//! not repeated there when the increment's `displacement` field is
//! written in double: it is `/time/<k>/<body>/displacement`; with
//! single-precision fields, or without that field, it is.
//! Written next to `/time/<k>` for every increment whose fields are
//! written, compressed like the fields, always double.
//! [`ResultsWriter::reopen`] opens a
//! file to continue it after increment K: what the file holds beyond K
//! (fields, restart states, index entries, history rows) is removed and
//! the XDMF lists increments 1..=K again.
use std::path::Path;

use fv_mesh::StateArrays;
use hdf5::types::VarLenUnicode;
use hdf5::{File, Group};

use super::{body_states, group, put, put_attr, vlen, At, History, ResultsWriter};
use crate::output::xdmf_document::{self, BodyGrid, IncrementRecord, PatchGrid};
use crate::output::{CellMeshData, Field, FieldSet, OutputError, Precision};

/// The group `name` of `parent`, created if missing.
fn open_or_create(
    label: &str,
    parent: &Group,
    gpath: &str,
    name: &str,
) -> Result<Group, OutputError> {
    if parent.link_exists(name) {
        parent.group(name).at(|| format!("{label}:{gpath}/{name}"))
    } else {
        group(label, parent, gpath, name)
    }
}

/// Whether a restart array is a body's cell displacement
/// (`body/<name>/momentum/u`).
fn is_cell_displacement(name: &str) -> bool {
    name.strip_prefix("body/")
        .and_then(|r| r.strip_suffix("/momentum/u"))
        .is_some_and(|body| !body.is_empty() && !body.contains('/'))
}

impl ResultsWriter {
    /// Stores what the restart states fit, one `key = value` line each
    /// ([`crate::restart::case_signature`]), as attribute `case` of
    /// `/restart` (created here).
    pub fn write_case_signature(&mut self, lines: &[String]) -> Result<(), OutputError> {
        let l = self.label.clone();
        let g = open_or_create(&l, &self.file, "", "restart")?;
        let at = || format!("{l}:/restart attribute case");
        if g.attr_names().at(at)?.iter().any(|n| n == "case") {
            g.delete_attr("case").at(at)?;
        }
        let v = lines
            .iter()
            .map(|s| vlen(s))
            .collect::<Result<Vec<_>, _>>()?;
        g.new_attr::<VarLenUnicode>()
            .shape([v.len()])
            .create("case")
            .at(at)?
            .write_raw(&v)
            .at(at)?;
        self.file.flush().at(|| l.clone())
    }

    /// Writes the state at the end of increment `k` (time `time`) as
    /// `/restart/<k>` and flushes the file; a body's cell displacement
    /// only if the increment's `displacement` is not written in double
    /// (see the module).
    pub fn write_restart(
        &mut self,
        k: usize,
        time: f64,
        state: &StateArrays,
    ) -> Result<(), OutputError> {
        let l = self.label.clone();
        let l = l.as_str();
        let root = open_or_create(l, &self.file, "", "restart")?;
        let kp = format!("/restart/{k}");
        if root.link_exists(&k.to_string()) {
            root.unlink(&k.to_string()).at(|| format!("{l}:{kp}"))?;
        }
        let kg = group(l, &root, "/restart", &k.to_string())?;
        put_attr(l, &kg, &kp, "time", &time)?;
        let double = self.precision == Precision::Double
            && self.fields.contains(crate::output::Field::Displacement);
        for a in &state.arrays {
            if double && is_cell_displacement(&a.name) {
                continue;
            }
            let (dir, name) = match a.name.rsplit_once('/') {
                Some((d, n)) => (Some(d), n),
                None => (None, a.name.as_str()),
            };
            let mut g = kg.clone();
            let mut gpath = kp.clone();
            for part in dir.into_iter().flat_map(|d| d.split('/')) {
                g = open_or_create(l, &g, &gpath, part)?;
                gpath = format!("{gpath}/{part}");
            }
            let rows = a.values.len() / a.columns.max(1);
            let shape: Vec<usize> = if a.columns == 1 {
                vec![rows]
            } else {
                vec![rows, a.columns]
            };
            put(l, &g, &gpath, name, &a.values, &shape)?;
        }
        self.file.flush().at(|| l.to_string())
    }

    /// Removes the state of increment `k` (`[output] restart_every`: only
    /// some are kept); its space goes to the states written next.
    pub fn drop_restart(&mut self, k: usize) -> Result<(), OutputError> {
        let l = self.label.clone();
        if !self.file.link_exists("restart") {
            return Ok(());
        }
        let root = self.file.group("restart").at(|| format!("{l}:/restart"))?;
        if root.link_exists(&k.to_string()) {
            root.unlink(&k.to_string())
                .at(|| format!("{l}:/restart/{k}"))?;
        }
        self.file.flush().at(|| l.clone())
    }

    /// Opens `<dir>/<title>.h5`, written for `bodies` by an earlier run, to
    /// continue it after increment `keep`: the fields, restart states,
    /// index entries and history rows of later increments are removed
    /// (HDF5 does not shrink the file: their space is reused by the
    /// increments written next only while the file stays open), and the
    /// XDMF is rewritten for increments 1..=`keep`.
    pub fn reopen(
        dir: &Path,
        title: &str,
        bodies: &[(&str, &CellMeshData)],
        keep: usize,
    ) -> Result<Self, OutputError> {
        let (mut states, _) = body_states(bodies)?;
        let h5_path = dir.join(format!("{title}.h5"));
        let xdmf_path = dir.join(format!("{title}.xdmf"));
        let label = h5_path.display().to_string();
        let l = label.as_str();
        let file = File::with_options()
            .with_fapl(super::access)
            .open_rw(&h5_path)
            .at(|| label.clone())?;
        // later increments go
        for root in ["time", "restart"] {
            if !file.link_exists(root) {
                continue;
            }
            let g = file.group(root).at(|| format!("{l}:/{root}"))?;
            for name in g.member_names().at(|| format!("{l}:/{root}"))? {
                if name.parse::<usize>().is_ok_and(|k| k > keep) {
                    g.unlink(&name).at(|| format!("{l}:/{root}/{name}"))?;
                }
            }
        }
        let increments = file
            .dataset("increments")
            .at(|| format!("{l}:/increments"))?;
        let times = file.dataset("times").at(|| format!("{l}:/times"))?;
        let ks: Vec<u64> = increments.read_raw().at(|| format!("{l}:/increments"))?;
        let ts: Vec<f64> = times.read_raw().at(|| format!("{l}:/times"))?;
        let n = ks.iter().take_while(|&&k| k as usize <= keep).count();
        increments.resize([n]).at(|| format!("{l}:/increments"))?;
        times.resize([n]).at(|| format!("{l}:/times"))?;
        let history = if file.link_exists("history") {
            let ds = file.dataset("history").at(|| format!("{l}:/history"))?;
            let shape = ds.shape();
            let rows = shape[0].min(keep);
            ds.resize([rows, shape[1]]).at(|| format!("{l}:/history"))?;
            let columns: Vec<VarLenUnicode> = ds
                .attr("columns")
                .and_then(|a| a.read_raw())
                .at(|| format!("{l}:/history attribute columns"))?;
            Some(History {
                ds,
                columns: columns.iter().map(|c| c.as_str().to_owned()).collect(),
                rows,
            })
        } else {
            None
        };
        // the patches met so far (their `block` numbers after the
        // bodies'), and every kept increment's grids
        let mut n_blocks = states.len();
        for st in &mut states {
            let pp = format!("/mesh/{}/patches", st.grid.name);
            let g = file.group(&pp).at(|| format!("{l}:{pp}"))?;
            for name in g.member_names().at(|| format!("{l}:{pp}"))? {
                let at = || format!("{l}:{pp}/{name}");
                let pg = g.group(&name).at(at)?;
                let offsets = pg.dataset("offsets").at(at)?.shape();
                let topo = pg.dataset("xdmf_topology").at(at)?.shape();
                let cells: Vec<u64> = pg.dataset("cells").at(at)?.read_raw().at(at)?;
                let block: Vec<i64> = pg.dataset("block").at(at)?.read_raw().at(at)?;
                let block = block.first().map_or(n_blocks, |&b| b.max(0) as usize);
                n_blocks = n_blocks.max(block + 1);
                st.grid.patches.push(PatchGrid {
                    name: name.clone(),
                    block,
                    n_faces: offsets[0].saturating_sub(1),
                    topo_len: topo[0],
                });
                st.face_cells.push(cells);
            }
        }
        let grids: Vec<BodyGrid> = states.iter().map(|b| b.grid.clone()).collect();
        let mut steps = Vec::with_capacity(n);
        for (&k, &time) in ks.iter().zip(&ts).take(n) {
            let mut record = IncrementRecord {
                k: k as usize,
                time,
                bodies: Vec::with_capacity(grids.len()),
                precision: Precision::Double,
                fields: FieldSet::NONE,
            };
            for grid in &grids {
                let bp = format!("/time/{k}/{}", grid.name);
                let bg = file.group(&bp).at(|| format!("{l}:{bp}"))?;
                // the precision the increment was written in (the case
                // may have changed `[output] precision` since)
                let at = || format!("{l}:{bp}/points");
                if bg.dataset("points").at(at)?.dtype().at(at)?.size() == 4 {
                    record.precision = Precision::Single;
                }
                // the fields it was written with (`[output] fields` may
                // have changed since): each is in every body or in none
                for (name, f) in Field::NAMES {
                    let path = match f {
                        Field::ContactPressure | Field::ContactTraction | Field::Gap => {
                            format!("xdmf/{name}")
                        }
                        _ => name.to_string(),
                    };
                    if f != Field::FaceCentres && bg.link_exists(&path) {
                        record.fields = record.fields.with(f);
                    }
                }
                let patches = (0..grid.patches.len())
                    .filter(|&i| bg.link_exists(&grid.patches[i].name))
                    .collect();
                record
                    .bodies
                    .push((bg.link_exists("plastic_strain"), patches));
            }
            steps.push(xdmf_document::render_step(
                &format!("{title}.h5"),
                &grids,
                &record,
            ));
        }
        file.flush().at(|| label.clone())?;
        let w = ResultsWriter {
            file,
            h5_path,
            xdmf_path,
            label: label.clone(),
            title: title.to_string(),
            bodies: states,
            last_k: ks[..n].last().map(|&k| k as usize),
            steps,
            history,
            index: (increments, times),
            n_blocks,
            precision: Precision::Double,
            fields: FieldSet::ALL,
        };
        w.write_xdmf()?;
        Ok(w)
    }
}
