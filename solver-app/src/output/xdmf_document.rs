//! The XDMF 3 document: a temporal collection of time steps, each a
//! spatial collection of one grid per body and per contact patch.
//!
//! ParaView's default reader for `.xdmf` files, Xdmf3ReaderS, flattens the
//! grids of a time step into one multi-piece dataset, the pieces of a
//! single partitioned mesh; its surface filter (and MergeBlocks) then keep
//! only the arrays *every* piece has. Bodies and patches used to share
//! only `point_displacement`, so colouring by `von_mises` found nothing
//! and drew everything grey. Every grid therefore carries every field
//! ([`FIELDS`]): body cells get the `contact_pressure`, `contact_traction`
//! and `gap` of the patch face they bound (0, 0 and NaN — nothing opposite,
//! as on an unmatched face — for cells that bound none), so that a body's
//! surface and the patch drawn over it show one colour, not a mottle of
//! both (the surfaces coincide); patch faces get the `displacement`,
//! `stress`, `von_mises` and `plastic_strain` of the cell they bound; a
//! body without plastic strain gets 0 when another body has it. The cell field `block` numbers the
//! grids (bodies first, then patches as they appear), which the default
//! reader does not name: a Threshold on it picks a body or a patch.
//!
//! Grids reference the body's *current* points (`/time/<k>/<body>/points`),
//! so ParaView shows the deformed shape without any filter; the document
//! says so in an `Information` element. There is no point displacement
//! field (issue 45: it took 14 % of the shallow-ironing results, and it
//! was the vector a "Warp By Vector" would have applied twice); a point's
//! displacement is `/time/<k>/<body>/points − /mesh/<body>/points`.
use std::fmt::Write;

use super::{FieldSet, Precision};

/// Every field of every grid of a time step: name, XDMF type, centre.
/// `plastic_strain` is left out of a step in which no body has it, and
/// every field out of a step that was written without it (`[output]
/// fields`).
pub(crate) const FIELDS: [(&str, &str, &str); 8] = [
    ("displacement", "Vector", "Cell"),
    ("stress", "Tensor6", "Cell"),
    ("von_mises", "Scalar", "Cell"),
    ("plastic_strain", "Scalar", "Cell"),
    ("contact_pressure", "Scalar", "Cell"),
    ("contact_traction", "Vector", "Cell"),
    ("gap", "Scalar", "Cell"),
    ("block", "Scalar", "Cell"),
];

/// What the XDMF needs to know about a body.
#[derive(Debug, Clone)]
pub(crate) struct BodyGrid {
    pub name: String,
    /// Value of the `block` field.
    pub block: usize,
    pub n_points: usize,
    /// Cells shown (after decomposition).
    pub vis_cells: usize,
    pub topo_len: usize,
    pub decomposed: bool,
    pub patches: Vec<PatchGrid>,
}

/// What the XDMF needs to know about a patch surface.
#[derive(Debug, Clone)]
pub(crate) struct PatchGrid {
    pub name: String,
    /// Value of the `block` field.
    pub block: usize,
    pub n_faces: usize,
    pub topo_len: usize,
}

/// One written increment: its number, time and, per body, whether it has
/// plastic strain and which of the body's patches were written; and the
/// precision of its fields (the datasets under `/time/<k>`).
#[derive(Debug, Clone)]
pub(crate) struct IncrementRecord {
    pub k: usize,
    pub time: f64,
    pub bodies: Vec<(bool, Vec<usize>)>,
    pub precision: Precision,
    /// The fields written (`block` always).
    pub fields: FieldSet,
}

/// Escapes a string for an XML attribute or text node.
pub(crate) fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            c => o.push(c),
        }
    }
    o
}

/// What the document says about itself (`Information` elements).
const CONFIGURATION: &str = "The geometry of every time step is the current (deformed) \
configuration: /time/<k>/<body>/points; the displacement of a point is \
/time/<k>/<body>/points - /mesh/<body>/points. Do not apply Warp By Vector with a \
displacement: it adds the displacement a second time.";
const FIELD_NOTE: &str = "Every body and patch grid carries every field, so that a \
reader which merges them keeps all: body cells have the contact_pressure, \
contact_traction and gap of the contact patch face they bound (0, 0 and NaN if none); \
patch faces have the displacement, stress, von_mises and plastic_strain of the cell \
they bound; a body without plastic strain has 0.";

