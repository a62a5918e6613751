//! The case file: TOML → validated, typed [`Case`].
//!
//! The format is the user-facing contract in `shared/CASE_FORMAT.md`. Every
//! key is checked here — unknown keys, wrong types, out-of-range values and
//! unknown names are [`InputError`]s naming the file, the line and the key
//! path (e.g. `body[0].material.nu`). Checks that need the mesh (patch names)
//! are the solver's, which reports them with [`CaseSource::error`]. The
//! user's reference is `docs/case-format.md`, kept true by a test against
//! the lists of accepted keys and names in [`keys`].
//!
//! ```no_run
//! let case = solver_app::case::load_case(std::path::Path::new("case.toml"))?;
//! println!("{} increments of {}", case.time.steps, case.time.dt());
//! # Ok::<(), solver_app::case::InputError>(())
//! ```

use std::path::Path;

use toml::de::DeTable;

mod boundary;
mod contact;
mod error;
pub mod keys;
mod material;
mod mesh;
mod reader;
mod settings;
mod source;
mod values;

pub use boundary::{BoundarySpec, BOUNDARY_TYPES};
pub use contact::{Augmentation, ContactAlgorithm, ContactSpec, Coupling, Detection, FacePosition};
pub use error::InputError;
pub use material::{MaterialModel, MaterialSpec};
pub use mesh::{MeshSpec, GENERATORS};
pub use settings::{
    Acceleration, Analysis, AnalysisKind, CouplingFallback, LinearMethod, LinearSettings,
    OnNonConvergence, OutputSettings, Predictor, SolverSettings, StrainKind, TimeControl,
    ANDERSON_LINEAR_TOLERANCE, NEWTON_FINAL_ATTEMPT_ITERATIONS,
};
pub use source::CaseSource;
pub use values::{Rotation, ScalarValue, VectorValue};

use reader::{Ctx, Node, Res, Table};
use source::LineIndex;

/// A validated case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Name of the run; results go to `<output.directory>/<title>/`.
    pub title: String,
    /// `[analysis]`.
    pub analysis: Analysis,
    /// `[time]`.
    pub time: TimeControl,
    /// `[solver]`.
    pub solver: SolverSettings,
    /// `[[body]]`, in file order (at least one).
    pub bodies: Vec<BodySpec>,
    /// `[[contact]]`, in file order.
    pub contacts: Vec<ContactSpec>,
    /// `[output]`.
    pub output: OutputSettings,
    /// The file, its directory and the line of every key.
    pub source: CaseSource,
}

/// One `[[body]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySpec {
    /// Unique, non-empty, without `/`.
    pub name: String,
    /// Where the mesh comes from.
    pub mesh: MeshSpec,
    /// Material; of a rigid body optional and never evaluated
    /// ([`MaterialSpec::unused`] when absent).
    pub material: MaterialSpec,
    /// Not solved: every point follows its boundary motion (default false).
    pub rigid: bool,
    /// `(patch, condition)` in file order; unlisted patches are traction-free.
    /// Patch names are checked against the mesh by the solver.
    pub boundary: Vec<(String, BoundarySpec)>,
}

impl Case {
    /// The body called `name`.
    pub fn body(&self, name: &str) -> Option<&BodySpec> {
        self.bodies.iter().find(|b| b.name == name)
    }
}

/// Reads and validates the case file at `path`.
///
/// Errors: the file cannot be read; it is not UTF-8 (the message gives the
/// line and byte offset of the first bad sequence); anything [`parse_case`]
/// rejects.
pub fn load_case(path: &Path) -> Result<Case, InputError> {
    load_case_with(path, None)
}

/// [`load_case`] with `[solver] nonlinear` set to `nonlinear` whatever the
/// file says (`fvc run --nonlinear`): the method's defaults apply to the
/// keys the file does not give.
pub fn load_case_with(
    path: &Path,
    nonlinear: Option<fv_nonlinear::NonlinearMethod>,
) -> Result<Case, InputError> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_CASE_BYTES as u64 + 1).read_to_end(&mut bytes))
        .map_err(|e| InputError::new(path, format!("cannot read the case file: {e}")))?;
    parse_case_bytes(bytes, path, nonlinear)
}

