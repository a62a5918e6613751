//! The results writer on a thread of its own: an increment's fields are
//! copied out of the solver and written (compressed) while the next
//! increment is solved, on the core the solve leaves idle in its serial
//! parts (the incomplete-Cholesky sweeps, the contact search).
//!
//! The channel holds [`QUEUED_JOBS`] jobs: one increment's history row,
//! fields, restart state and the removal of the previous restart state go
//! over without waiting, so the solver goes on with the next increment
//! while they are written. With a rendezvous channel each of those hand-
//! overs waited for the write before it, and the solver's thread wrote in
//! all but name: on curved beams (63 increments of 1,000 cells) 1.1 s of a
//! 5.2 s run. When the writer falls behind, the solver waits at the next
//! increment's hand-over: at most one increment's fields are queued beside
//! the one being written. [`BackgroundWriter::close`] (or dropping the
//! writer) waits for the writes handed over: a run that ends, fails or is
//! interrupted leaves every increment handed over on disk.
use std::sync::mpsc::{sync_channel, SyncSender};
use std::thread::JoinHandle;

use crate::output::{BodyIncrement, OutputError, PatchFaces, PatchIncrement, ResultsWriter};

/// The fields of one contact patch, owned.
pub struct OwnedPatch {
    /// Patch name.
    pub name: String,
    /// `n_faces + 1` offsets from 0 into `connectivity`.
    pub offsets: Vec<u32>,
    /// Body point indices of the faces, concatenated.
    pub connectivity: Vec<u32>,
    /// Face centres, current configuration.
    pub face_centres: Vec<[f64; 3]>,
    /// Contact pressure.
    pub pressure: Vec<f64>,
    /// Contact traction.
    pub traction: Vec<[f64; 3]>,
    /// Normal gap.
    pub gap: Vec<f64>,
}

/// The fields of one body at one increment, owned
/// ([`BodyIncrement`]'s data).
pub struct OwnedBody {
    /// Body name.
    pub name: String,
    /// Current points.
    pub points: Vec<[f64; 3]>,
    /// Cell displacement.
    pub displacement: Vec<[f64; 3]>,
    /// Cauchy stress, xx yy zz xy yz xz.
    pub stress: Vec<[f64; 6]>,
    /// Equivalent plastic strain (plastic models).
    pub plastic_strain: Option<Vec<f64>>,
    /// Contact patches.
    pub patches: Vec<OwnedPatch>,
}

/// What [`ResultsWriter::write_increment`] takes, owned.
pub struct OwnedIncrement {
    /// Increment number (from 1).
    pub k: usize,
    /// Its time.
    pub time: f64,
    /// Nonlinear iterations.
    pub outer_iterations: usize,
    /// Final residual.
    pub residual: f64,
    /// Whether it converged.
    pub converged: bool,
    /// Every body.
    pub bodies: Vec<OwnedBody>,
}

/// Jobs the channel holds: those of one increment (history row, fields,
/// restart state, removal of the previous restart state).
const QUEUED_JOBS: usize = 4;

enum Job {
    Increment(OwnedIncrement),
    History {
        columns: Vec<String>,
        row: Vec<f64>,
    },
    Restart {
        k: usize,
        time: f64,
        state: fv_mesh::StateArrays,
    },
    DropRestart(usize),
}

/// A [`ResultsWriter`] fed through a channel by the solver's thread.
pub struct BackgroundWriter {
    jobs: Option<SyncSender<Job>>,
    worker: Option<JoinHandle<Result<(), OutputError>>>,
}

impl BackgroundWriter {
    /// Moves `writer` to a thread of its own.
    pub fn start(writer: ResultsWriter) -> Result<Self, OutputError> {
        let (jobs, inbox) = sync_channel::<Job>(QUEUED_JOBS);
        let worker = std::thread::Builder::new()
            .name("fvc-results".into())
            .spawn(move || {
                let mut writer = writer;
                for job in inbox {
                    match job {
                        Job::Increment(inc) => write_increment(&mut writer, &inc)?,
                        Job::History { columns, row } => {
                            let columns: Vec<&str> = columns.iter().map(String::as_str).collect();
                            writer.write_history(&columns, &row)?;
                        }
                        Job::Restart { k, time, state } => writer.write_restart(k, time, &state)?,
                        Job::DropRestart(k) => writer.drop_restart(k)?,
                    }
                }
                writer.close()
            })
            .map_err(|e| OutputError::invalid(format!("cannot start the results writer: {e}")))?;
        Ok(BackgroundWriter {
            jobs: Some(jobs),
            worker: Some(worker),
        })
    }

    /// Hands increment `inc` over (waits while the queue is full). An error
    /// of an earlier write is returned here or by a later call.
    pub fn write_increment(&mut self, inc: OwnedIncrement) -> Result<(), OutputError> {
        self.send(Job::Increment(inc))
    }

    /// Hands a `/history` row over.
    pub fn write_history(&mut self, columns: &[&str], row: &[f64]) -> Result<(), OutputError> {
        self.send(Job::History {
            columns: columns.iter().map(|c| c.to_string()).collect(),
            row: row.to_vec(),
        })
    }

    /// Hands over the restart state of increment `k` (written after it).
    pub fn write_restart(
        &mut self,
        k: usize,
        time: f64,
        state: fv_mesh::StateArrays,
    ) -> Result<(), OutputError> {
        self.send(Job::Restart { k, time, state })
    }