/// Renders the XDMF document from the already rendered time steps (see
/// [`render_step`]); without steps it shows the initial meshes, no time.
pub(crate) fn render(h5_name: &str, title: &str, bodies: &[BodyGrid], steps: &[String]) -> String {
    let mut x = String::with_capacity(1024 + steps.iter().map(String::len).sum::<usize>());
    x.push_str("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n");
    x.push_str("<Xdmf Version=\"3.0\">\n  <Domain>\n");
    let mut blocks: Vec<(usize, String)> = Vec::new();
    for b in bodies {
        blocks.push((b.block, b.name.clone()));
        for p in &b.patches {
            blocks.push((p.block, format!("{}/{}", b.name, p.name)));
        }
    }
    blocks.sort();
    let blocks: Vec<String> = blocks.iter().map(|(i, n)| format!("{i} {n}")).collect();
    for (name, value) in [
        ("configuration", CONFIGURATION.to_string()),
        ("fields", FIELD_NOTE.to_string()),
        ("block", format!("cell field block: {}", blocks.join(", "))),
    ] {
        let _ = writeln!(
            x,
            "    <Information Name=\"{name}\" Value=\"{}\"/>",
            esc(&value)
        );
    }
    let kind = if steps.is_empty() {
        "Spatial"
    } else {
        "Temporal"
    };
    let _ = writeln!(
        x,
        "    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"{kind}\">",
        esc(title)
    );
    if steps.is_empty() {
        let h5 = esc(h5_name);
        for b in bodies {
            let pts = format!("/mesh/{}/points", b.name);
            grid_open(
                &mut x,
                &h5,
                &b.name,
                b.vis_cells,
                &topology(b),
                &(pts, 8),
                b,
                "      ",
            );
            x.push_str("      </Grid>\n");
        }
    }
    for step in steps {
        x.push_str(step);
    }
    x.push_str("    </Grid>\n  </Domain>\n</Xdmf>\n");
    x
}

/// Renders one time step (a spatial collection of the body and patch
/// grids); rendered once per increment and kept, so that rewriting the
/// document costs a copy, not a re-rendering.
pub(crate) fn render_step(h5_name: &str, bodies: &[BodyGrid], inc: &IncrementRecord) -> String {
    let mut x = String::new();
    let h5 = esc(h5_name);
    let _ = writeln!(
        x,
        "      <Grid Name=\"increment {}\" GridType=\"Collection\" CollectionType=\"Spatial\">",
        inc.k
    );
    let _ = writeln!(x, "        <Time Value=\"{:e}\"/>", inc.time);
    let any_plastic = inc.bodies.iter().any(|(plastic, _)| *plastic);
    for (b, (plastic, patches)) in bodies.iter().zip(&inc.bodies) {
        let base = format!("/time/{}/{}", inc.k, b.name);
        let ind = "        ";
        let points = (format!("{base}/points"), inc.precision.bytes());
        grid_open(
            &mut x,
            &h5,
            &b.name,
            b.vis_cells,
            &topology(b),
            &points,
            b,
            ind,
        );
        let cells = if b.decomposed {
            format!("{base}/xdmf")
        } else {
            base.clone()
        };
        let mesh = format!("/mesh/{}/xdmf", b.name);
        let source = |field: &str| match field {
            "plastic_strain" if !plastic => format!("{mesh}/{}", zero(inc.precision)),
            "contact_pressure" | "contact_traction" | "gap" => format!("{base}/xdmf/{field}"),
            "block" => format!("{mesh}/block"),
            f => format!("{cells}/{f}"),
        };
        attributes(&mut x, &h5, b.vis_cells, any_plastic, inc, source);
        let _ = writeln!(x, "{ind}</Grid>");
        for &p in patches {
            let pg = &b.patches[p];
            if pg.n_faces == 0 {
                continue;
            }
            let name = format!("{}/{}", b.name, pg.name);
            let mesh = format!("/mesh/{}/patches/{}", b.name, pg.name);
            let topo = (format!("{mesh}/xdmf_topology"), pg.topo_len);
            grid_open(&mut x, &h5, &name, pg.n_faces, &topo, &points, b, ind);
            let faces = format!("{base}/{}", pg.name);
            let source = |field: &str| match field {
                "plastic_strain" if !plastic => format!("{mesh}/{}", zero(inc.precision)),
                "displacement" | "stress" | "von_mises" | "plastic_strain" => {
                    format!("{faces}/xdmf/{field}")
                }
                "block" => format!("{mesh}/block"),
                f => format!("{faces}/{f}"),
            };
            attributes(&mut x, &h5, pg.n_faces, any_plastic, inc, source);
            let _ = writeln!(x, "{ind}</Grid>");
        }
    }
    x.push_str("      </Grid>\n");
    x
}