fn too_large(path: &Path) -> InputError {
    InputError::new(
        path,
        format!(
            "the case file is larger than {} MiB, the most a case file may have",
            MAX_CASE_BYTES >> 20
        ),
    )
}

/// [`load_case_with`] of the file's content: UTF-8 checked, a byte-order
/// mark dropped, then [`parse_case_with`] (the case fuzz target's entry).
pub fn parse_case_bytes(
    bytes: Vec<u8>,
    path: &Path,
    nonlinear: Option<fv_nonlinear::NonlinearMethod>,
) -> Result<Case, InputError> {
    if bytes.len() > MAX_CASE_BYTES {
        return Err(too_large(path));
    }
    let text = String::from_utf8(bytes).map_err(|e| utf8_error(path, e))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    parse_case_with(text, path, nonlinear)
}

fn utf8_error(path: &Path, e: std::string::FromUtf8Error) -> InputError {
    let bytes = e.as_bytes();
    let at = e.utf8_error().valid_up_to();
    let before = &bytes[..at];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let column = at
        - before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |p| p + 1)
        + 1;
    let bad_len = e.utf8_error().error_len().unwrap_or(bytes.len() - at);
    let bad: Vec<String> = bytes[at..at + bad_len]
        .iter()
        .map(|b| format!("0x{b:02x}"))
        .collect();
    InputError::new(
        path,
        format!(
            "not valid UTF-8: invalid byte sequence {} at byte {at} (line {line}, column {column}); \
             save the file as UTF-8",
            bad.join(" ")
        ),
    )
    .at_line(line)
}

/// Parses and validates case text; `path` names the file in messages and
/// its directory resolves relative mesh paths.
pub fn parse_case(text: &str, path: &Path) -> Result<Case, InputError> {
    parse_case_with(text, path, None)
}

/// Largest case file read: the TOML tree takes about a hundred times the
/// text's size in memory (`fvc check` of an 8 MiB array of zeros: 768 MB,
/// 7.6 s; issue 44 bounds any input to 4 GB and 30 s). Deep nesting is
/// refused by the TOML parser itself (80 levels).
pub const MAX_CASE_BYTES: usize = 8 << 20;

/// [`parse_case`] with `[solver] nonlinear` overridden ([`load_case_with`]).
pub fn parse_case_with(
    text: &str,
    path: &Path,
    nonlinear: Option<fv_nonlinear::NonlinearMethod>,
) -> Result<Case, InputError> {
    if text.len() > MAX_CASE_BYTES {
        return Err(too_large(path));
    }
    let index = LineIndex::new(text);
    let root = match DeTable::parse(text) {
        Ok(root) => root,
        Err(e) => {
            let mut err = InputError::new(path, format!("TOML syntax error: {}", e.message()));
            if let Some(span) = e.span() {
                err = err.at_line(index.line(span.start));
                let near = text.get(span.clone()).unwrap_or("").trim();
                if !near.is_empty() && near.len() <= 40 && !near.contains('\n') {
                    err.message = format!("{} at `{near}`", err.message);
                }
                err.message = format!("{} (column {})", err.message, index.column(span.start));
            }
            return Err(err);
        }
    };
    let source = CaseSource::new(path, text, Some(root.get_ref()));
    let ctx = Ctx {
        file: path,
        text,
        index,
    };
    let top = Table {
        ctx: &ctx,
        path: "",
        line: None,
        table: root.get_ref(),
    };
    build(&top, source, nonlinear)
}