    /// Hands over the removal of the restart state of increment `k`.
    pub fn drop_restart(&mut self, k: usize) -> Result<(), OutputError> {
        self.send(Job::DropRestart(k))
    }

    fn send(&mut self, job: Job) -> Result<(), OutputError> {
        let sent = match &self.jobs {
            Some(jobs) => jobs.send(job).is_ok(),
            None => false,
        };
        if sent {
            return Ok(());
        }
        // the writer stopped: its error
        self.finish()?;
        Err(OutputError::invalid("the results writer has stopped"))
    }

    /// Waits for the writes handed over and closes the file.
    pub fn close(mut self) -> Result<(), OutputError> {
        self.finish()
    }

    fn finish(&mut self) -> Result<(), OutputError> {
        self.jobs = None;
        match self.worker.take().map(JoinHandle::join) {
            None => Ok(()),
            Some(Ok(result)) => result,
            Some(Err(_)) => Err(OutputError::invalid("the results writer panicked")),
        }
    }
}

impl Drop for BackgroundWriter {
    /// A writer dropped unclosed (a run that returned early) still writes
    /// what it was handed.
    fn drop(&mut self) {
        let _ = self.finish();
    }
}

fn write_increment(writer: &mut ResultsWriter, inc: &OwnedIncrement) -> Result<(), OutputError> {
    let bodies: Vec<BodyIncrement> = inc
        .bodies
        .iter()
        .map(|b| BodyIncrement {
            name: &b.name,
            points: &b.points,
            displacement: &b.displacement,
            stress: &b.stress,
            plastic_strain: b.plastic_strain.as_deref(),
            patches: b
                .patches
                .iter()
                .map(|p| PatchIncrement {
                    name: &p.name,
                    faces: PatchFaces {
                        offsets: &p.offsets,
                        connectivity: &p.connectivity,
                    },
                    face_centres: &p.face_centres,
                    contact_pressure: &p.pressure,
                    contact_traction: &p.traction,
                    gap: &p.gap,
                })
                .collect(),
        })
        .collect();
    writer.write_increment(
        inc.k,
        inc.time,
        inc.outer_iterations,
        inc.residual,
        inc.converged,
        &bodies,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::CellMeshData;

    fn tet_increment(k: usize, body: &str) -> OwnedIncrement {
        let points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        OwnedIncrement {
            k,
            time: 0.25 * k as f64,
            outer_iterations: 3,
            residual: 1e-7,
            converged: true,
            bodies: vec![OwnedBody {
                name: body.to_owned(),
                points,
                displacement: vec![[0.0, -1e-3 * k as f64, 0.0]],
                stress: vec![[0.0, -2.0 * k as f64, 0.0, 0.0, 0.0, 0.0]],
                plastic_strain: None,
                patches: vec![OwnedPatch {
                    name: "bottom".to_owned(),
                    offsets: vec![0, 3],
                    connectivity: vec![0, 2, 1],
                    face_centres: vec![[1.0 / 3.0, 1.0 / 3.0, 0.0]],
                    pressure: vec![2.0 * k as f64],
                    traction: vec![[0.0, 0.0, 2.0 * k as f64]],
                    gap: vec![-1e-4],
                }],
            }],
        }
    }

    fn tet() -> CellMeshData {
        let points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        CellMeshData::from_cells(points, [(10u8, &[0u32, 1, 2, 3][..])]).unwrap()
    }

    /// What is handed over is on disk once the writer is closed, in order.
    #[test]
    fn increments_handed_over_are_written_by_close() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = tet();
        let w = ResultsWriter::create(dir.path(), "t", &[("tet", &mesh)]).unwrap();
        let mut bg = BackgroundWriter::start(w).unwrap();
        for k in 1..=3 {
            bg.write_history(&["time"], &[0.25 * k as f64]).unwrap();
            bg.write_increment(tet_increment(k, "tet")).unwrap();
        }
        bg.close().unwrap();
        let f = hdf5::File::open(dir.path().join("t.h5")).unwrap();
        let times = f.dataset("times").unwrap().read_raw::<f64>().unwrap();
        assert_eq!(times, [0.25, 0.5, 0.75]);
        let p = f.dataset("time/3/tet/bottom/contact_pressure").unwrap();
        assert_eq!(p.read_raw::<f64>().unwrap(), [6.0]);
        let h = f.dataset("history").unwrap().read_raw::<f64>().unwrap();
        assert_eq!(h, [0.25, 0.5, 0.75]);
    }

    /// A write that fails (an unknown body) is reported by a later call,
    /// and the increments before it stay written.
    #[test]
    fn a_failed_write_is_reported_by_the_next_call() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = tet();
        let w = ResultsWriter::create(dir.path(), "t", &[("tet", &mesh)]).unwrap();
        let mut bg = BackgroundWriter::start(w).unwrap();
        bg.write_increment(tet_increment(1, "tet")).unwrap();
        // handed over; its failure shows later
        bg.write_increment(tet_increment(2, "cube")).unwrap();
        let e = bg
            .write_history(&["time"], &[0.5])
            .and_then(|_| bg.close())
            .unwrap_err();
        assert!(e.to_string().contains("body 'tet' is missing"), "{e}");
        let f = hdf5::File::open(dir.path().join("t.h5")).unwrap();
        assert_eq!(f.group("time").unwrap().member_names().unwrap(), ["1"]);
    }
}