/// The name of the constant 0 (per shown cell or patch face, under
/// `/mesh`) of a field in `precision`: an array that MergeBlocks appends
/// to one of another type is dropped.
pub(crate) fn zero(precision: Precision) -> &'static str {
    match precision {
        Precision::Double => "zero",
        Precision::Single => "zero_single",
    }
}

/// The body's topology dataset and its length.
fn topology(b: &BodyGrid) -> (String, usize) {
    (format!("/mesh/{}/xdmf/topology", b.name), b.topo_len)
}

/// Opens a uniform grid: its mixed topology and the body's points (the
/// dataset and its bytes per value).
#[allow(clippy::too_many_arguments)]
fn grid_open(
    x: &mut String,
    h5: &str,
    name: &str,
    n_cells: usize,
    (topo, topo_len): &(String, usize),
    (points, bytes): &(String, usize),
    b: &BodyGrid,
    ind: &str,
) {
    let _ = writeln!(x, "{ind}<Grid Name=\"{}\" GridType=\"Uniform\">", esc(name));
    let _ = writeln!(
        x,
        "{ind}  <Topology TopologyType=\"Mixed\" NumberOfElements=\"{n_cells}\">"
    );
    data_item(x, h5, topo, &[*topo_len], ("Int", 8), &format!("{ind}    "));
    let _ = writeln!(x, "{ind}  </Topology>");
    let _ = writeln!(x, "{ind}  <Geometry GeometryType=\"XYZ\">");
    data_item(
        x,
        h5,
        points,
        &[b.n_points, 3],
        ("Float", *bytes),
        &format!("{ind}    "),
    );
    let _ = writeln!(x, "{ind}  </Geometry>");
}

/// The attributes of [`FIELDS`], each from the dataset `source(name)`:
/// `block` 8-byte integers, the others floats in the increment's
/// precision.
fn attributes(
    x: &mut String,
    h5: &str,
    n_cells: usize,
    plastic: bool,
    inc: &IncrementRecord,
    source: impl Fn(&str) -> String,
) {
    let ind = "          ";
    for (name, kind, center) in FIELDS {
        if name == "plastic_strain" && !plastic || !inc.fields.holds_name(name) {
            continue;
        }
        let (dims, number) = match (name, kind) {
            ("block", _) => (vec![n_cells], "Int"),
            (_, "Vector") => (vec![n_cells, 3], "Float"),
            (_, "Tensor6") => (vec![n_cells, 6], "Float"),
            _ => (vec![n_cells], "Float"),
        };
        let _ = writeln!(
            x,
            "{ind}<Attribute Name=\"{name}\" AttributeType=\"{kind}\" Center=\"{center}\">"
        );
        let bytes = if name == "block" {
            8
        } else {
            inc.precision.bytes()
        };
        let item = (number, bytes);
        data_item(x, h5, &source(name), &dims, item, &format!("{ind}  "));
        let _ = writeln!(x, "{ind}</Attribute>");
    }
}

/// A DataItem of `path`: its number type and bytes per value.
fn data_item(
    x: &mut String,
    h5: &str,
    path: &str,
    dims: &[usize],
    (number, bytes): (&str, usize),
    ind: &str,
) {
    let dims: Vec<String> = dims.iter().map(|d| d.to_string()).collect();
    let _ = writeln!(
        x,
        "{ind}<DataItem Dimensions=\"{}\" NumberType=\"{number}\" Precision=\"{bytes}\" Format=\"HDF\">{h5}:{}</DataItem>",
        dims.join(" "),
        esc(path)
    );
}