/// Why the pair `spec` cannot share its patch `side` (its master or its
/// slave) with the pair `o`, if it cannot. A deformable body's patch
/// carries one contact condition, which sums those of its pairs: their
/// tractions with explicit coupling, and with implicit coupling their
/// grounded springs against rigid bodies (a spring to another deformable
/// body joins two cells, and a patch's condition is either kind, not
/// both). `None` as well when `side` is a rigid body's or not in `o`.
pub(crate) fn shared_patch_conflict(
    spec: &ContactSpec,
    side: &(String, String),
    o: &ContactSpec,
    is_rigid: impl Fn(&(String, String)) -> bool,
) -> Option<&'static str> {
    if is_rigid(side) {
        return None;
    }
    let other = if *side == spec.master {
        &spec.slave
    } else {
        &spec.master
    };
    let o_other = if o.master == *side {
        &o.slave
    } else if o.slave == *side {
        &o.master
    } else {
        return None;
    };
    if o_other == other {
        Some("the same two patches are already a pair")
    } else if o.coupling != spec.coupling {
        Some("the pairs of one deformable patch need the same coupling")
    } else if spec.coupling == Coupling::Implicit && !(is_rigid(other) && is_rigid(o_other)) {
        Some(
            "with implicit coupling a deformable body's patch can be in \
             several pairs only against rigid bodies (use coupling = \
             \"explicit\", or split the patch)",
        )
    } else {
        None
    }
}

fn build(
    t: &Table<'_>,
    source: CaseSource,
    nonlinear: Option<fv_nonlinear::NonlinearMethod>,
) -> Res<Case> {
    t.deny_unknown(keys::TOP)?;
    let title = t.need("title", title)?;
    let analysis = match t.get("analysis") {
        Some(a) => settings::analysis(&a.node().table()?)?,
        None => Analysis::default(),
    };
    let time = match t.get("time") {
        Some(a) => settings::time(&a.node().table()?)?,
        None => {
            return Err(t.err_at_key(
                "time",
                "missing required table [time] (end = ..., steps = ... or step = ...)",
            ))
        }
    };
    let solver_defaults = SolverSettings::for_analysis(&analysis, t.get("contact").is_some());
    let solver = match t.get("solver") {
        Some(a) => settings::solver(&a.node().table()?, &solver_defaults, nonlinear)?,
        None => settings::solver_without_table(&solver_defaults, nonlinear),
    };

    let body_entry = t.get("body");
    let body_nodes = match &body_entry {
        Some(b) => tables(&b.node(), "body")?,
        None => Vec::new(),
    };
    if body_nodes.is_empty() {
        return Err(t.err_at_key("body", "at least one [[body]] is required"));
    }
    let mut bodies: Vec<BodySpec> = Vec::with_capacity(body_nodes.len());
    for b in &body_nodes {
        let node = b.node();
        let spec = body(&node, &source.dir)?;
        if let Some(i) = bodies.iter().position(|o| o.name == spec.name) {
            let name = node.table()?.req("name")?;
            return Err(name.node().err(format!(
                "duplicate body name \"{}\" (also body[{i}])",
                spec.name
            )));
        }
        bodies.push(spec);
    }
    if analysis.kind == AnalysisKind::Dynamic {
        if let Some(i) = bodies
            .iter()
            .position(|b| !b.rigid && b.material.rho.is_none())
        {
            return Err(source.error(
                &format!("body[{i}].material.rho"),
                "a dynamic analysis needs the density `rho` on every non-rigid body",
            ));
        }
    }

    if bodies.iter().all(|b| b.rigid) {
        // nothing to solve: a rigid body only follows its boundary motion
        return Err(source.error(
            "body[0].rigid",
            "every body is rigid: at least one body must be deformable (rigid bodies are not solved, they only follow their boundary motion)",
        ));
    }
    let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let contact_entry = t.get("contact");
    let mut contacts: Vec<ContactSpec> = Vec::new();
    if let Some(c) = &contact_entry {
        for item in tables(&c.node(), "contact")? {
            let node = item.node();
            let spec = contact::contact(&node, &names)?;
            let is_rigid =
                |side: &(String, String)| bodies.iter().any(|b| b.name == side.0 && b.rigid);
            for (key, side) in [("master", &spec.master), ("slave", &spec.slave)] {
                for (j, o) in contacts.iter().enumerate() {
                    if let Some(why) = shared_patch_conflict(&spec, side, o, is_rigid) {
                        return Err(node.table()?.req(key)?.node().err(format!(
                            "patch \"{}/{}\" of the deformable body \"{}\" is already in \
                             contact[{j}]: {why}",
                            side.0, side.1, side.0
                        )));
                    }
                }
            }
            if matches!(spec.augmentation, Some(Some(_))) && is_rigid(&spec.slave) {
                // the multipliers live on the slave faces, where the
                // algorithms resolve the pressure
                return Err(node.table()?.req("augmentation")?.node().err(format!(
                    "augmentation needs a deformable slave; \"{}/{}\" is a rigid body's \
                     patch: make it the master",
                    spec.slave.0, spec.slave.1
                )));
            }
            contacts.push(spec);
        }
    }
    let output = match t.get("output") {
        Some(a) => settings::output(&a.node().table()?)?,
        None => OutputSettings::default(),
    };
    Ok(Case {
        title,
        analysis,
        time,
        solver,
        bodies,
        contacts,
        output,
        source,
    })
}

/// The elements of an array of tables (`[[name]]`).
fn tables<'a>(n: &Node<'a>, name: &str) -> Res<Vec<reader::Owned<'a>>> {
    if n.table().is_ok() {
        return Err(n.err(format!(
            "expected [[{name}]] (an array of tables), got a single [{name}] table"
        )));
    }
    let items = n.array()?;
    for item in &items {
        item.node().table()?;
    }
    Ok(items)
}

/// Longest `title` in bytes: the results file `<title>.xdmf` must fit a
/// file name (255 bytes on the usual file systems).
const MAX_TITLE_BYTES: usize = 240;

/// Whether a body or patch name can head a column of `history.csv` as it
/// is: no ',' or '"' (a comma in a name split the header, and `fvc plot`
/// then took the file for truncated).
pub(crate) fn column_safe(name: &str) -> bool {
    !name.contains(',') && !name.contains('"')
}

/// `title`: non-empty and usable as a directory name.
fn title(n: &Node<'_>) -> Res<String> {
    let s = n.nonempty_str()?;
    let bad = if s.len() > MAX_TITLE_BYTES {
        Some("more than 240 bytes (the results files are named after it)")
    } else if s.contains('/') || s.contains('\\') {
        Some("a path separator")
    } else if s == "." || s == ".." || s.contains("..") {
        Some("\"..\"")
    } else if s.chars().any(char::is_control) {
        Some("a control character")
    } else {
        None
    };
    match bad {
        Some(what) => Err(n.err(format!(
            "must be usable as a directory name, but contains {what}: {}",
            n.raw()
        ))),
        None => Ok(s.to_owned()),
    }
}

fn body(n: &Node<'_>, dir: &Path) -> Res<BodySpec> {
    let t = n.table()?;
    t.deny_unknown(keys::BODY)?;
    let name = t.need("name", |n| {
        let s = n.nonempty_str()?;
        if s.contains('/') || s.chars().any(char::is_control) || !column_safe(s) {
            return Err(n.err(format!(
                "a body name must not contain '/', ',', '\"' or control characters (it heads the columns of history.csv), got {}",
                n.raw()
            )));
        }
        Ok(s.to_owned())
    })?;
    let mesh = t.need("mesh", |n| mesh::mesh(n, dir))?;
    let rigid = t.opt("rigid", false, |n| n.bool())?;
    // a rigid body is not solved: its material may be left out
    let material = match rigid {
        true => t.opt("material", MaterialSpec::unused(), material::material)?,
        false => t.need("material", material::material)?,
    };
    let mut boundary = Vec::new();
    if let Some(b) = t.get("boundary") {
        let node = b.node();
        for (patch, cond) in node.table()?.entries() {
            let c = cond.node();
            if patch.trim().is_empty() {
                return Err(c.err("empty patch name"));
            }
            if !column_safe(patch) {
                return Err(c.err(format!(
                    "patch name \"{patch}\" contains ',' or '\"', which would split its columns in history.csv; rename the patch (the mesh's physical group)"
                )));
            }
            boundary.push((patch.to_owned(), boundary::boundary_condition(&c)?));
        }
    }
    Ok(BodySpec {
        name,
        mesh,
        material,
        rigid,
        boundary,
    })
}

#[cfg(test)]
mod tests;
