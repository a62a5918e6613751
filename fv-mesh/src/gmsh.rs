//! Gmsh MSH 4.1 import (ascii and binary) through the `mshio` crate.
//!
//! Volume elements (linear tetrahedra, hexahedra, prisms and pyramids)
//! become cells; the triangles and quadrilaterals of surface entities that
//! carry physical tags become boundary patches named after their physical
//! group (`$PhysicalNames`, or `patch<tag>` for an unnamed group). Boundary
//! faces in no group end up in the patch `defaultFaces`. Physical volume
//! groups are kept as [`CellZone`]s, but every volume element becomes a cell
//! whether it is in a physical volume or not.
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use mshio::ElementType;

use crate::extrude_plane::{extrude_plane, PlaneElements};
use crate::{CellShape, CellType, CellZone, FaceZone, MeshError, PolyMesh, Vector};

/// Reads a Gmsh MSH 4.1 file (ascii or binary) into a [`PolyMesh`].
///
/// Errors name the file; they are [`MeshError::Io`] when it cannot be read,
/// [`MeshError::Unsupported`] for higher-order elements and meshes without
/// volume elements, and [`MeshError::Parse`] for everything else
/// (wrong MSH version, malformed or truncated content, unknown node tags).
pub fn read_gmsh(path: &Path) -> Result<PolyMesh, MeshError> {
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_gmsh_bytes(&bytes, path)
}

/// Parses the content of a Gmsh MSH 4.1 file; `path` is only used in messages.
pub fn read_gmsh_bytes(bytes: &[u8], path: &Path) -> Result<PolyMesh, MeshError> {
    let err = |line: Option<usize>, message: String| MeshError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let header = parse_header(bytes).map_err(|m| err(None, m))?;
    check_not_truncated(bytes).map_err(|m| err(None, m))?;
    if let Some(at) = find_section_line(bytes, header.body_start, b"$PartitionedEntities") {
        return Err(err(
            (!header.binary).then(|| line_of(bytes, at)),
            "a partitioned mesh ($PartitionedEntities: gmsh -part, or Mesh.NbPartitions > 0) is not \
             supported: its physical groups are attached to the partition entities; re-export it \
             without partitioning"
                .into(),
        ));
    }
    let names = parse_physical_names(bytes, &header).map_err(|(line, m)| err(line, m))?;
    let patched = force_sparse_node_tags(bytes, &header).map_err(|m| err(None, m))?;

    let parsed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        mshio::parse_msh_bytes(&patched).map_err(|e| describe_mshio_error(&e, &patched, &header))
    }));
    let msh = match parsed {
        Ok(Ok(msh)) => msh,
        failed => {
            // an element type the parser does not know (some second-order
            // ones) fails it before `convert` can name the type
            if let Some((t, line)) = unsupported_element_type(bytes, &header) {
                return Err(MeshError::Unsupported(format!(
                    "{}{}: {}",
                    path.display(),
                    line.map(|l| format!(":{l}")).unwrap_or_default(),
                    unsupported_type_message(t)
                )));
            }
            return Err(match failed {
                Ok(Err((line, m))) => err(line, m),
                _ => err(
                    None,
                    "malformed MSH 4.1 content (the MSH parser gave up on it)".into(),
                ),
            });
        }
    };
    convert(msh, &names, path)
}

/// What the `$MeshFormat` section says.
struct Header {
    binary: bool,
    size_t: usize,
    /// Byte offset just after `$EndMeshFormat` and its line break.
    body_start: usize,
}

fn parse_header(bytes: &[u8]) -> Result<Header, String> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err("the file is empty: expected a Gmsh MSH 4.1 mesh".into());
    }
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(0);
    if !bytes[start..].starts_with(b"$MeshFormat") {
        return Err(
            "not a Gmsh mesh file: it does not start with $MeshFormat (a Gmsh MSH 4.1 file is expected)"
                .into(),
        );
    }
    let mut pos = start + b"$MeshFormat".len();
    // the format line: version file-type data-size
    let line_end = |from: usize| {
        bytes[from..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|p| from + p)
    };
    let Some(nl) = line_end(pos) else {
        return Err("truncated file: the $MeshFormat section ends prematurely".into());
    };
    if !bytes[pos..nl].iter().all(|b| b.is_ascii_whitespace()) {
        return Err("malformed $MeshFormat line".into());
    }
    pos = nl + 1;
    let Some(nl) = line_end(pos) else {
        return Err("truncated file: the $MeshFormat section ends prematurely".into());
    };
    let line = String::from_utf8_lossy(&bytes[pos..nl]).into_owned();
    let mut tok = line.split_whitespace();
    let version = tok.next().unwrap_or("");
    if version != "4.1" {
        let v: Option<f64> = version.parse().ok();
        return Err(match v {
            Some(v) if v < 4.0 && version.starts_with('2') => format!(
                "MSH {version} is not supported: re-export with Mesh.MshFileVersion = 4.1"
            ),
            Some(_) => format!(
                "MSH version {version} is not supported: MSH 4.1 is required (re-export with Mesh.MshFileVersion = 4.1)"
            ),
            None => format!("malformed $MeshFormat section: expected the version 4.1, found '{version}'"),
        });
    }
    let file_type = tok.next().unwrap_or("");
    let binary = match file_type {
        "0" => false,
        "1" => true,
        _ => {
            return Err(format!(
                "malformed $MeshFormat section: file type must be 0 (ascii) or 1 (binary), found '{file_type}'"
            ))
        }
    };
    let size_t = match tok.next().unwrap_or("") {
        "4" => 4,
        "8" => 8,
        other => {
            return Err(format!(
                "malformed $MeshFormat section: data size must be 4 or 8, found '{other}'"
            ))
        }
    };
    if tok.next().is_some() {
        return Err("malformed $MeshFormat section: extra values after the data size".into());
    }
    pos = nl + 1;
    if binary {
        // the integer 1 in the file's byte order, then a line break
        if bytes.len() < pos + 5 {
            return Err("truncated file: the $MeshFormat section ends prematurely".into());
        }
        let one = [bytes[pos], bytes[pos + 1], bytes[pos + 2], bytes[pos + 3]];
        if i32::from_le_bytes(one) != 1 && i32::from_be_bytes(one) != 1 {
            return Err(
                "malformed binary $MeshFormat section: the endianness marker is not 1".into(),
            );
        }
        pos += 4;
        if bytes[pos] == b'\n' {
            pos += 1;
        }
    }
    // $EndMeshFormat
    let rest = &bytes[pos..];
    let skip = rest
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(rest.len());
    if !rest[skip..].starts_with(b"$EndMeshFormat") {
        return Err(if rest[skip..].is_empty() {
            "truncated file: $EndMeshFormat missing".into()
        } else {
            "malformed $MeshFormat section: $EndMeshFormat expected".into()
        });
    }
    let mut body_start = pos + skip + b"$EndMeshFormat".len();
    while body_start < bytes.len() && bytes[body_start] != b'\n' {
        body_start += 1;
    }
    Ok(Header {
        binary,
        size_t,
        body_start: (body_start + 1).min(bytes.len()),
    })
}

/// Start offsets of lines that consist of `tag` (optionally followed by
/// `\r`), searched from `from`.
fn find_section_line(bytes: &[u8], from: usize, tag: &[u8]) -> Option<usize> {
    let mut i = from;
    while i + tag.len() <= bytes.len() {
        let at_line_start = i == 0 || bytes[i - 1] == b'\n';
        if at_line_start && bytes[i..].starts_with(tag) {
            let after = &bytes[i + tag.len()..];
            if after.is_empty() || after[0] == b'\n' || after.starts_with(b"\r\n") {
                return Some(i);
            }
        }
        match bytes[i..].iter().position(|&b| b == b'\n') {
            Some(p) => i += p + 1,
            None => return None,
        }
    }
    None
}

/// 1-based line of byte offset `off`.
fn line_of(bytes: &[u8], off: usize) -> usize {
    1 + bytes[..off.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// Nodes of the Gmsh element types that [`convert`] reads (point, line,
/// triangle, quadrangle, tetrahedron, hexahedron, prism, pyramid).
fn linear_element_nodes(gmsh_type: i32) -> Option<usize> {
    match gmsh_type {
        15 => Some(1),
        1 => Some(2),
        2 => Some(3),
        3 | 4 => Some(4),
        5 => Some(8),
        6 => Some(6),
        7 => Some(5),
        _ => None,
    }
}

/// Why an element type other than those of [`linear_element_nodes`] is
/// refused.
fn unsupported_type_message(gmsh_type: i32) -> String {
    let name = match gmsh_type {
        8 => " (3-node line)",
        9 => " (6-node triangle)",
        10 => " (9-node quadrangle)",
        11 => " (10-node tetrahedron)",
        12 => " (27-node hexahedron)",
        13 => " (18-node prism)",
        14 => " (14-node pyramid)",
        16 => " (8-node quadrangle)",
        17 => " (20-node hexahedron)",
        18 => " (15-node prism)",
        19 => " (13-node pyramid)",
        _ => "",
    };
    format!(
        "element type {gmsh_type}{name} is not supported: only linear elements are (tetrahedra, \
         hexahedra, prisms, pyramids; triangles and quadrangles on the boundary); re-mesh with \
         Mesh.ElementOrder = 1"
    )
}

/// The first element type in the `$Elements` section that
/// [`linear_element_nodes`] does not know, with its line (ascii files), by
/// walking the block headers; `None` when there is none or the section
/// cannot be walked.
fn unsupported_element_type(bytes: &[u8], header: &Header) -> Option<(i32, Option<usize>)> {
    let start = find_section_line(bytes, header.body_start, b"$Elements")?;
    let mut pos = start + b"$Elements".len();
    pos += bytes[pos..].iter().position(|&b| b == b'\n')? + 1;
    if header.binary {
        let st = header.size_t;
        let size_at = |p: usize| -> Option<u64> {
            let b = bytes.get(p..p + st)?;
            Some(if st == 8 {
                u64::from_le_bytes(b.try_into().ok()?)
            } else {
                u32::from_le_bytes(b.try_into().ok()?) as u64
            })
        };
        let int_at = |p: usize| -> Option<i32> {
            Some(i32::from_le_bytes(bytes.get(p..p + 4)?.try_into().ok()?))
        };
        let blocks = size_at(pos)?;
        pos += 4 * st;
        for _ in 0..blocks {
            let t = int_at(pos + 8)?;
            let n = size_at(pos + 12)? as usize;
            pos += 12 + st;
            let per = linear_element_nodes(t).map(|k| k + 1);
            match per {
                Some(per) => pos = pos.checked_add(n.checked_mul(per)?.checked_mul(st)?)?,
                None => return Some((t, None)),
            }
        }
        None
    } else {
        let text = std::str::from_utf8(&bytes[pos..]).ok()?;
        let mut lines = text.lines();
        let blocks: usize = lines.next()?.split_whitespace().next()?.parse().ok()?;
        let mut line = line_of(bytes, pos) + 1;
        for _ in 0..blocks {
            let head = lines.next()?;
            let v: Vec<i64> = head
                .split_whitespace()
                .map(|x| x.parse().ok())
                .collect::<Option<Vec<i64>>>()?;
            let (t, n) = (*v.get(2)? as i32, *v.get(3)? as usize);
            if linear_element_nodes(t).is_none() {
                return Some((t, Some(line)));
            }
            for _ in 0..n {
                lines.next()?;
            }
            line += n + 1;
        }
        None
    }
}

/// `(dimension, tag) → name` of physical groups.
type PhysicalNames = HashMap<(i32, i32), String>;

/// `(dimension, tag) → name` from the `$PhysicalNames` section (always ascii,
/// before the binary sections in files written by Gmsh).
fn parse_physical_names(
    bytes: &[u8],
    header: &Header,
) -> Result<PhysicalNames, (Option<usize>, String)> {
    let mut names = HashMap::new();
    // In a binary file only look before the first binary section.
    let limit = if header.binary {
        [
            &b"$Entities"[..],
            b"$Nodes",
            b"$Elements",
            b"$PartitionedEntities",
        ]
        .iter()
        .filter_map(|t| find_section_line(bytes, header.body_start, t))
        .min()
        .unwrap_or(bytes.len())
    } else {
        bytes.len()
    };
    let Some(start) = find_section_line(&bytes[..limit], header.body_start, b"$PhysicalNames")
    else {
        return Ok(names);
    };
    let start_line = line_of(bytes, start);
    let Some(end) = find_section_line(&bytes[..limit], start, b"$EndPhysicalNames") else {
        return Err((
            Some(start_line),
            "truncated $PhysicalNames section: $EndPhysicalNames missing".into(),
        ));
    };
    let text = String::from_utf8_lossy(&bytes[start..end]);
    let mut lines = text.lines().enumerate().skip(1);
    let count_line = lines.find(|(_, l)| !l.trim().is_empty());
    let Some((i, count)) = count_line else {
        return Err((Some(start_line), "empty $PhysicalNames section".into()));
    };
    let n: usize = count.trim().parse().map_err(|_| {
        (
            Some(start_line + i),
            format!(
                "$PhysicalNames: expected the number of names, found '{}'",
                count.trim()
            ),
        )
    })?;
    let mut read = 0usize;
    for (i, l) in lines {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        let line_no = Some(start_line + i);
        let bad = || {
            (
                line_no,
                format!("$PhysicalNames: expected 'dimension tag \"name\"', found '{l}'"),
            )
        };
        let mut it = l.splitn(3, char::is_whitespace);
        let dim: i32 = it.next().and_then(|s| s.parse().ok()).ok_or_else(bad)?;
        let rest = it.next().ok_or_else(bad)?;
        let tag: i32 = rest.parse().map_err(|_| bad())?;
        let name = it.next().ok_or_else(bad)?.trim();
        let name = name
            .strip_prefix('"')
            .and_then(|s| s.strip_suffix('"'))
            .ok_or_else(bad)?;
        // read lossily above: a name that is not UTF-8 would become one
        // that no case file can name
        if name.contains(char::REPLACEMENT_CHARACTER) {
            return Err((
                line_no,
                format!("$PhysicalNames: the name '{name}' is not UTF-8 text; save the mesh with names in UTF-8"),
            ));
        }
        names.insert((dim, tag), name.to_string());
        read += 1;
    }
    if read != n {
        return Err((
            Some(start_line),
            format!("$PhysicalNames announces {n} names but lists {read}"),
        ));
    }
    Ok(names)
}

/// `mshio` keeps the node tags of a block only when the file's tags are
/// sparse; for dense tags it assumes they follow the file order, which the
/// format does not guarantee. Raising `maxNodeTag` in the `$Nodes` header
/// (which mshio uses for nothing else) makes it keep the tags always.
fn force_sparse_node_tags(bytes: &[u8], header: &Header) -> Result<Vec<u8>, String> {
    let mut out = bytes.to_vec();
    // Nodes come after $Entities (binary) so search past it when possible.
    let from = if header.binary {
        find_section_line(bytes, header.body_start, b"$EndEntities").unwrap_or(header.body_start)
    } else {
        header.body_start
    };
    let Some(start) = find_section_line(bytes, from, b"$Nodes") else {
        return Ok(out); // reported later as "no nodes"
    };
    let mut pos = start + b"$Nodes".len();
    if bytes[pos..].starts_with(b"\r\n") {
        pos += 2;
    } else if pos < bytes.len() {
        pos += 1;
    }
    if header.binary {
        let field = pos + 3 * header.size_t;
        if field + header.size_t <= out.len() {
            out[field..field + header.size_t].fill(0xff);
        }
        return Ok(out);
    }
    // ascii: numEntityBlocks numNodes minNodeTag maxNodeTag
    let mut p = pos;
    for k in 0..4 {
        while p < out.len() && out[p].is_ascii_whitespace() {
            p += 1;
        }
        let tok_start = p;
        while p < out.len() && !out[p].is_ascii_whitespace() {
            p += 1;
        }
        if k == 3 && p > tok_start {
            let max = u64::MAX.to_string();
            out.splice(tok_start..p, max.bytes());
        }
    }
    Ok(out)
}

fn describe_mshio_error(
    e: &mshio::MshParserError<&[u8]>,
    buf: &[u8],
    header: &Header,
) -> (Option<usize>, String) {
    let trace = e.filtered_backtrace();
    // outermost context first; error kinds separately
    let mut contexts: Vec<String> = Vec::new();
    let mut causes: Vec<String> = Vec::new();
    for (_, kind) in trace.iter().rev() {
        match kind.context() {
            Some(c) => {
                if !contexts.iter().any(|x| x == c) {
                    contexts.push(c.to_string());
                }
            }
            None => {
                let s = kind.to_string();
                if !causes.contains(&s) {
                    causes.push(s);
                }
            }
        }
    }
    let location = trace.first().and_then(|(slice, _)| {
        let base = buf.as_ptr() as usize;
        let p = slice.as_ptr() as usize;
        (p >= base && p <= base + buf.len()).then(|| p - base)
    });
    let mut message = "malformed MSH 4.1 content".to_string();
    if !contexts.is_empty() {
        message.push_str(&format!(" (in {})", contexts.join(" > ")));
    }
    if !causes.is_empty() {
        message.push_str(&format!(": {}", causes.join(" ")));
    }
    match location {
        Some(o) if !header.binary => (Some(line_of(buf, o)), message),
        Some(o) => (None, format!("{message} at byte {o}")),
        None => (None, message),
    }
}

/// A complete MSH file ends with a `$End…` line; anything else was cut off.
fn check_not_truncated(bytes: &[u8]) -> Result<(), String> {
    let end = bytes.len()
        - bytes
            .iter()
            .rev()
            .take_while(|b| b.is_ascii_whitespace())
            .count();
    let last_line = bytes[..end]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    if bytes[last_line..end].starts_with(b"$End") {
        Ok(())
    } else {
        Err("truncated file: it does not end with the closing $End… line of a section".into())
    }
}

fn element_kind(t: ElementType) -> Option<CellType> {
    match t {
        ElementType::Tet4 => Some(CellType::Tetra),
        ElementType::Hex8 => Some(CellType::Hexa),
        ElementType::Pri6 => Some(CellType::Wedge),
        ElementType::Pyr5 => Some(CellType::Pyramid),
        _ => None,
    }
}

fn convert(
    msh: mshio::MshFile<u64, i32, f64>,
    names: &PhysicalNames,
    path: &Path,
) -> Result<PolyMesh, MeshError> {
    let parse_err = |message: String| MeshError::Parse {
        path: path.to_path_buf(),
        line: None,
        message,
    };
    let unsupported = |what: String| MeshError::Unsupported(format!("{}: {what}", path.display()));

    // physical tags of surface and volume entities
    let mut curve_phys: HashMap<i32, Vec<i32>> = HashMap::new();
    let mut surface_phys: HashMap<i32, Vec<i32>> = HashMap::new();
    let mut volume_phys: HashMap<i32, Vec<i32>> = HashMap::new();
    if let Some(ent) = &msh.data.entities {
        for c in &ent.curves {
            if !c.physical_tags.is_empty() {
                curve_phys.insert(c.tag, c.physical_tags.clone());
            }
        }
        for s in &ent.surfaces {
            if !s.physical_tags.is_empty() {
                surface_phys.insert(s.tag, s.physical_tags.clone());
            }
        }
        for v in &ent.volumes {
            if !v.physical_tags.is_empty() {
                volume_phys.insert(v.tag, v.physical_tags.clone());
            }
        }
    }

    // nodes: tag → index in file order
    let Some(nodes) = &msh.data.nodes else {
        return Err(parse_err(
            "the file has no $Nodes section, so it holds no mesh (truncated?)".into(),
        ));
    };
    let mut coords: Vec<Vector> = Vec::new();
    let mut index_of: HashMap<u64, u32> = HashMap::new();
    for block in &nodes.node_blocks {
        let tags: Vec<(u64, usize)> = match &block.node_tags {
            Some(map) => map.iter().map(|(&t, &i)| (t, i)).collect(),
            // dense tags, in file order (only when the header could not be patched)
            None => (0..block.nodes.len())
                .map(|i| {
                    (
                        nodes.min_node_tag.wrapping_add((coords.len() + i) as u64),
                        i,
                    )
                })
                .collect(),
        };
        if tags.len() != block.nodes.len() {
            return Err(parse_err(format!(
                "node block of entity ({}, {}) repeats a node tag",
                block.entity_dim, block.entity_tag
            )));
        }
        let base = coords.len();
        for n in &block.nodes {
            let v = Vector::new(n.x, n.y, n.z);
            if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
                return Err(parse_err(format!(
                    "a node of entity ({}, {}) has a non-finite coordinate",
                    block.entity_dim, block.entity_tag
                )));
            }
            coords.push(v);
        }
        if coords.len() >= u32::MAX as usize {
            return Err(unsupported("more than 2^32 - 1 nodes".into()));
        }
        for (t, i) in tags {
            if index_of.insert(t, (base + i) as u32).is_some() {
                return Err(parse_err(format!("node tag {t} is defined twice")));
            }
        }
    }

    let Some(elements) = &msh.data.elements else {
        return Err(unsupported(
            "the file has no $Elements section, so no volume elements: a 3D mesh is required"
                .into(),
        ));
    };
    // volume elements → cells (file node indices for now)
    let mut cells: Vec<CellShape> = Vec::new();
    let mut cell_volume_entity: Vec<i32> = Vec::new();
    let lookup = |t: u64, etag: u64| -> Result<u32, MeshError> {
        index_of.get(&t).copied().ok_or_else(|| {
            parse_err(format!(
                "element {etag} refers to node tag {t}, which is not in the $Nodes section"
            ))
        })
    };
    // the 2-D elements: boundary faces of a volume mesh, or the cells of a
    // plane mesh to extrude
    let mut plane = PlaneElements::default();
    for block in &elements.element_blocks {
        let t = block.element_type;
        match t {
            ElementType::Pnt => continue,
            ElementType::Lin2 => {
                let Some(phys) = curve_phys.get(&block.entity_tag) else {
                    continue;
                };
                let segments = block
                    .elements
                    .iter()
                    .map(|e| match e.nodes[..] {
                        [a, b] => Ok([lookup(a, e.element_tag)?, lookup(b, e.element_tag)?]),
                        _ => Err(parse_err(format!(
                            "line element {} has {} nodes, not 2",
                            e.element_tag,
                            e.nodes.len()
                        ))),
                    })
                    .collect::<Result<Vec<[u32; 2]>, _>>()?;
                for &p in phys {
                    let name = names
                        .get(&(1, p))
                        .cloned()
                        .unwrap_or_else(|| format!("patch{p}"));
                    plane.edges.entry(name).or_default().extend(&segments);
                }
            }
            ElementType::Tri3 | ElementType::Qua4 => {
                for e in &block.elements {
                    let f = e
                        .nodes
                        .iter()
                        .map(|&n| lookup(n, e.element_tag))
                        .collect::<Result<Vec<u32>, _>>()?;
                    let expected = if t == ElementType::Tri3 { 3 } else { 4 };
                    if f.len() != expected {
                        return Err(parse_err(format!(
                            "element {} has {} nodes, {t:?} needs {expected}",
                            e.element_tag,
                            f.len()
                        )));
                    }
                    plane.faces.push((f, block.entity_tag));
                }
            }
            _ => {
                let Some(kind) = element_kind(t) else {
                    return Err(unsupported(format!(
                        "element type {t:?} (Gmsh type {}) in entity ({}, {}) is not supported: only linear \
                         elements are (tetrahedra, hexahedra, prisms, pyramids; triangles and quadrangles on \
                         the boundary); re-mesh with Mesh.ElementOrder = 1",
                        t as i32, block.entity_dim, block.entity_tag
                    )));
                };
                for e in &block.elements {
                    let nodes = e
                        .nodes
                        .iter()
                        .map(|&n| lookup(n, e.element_tag))
                        .collect::<Result<Vec<u32>, _>>()?;
                    if nodes.len() != kind.n_nodes() {
                        return Err(parse_err(format!(
                            "element {} has {} nodes, {kind:?} needs {}",
                            e.element_tag,
                            nodes.len(),
                            kind.n_nodes()
                        )));
                    }
                    cells.push(CellShape {
                        kind,
                        nodes: nodes.into(),
                    });
                    cell_volume_entity.push(block.entity_tag);
                }
            }
        }
    }
    if cells.is_empty() && !plane.faces.is_empty() {
        return plane_mesh(&coords, &plane, &surface_phys, names, path);
    }
    if cells.is_empty() {
        return Err(unsupported(
            "the mesh has no volume elements (tetrahedra, hexahedra, prisms, pyramids) and no 2D \
             elements (triangles, quadrangles) to extrude: mesh the volume (gmsh -3) or the plane \
             (gmsh -2). If the .geo defines physical groups, Gmsh saves only the elements in them: add \
             a Physical Volume (or Physical Surface) or set Mesh.SaveAll = 1"
                .into(),
        ));
    }
    if cells.len() >= u32::MAX as usize {
        return Err(unsupported("more than 2^32 - 1 cells".into()));
    }

    // keep only the nodes of volume elements, renumbered in file order
    let mut new_index = vec![u32::MAX; coords.len()];
    for c in &cells {
        for &n in &c.nodes {
            new_index[n as usize] = 0;
        }
    }
    let mut points = Vec::new();
    for (i, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = points.len() as u32;
            points.push(coords[i]);
        }
    }
    for c in &mut cells {
        for n in &mut c.nodes {
            *n = new_index[*n as usize];
        }
    }
    // physical surface tag → faces (file node indices)
    let mut groups: BTreeMap<i32, Vec<&[u32]>> = BTreeMap::new();
    for (f, entity) in &plane.faces {
        for &p in surface_phys.get(entity).into_iter().flatten() {
            groups.entry(p).or_default().push(f);
        }
    }
    let mut boundary_groups: Vec<(String, Vec<Vec<u32>>)> = Vec::new();
    for (tag, faces) in groups {
        let faces: Vec<Vec<u32>> = faces
            .into_iter()
            .filter_map(|f| {
                f.iter()
                    .map(|&n| Some(new_index[n as usize]).filter(|&m| m != u32::MAX))
                    .collect::<Option<Vec<u32>>>()
            })
            .collect();
        let name = names
            .get(&(2, tag))
            .cloned()
            .unwrap_or_else(|| format!("patch{tag}"));
        if let Some(g) = boundary_groups.iter_mut().find(|g| g.0 == name) {
            g.1.extend(faces);
        } else {
            boundary_groups.push((name, faces));
        }
    }

    assemble(
        points,
        cells,
        &boundary_groups,
        &cell_volume_entity,
        &volume_phys,
        (3, "volume"),
        names,
        path,
    )
}

/// The mesh of a file without volume elements: its 2-D elements extruded
/// one cell thick ([`extrude_plane`]); physical surfaces become cell zones.
fn plane_mesh(
    coords: &[Vector],
    plane: &PlaneElements,
    surface_phys: &HashMap<i32, Vec<i32>>,
    names: &PhysicalNames,
    path: &Path,
) -> Result<PolyMesh, MeshError> {
    let e = extrude_plane(coords, plane)
        .map_err(|m| MeshError::Unsupported(format!("{}: {m}", path.display())))?;
    assemble(
        e.points,
        e.cells,
        &e.boundary_groups,
        &e.cell_entity,
        surface_phys,
        (2, "surface"),
        names,
        path,
    )
}

/// The [`PolyMesh`] of `cells` with its patches; the cells of each physical
/// group of dimension `zone_kind.0` (through their entity `cell_entity`
/// and `entity_phys`) become a [`CellZone`] named after the group, or
/// `<zone_kind.1><tag>`.
#[allow(clippy::too_many_arguments)]
fn assemble(
    points: Vec<Vector>,
    cells: Vec<CellShape>,
    boundary_groups: &[(String, Vec<Vec<u32>>)],
    cell_entity: &[i32],
    entity_phys: &HashMap<i32, Vec<i32>>,
    zone_kind: (i32, &str),
    names: &PhysicalNames,
    path: &Path,
) -> Result<PolyMesh, MeshError> {
    // a boundary face in two groups would take the condition of one of them
    // only; the other would silently lose it
    let mut group_of: HashMap<Vec<u32>, usize> = HashMap::new();
    for (gi, (name, faces)) in boundary_groups.iter().enumerate() {
        for f in faces {
            let mut key = f.clone();
            key.sort_unstable();
            key.dedup();
            if let Some(&other) = group_of.get(&key) {
                if other != gi {
                    return Err(MeshError::Parse {
                        path: path.to_path_buf(),
                        line: None,
                        message: format!(
                            "a boundary face (nodes at {}) is in two physical groups, '{}' and \
                             '{name}': a face takes one boundary condition, so the groups must not \
                             share faces",
                            f.iter()
                                .map(|&n| format!("{:?}", points[n as usize].as_slice()))
                                .collect::<Vec<_>>()
                                .join(" "),
                            boundary_groups[other].0
                        ),
                    });
                }
            }
            group_of.insert(key, gi);
        }
    }
    let mut zones: BTreeMap<i32, Vec<u32>> = BTreeMap::new();
    for (ci, ent) in cell_entity.iter().enumerate() {
        for &p in entity_phys.get(ent).into_iter().flatten() {
            zones.entry(p).or_default().push(ci as u32);
        }
    }
    let mut mesh = PolyMesh::from_cells(points, cells, boundary_groups).map_err(|e| match e {
        MeshError::Invalid(m) => MeshError::Parse {
            path: path.to_path_buf(),
            line: None,
            message: format!("invalid mesh: {m}"),
        },
        other => other,
    })?;
    // a physical surface between two physical volumes lies on internal
    // faces: kept as a face zone, the patch of that name where a body is
    // cut out along it (`zone = ...`)
    let mut face_zones: Vec<FaceZone> = Vec::new();
    for f in 0..mesh.n_internal_faces() {
        let mut key = mesh.face(f).to_vec();
        key.sort_unstable();
        key.dedup();
        if let Some(&gi) = group_of.get(&key) {
            let name = &boundary_groups[gi].0;
            match face_zones.iter_mut().find(|z| &z.name == name) {
                Some(z) => z.faces.push(f as u32),
                None => face_zones.push(FaceZone {
                    name: name.clone(),
                    faces: vec![f as u32],
                }),
            }
        }
    }
    mesh.face_zones = face_zones;
    mesh.cell_zones = zones
        .into_iter()
        .map(|(tag, cells)| CellZone {
            name: names
                .get(&(zone_kind.0, tag))
                .cloned()
                .unwrap_or_else(|| format!("{}{tag}", zone_kind.1)),
            cells,
        })
        .collect();
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MeshGeometry;
    use crate::{FRONT_AND_BACK, PLANE_THICKNESS};
    use std::path::PathBuf;

    fn read(text: &str) -> Result<PolyMesh, MeshError> {
        read_gmsh_bytes(text.as_bytes(), Path::new("test.msh"))
    }

    fn patch_sizes(m: &PolyMesh) -> Vec<(String, usize)> {
        m.patches.iter().map(|p| (p.name.clone(), p.size)).collect()
    }

    fn volume(m: &PolyMesh) -> f64 {
        MeshGeometry::new(m).expect("valid geometry").total_volume()
    }

    /// Unit cube, one hexahedron, sparse node tags (10, 20, …, 80) written in
    /// a shuffled order. Groups: bottom (z=0), top (z=1), sides (y=0, y=1 and
    /// x=0, two entities with one physical tag); the face x=1 is in no group.
    const HEX: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
2 1 \"bottom\"
2 2 \"top\"
2 3 \"sides\"
3 4 \"cube\"
$EndPhysicalNames
$Entities
0 0 5 1
1 0 0 0 1 1 0 1 1 0
2 0 0 1 1 1 1 1 2 0
3 0 0 0 1 0 1 1 3 0
4 0 0 0 0 1 1 1 3 0
5 1 0 0 1 1 1 0 0
1 0 0 0 1 1 1 1 4 0
$EndEntities
$Nodes
2 8 10 80
2 1 0 4
10
20
30
40
0 0 0
1 0 0
1 1 0
0 1 0
3 1 0 4
80
60
50
70
0 1 1
1 0 1
0 0 1
1 1 1
$EndNodes
$Elements
6 7 1 7
2 1 3 1
1 10 40 30 20
2 2 3 1
2 50 60 70 80
2 3 3 2
3 10 20 60 50
4 40 30 70 80
2 4 3 1
5 10 50 80 40
2 5 3 1
6 20 30 70 60
3 1 5 1
7 10 20 30 40 50 60 70 80
$EndElements
";

    #[test]
    fn single_hexahedron() {
        let m = read(HEX).expect("reads");
        assert_eq!(m.n_cells, 1);
        assert_eq!(m.n_points(), 8);
        assert_eq!(m.n_internal_faces(), 0);
        assert_eq!(
            patch_sizes(&m),
            vec![
                ("bottom".into(), 1),
                ("top".into(), 1),
                ("sides".into(), 3),
                ("defaultFaces".into(), 1)
            ]
        );
        assert!((volume(&m) - 1.0).abs() < 1e-12);
        // the top face really is the one at z = 1
        let g = MeshGeometry::new(&m).expect("geometry");
        let top = m.patches[m.patch_index("top").expect("top")].start;
        assert!((g.face_centres[top].z - 1.0).abs() < 1e-12);
        assert!(g.face_normal(top).z > 0.99);
        let d = m.patches[m.patch_index("defaultFaces").expect("default")].start;
        assert!((g.face_centres[d].x - 1.0).abs() < 1e-12);
        assert_eq!(m.cell_zones.len(), 1);
        assert_eq!(m.cell_zones[0].name, "cube");
        assert_eq!(m.cell_zones[0].cells, vec![0]);
        let shapes = m.cell_shapes.as_ref().expect("shapes");
        assert_eq!(shapes[0].kind, CellType::Hexa);
    }

    /// A face in two physical groups would keep the condition of one only:
    /// refused, naming both.
    #[test]
    fn a_face_in_two_groups_is_an_error() {
        let text = HEX.replace("2 0 0 1 1 1 1 1 2 0", "2 0 0 1 1 1 1 2 2 1 0");
        let e = read(&text).expect_err("overlapping groups");
        let m = e.to_string();
        assert!(
            m.contains("two physical groups") && m.contains("'bottom'") && m.contains("'top'"),
            "{m}"
        );
    }

    /// A physical group named `defaultFaces` takes the faces in no group:
    /// one patch of that name.
    #[test]
    fn a_group_named_default_faces_takes_the_ungrouped_faces() {
        let text = HEX.replace("\"sides\"", "\"defaultFaces\"");
        let m = read(&text).expect("reads");
        assert_eq!(
            patch_sizes(&m),
            vec![
                ("bottom".into(), 1),
                ("top".into(), 1),
                ("defaultFaces".into(), 4)
            ]
        );
    }

    /// A partitioned file keeps its physical groups on the partition
    /// entities: refused with advice, not read as a mesh without groups.
    #[test]
    fn a_partitioned_mesh_is_refused() {
        let text = HEX.replace(
            "$Nodes",
            "$PartitionedEntities\n2\n0\n0 0 0 0\n$EndPartitionedEntities\n$Nodes",
        );
        let e = read(&text).expect_err("partitioned");
        assert!(e.to_string().contains("partitioned mesh"), "{e}");
    }

    /// Element types the parser may not know are found by walking the
    /// `$Elements` block headers, ascii and binary.
    #[test]
    fn second_order_types_are_named_from_the_block_headers() {
        let text = HEX.replace("3 1 5 1\n", "3 1 13 1\n");
        let header = parse_header(text.as_bytes()).expect("header");
        let (t, line) = unsupported_element_type(text.as_bytes(), &header).expect("found");
        assert_eq!(t, 13);
        let line = line.expect("ascii line");
        assert_eq!(text.lines().nth(line - 1), Some("3 1 13 1"));
        assert!(unsupported_type_message(t).contains("18-node prism"));
        assert!(unsupported_element_type(HEX.as_bytes(), &header).is_none());
        // binary, 8-byte size_t: a quadrangle block, then a 14-node pyramid
        let mut b: Vec<u8> = b"$MeshFormat\n4.1 1 8\n".to_vec();
        b.extend(1i32.to_le_bytes());
        b.extend(b"\n$EndMeshFormat\n$Elements\n");
        for v in [2u64, 2, 1, 2] {
            b.extend(v.to_le_bytes());
        }
        for (dim, t, nodes) in [(2i32, 3i32, 4u64), (3, 14, 14)] {
            b.extend(dim.to_le_bytes());
            b.extend(1i32.to_le_bytes());
            b.extend(t.to_le_bytes());
            b.extend(1u64.to_le_bytes());
            for v in 0..=nodes {
                b.extend(v.to_le_bytes());
            }
        }
        b.extend(b"\n$EndElements\n");
        let header = parse_header(&b).expect("binary header");
        assert_eq!(unsupported_element_type(&b, &header), Some((14, None)));
    }

    /// Unit cube split along the x-y diagonal into two prisms; the x=0 face is
    /// in an unnamed physical group (tag 7), the other sides in no group. No
    /// physical volume. Node tags are dense but written in reverse order.
    const PRISMS: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 \"bottom\"
2 2 \"top\"
$EndPhysicalNames
$Entities
0 0 3 1
1 0 0 0 1 1 0 1 1 0
2 0 0 1 1 1 1 1 2 0
3 0 0 0 0 1 1 1 7 0
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
1 8 1 8
3 1 0 8
8
7
6
5
4
3
2
1
0 1 1
1 1 1
1 0 1
0 0 1
0 1 0
1 1 0
1 0 0
0 0 0
$EndNodes
$Elements
4 7 1 7
2 1 2 2
1 1 2 3
2 1 3 4
2 2 2 2
3 5 6 7
4 5 7 8
2 3 3 1
5 1 4 8 5
3 1 6 2
6 1 2 3 5 6 7
7 1 3 4 5 7 8
$EndElements
";

    #[test]
    fn two_prisms() {
        let m = read(PRISMS).expect("reads");
        assert_eq!(m.n_cells, 2);
        assert_eq!(m.n_internal_faces(), 1);
        assert_eq!(
            patch_sizes(&m),
            vec![
                ("bottom".into(), 2),
                ("top".into(), 2),
                ("patch7".into(), 1),
                ("defaultFaces".into(), 3)
            ]
        );
        assert!((volume(&m) - 1.0).abs() < 1e-12);
        let g = MeshGeometry::new(&m).expect("geometry");
        for f in m.patches[0].faces() {
            assert!(g.face_centres[f].z.abs() < 1e-12, "bottom at z = 0");
            assert!(g.face_normal(f).z < -0.99, "bottom normal points down");
        }
        let p7 = &m.patches[2];
        assert!(g.face_centres[p7.start].x.abs() < 1e-12);
        assert!(m.cell_zones.is_empty());
        let shapes = m.cell_shapes.as_ref().expect("shapes");
        assert!(shapes.iter().all(|s| s.kind == CellType::Wedge));
    }

    /// Unit cube as six tetrahedra around the main diagonal (Kuhn split);
    /// only the bottom (2 triangles) and top (2 triangles) are grouped.
    const TETS: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
2 11 \"bottom\"
2 12 \"top\"
$EndPhysicalNames
$Entities
0 0 2 1
1 0 0 0 1 1 0 1 11 0
2 0 0 1 1 1 1 1 12 0
1 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
1 8 1 8
3 1 0 8
1
2
3
4
5
6
7
8
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
$EndNodes
$Elements
3 10 1 10
2 1 2 2
1 1 2 3
2 1 3 4
2 2 2 2
3 5 6 7
4 5 7 8
3 1 4 6
5 1 2 3 7
6 1 3 4 7
7 1 4 8 7
8 1 8 5 7
9 1 5 6 7
10 1 6 2 7
$EndElements
";

    #[test]
    fn six_tetrahedra() {
        let m = read(TETS).expect("reads");
        assert_eq!(m.n_cells, 6);
        assert_eq!(m.n_internal_faces(), 6);
        assert_eq!(
            patch_sizes(&m),
            vec![
                ("bottom".into(), 2),
                ("top".into(), 2),
                ("defaultFaces".into(), 8)
            ]
        );
        assert!((volume(&m) - 1.0).abs() < 1e-12);
    }

    /// Unit cube as six pyramids on its faces with the apex at the centre,
    /// the pyramid on the top face split into two tetrahedra. Groups: "lid"
    /// (the two top triangles), "walls" (four side quads); the bottom quad is
    /// in no group.
    const PYRAMIDS_AND_TETS: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
2 1 \"lid\"
2 2 \"walls\"
3 3 \"all\"
$EndPhysicalNames
$Entities
0 0 2 1
1 0 0 1 1 1 1 1 1 0
2 0 0 0 1 1 1 1 2 0
1 0 0 0 1 1 1 1 3 0
$EndEntities
$Nodes
1 9 1 9
3 1 0 9
1
2
3
4
5
6
7
8
9
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
0.5 0.5 0.5
$EndNodes
$Elements
4 13 1 13
2 1 2 2
1 5 6 7
2 5 7 8
2 2 3 4
3 1 2 6 5
4 2 3 7 6
5 3 4 8 7
6 4 1 5 8
3 1 7 5
7 1 2 3 4 9
8 1 2 6 5 9
9 2 3 7 6 9
10 3 4 8 7 9
11 4 1 5 8 9
3 1 4 2
12 5 6 7 9
13 5 7 8 9
$EndElements
";

    #[test]
    fn pyramids_and_tetrahedra() {
        let m = read(PYRAMIDS_AND_TETS).expect("reads");
        assert_eq!(m.n_cells, 7);
        assert_eq!(m.n_internal_faces(), 13);
        // 12 triangles (cube edge + centre) between neighbouring cells and
        // one between the two tetrahedra
        assert_eq!(
            patch_sizes(&m),
            vec![
                ("lid".into(), 2),
                ("walls".into(), 4),
                ("defaultFaces".into(), 1)
            ]
        );
        assert!((volume(&m) - 1.0).abs() < 1e-12);
        let shapes = m.cell_shapes.as_ref().expect("shapes");
        assert_eq!(
            shapes
                .iter()
                .filter(|s| s.kind == CellType::Pyramid)
                .count(),
            5
        );
        assert_eq!(m.cell_zones[0].cells.len(), 7);
    }

    #[test]
    fn unknown_node_tag_is_an_error() {
        let bad = HEX.replace("7 10 20 30 40 50 60 70 80", "7 10 20 30 40 50 60 70 99");
        let e = read(&bad).expect_err("unknown tag");
        let s = e.to_string();
        assert!(s.contains("node tag 99"), "{s}");
        assert!(matches!(e, MeshError::Parse { .. }));
    }

    #[test]
    fn higher_order_is_rejected() {
        // a 10-node tetrahedron
        let bad = TETS
            .replace("3 1 4 6\n", "3 1 11 1\n")
            .replace(
                "5 1 2 3 7\n6 1 3 4 7\n7 1 4 8 7\n8 1 8 5 7\n9 1 5 6 7\n10 1 6 2 7\n",
                "5 1 2 3 7 1 2 3 4 5 6\n",
            )
            .replace("3 10 1 10", "3 5 1 5");
        let e = read(&bad).expect_err("higher order");
        assert!(matches!(e, MeshError::Unsupported(_)), "{e}");
        assert!(e.to_string().contains("ElementOrder = 1"), "{e}");
    }

    /// A plane mesh, 2 × 1 in z = 0: two triangles (the second written
    /// clockwise) and a quadrangle; physical curves "left" (x = 0),
    /// "bottom" (y = 0) and "right" (x = 2), the top edges in no group,
    /// physical surface "plate".
    const PLANE: &str = include_str!("../tests/data/plate_2d.msh");

    /// Two hexahedra side by side whose shared face is the physical
    /// surface "mid" (tests/data/two_cubes_mid.geo): the face is internal,
    /// kept as a face zone, and a body cut out of either cube has it as its
    /// patch "mid", not in `defaultFaces` (found by a probe, 2026-12-01:
    /// the name a user gave an interface between two physical volumes was
    /// lost, and the contact naming it refused).
    #[test]
    fn a_physical_surface_between_volumes_names_the_cut() {
        let m = read(include_str!("../tests/data/two_cubes_mid.msh")).expect("reads");
        assert_eq!(m.n_internal_faces(), 1);
        assert_eq!(m.face_zones.len(), 1);
        assert_eq!(m.face_zones[0].name, "mid");
        assert_eq!(m.face_zones[0].faces, [0]);
        for cell in [0u32, 1] {
            let one = m.subset(&[cell]).expect("subset");
            let names: Vec<&str> = one.patches.iter().map(|p| p.name.as_str()).collect();
            assert!(names.contains(&"mid"), "{names:?}");
            // the cube's four faces in no group, not the cut face
            let d = one.patch_index("defaultFaces").expect("defaultFaces");
            assert_eq!(one.patches[d].size, 4, "{names:?}");
            let mid = one.patch_index("mid").expect("mid");
            assert_eq!(one.patches[mid].size, 1);
            // the cut face points out of the cube that keeps it
            let g = MeshGeometry::new(&one).expect("geometry");
            let f = one.patches[mid].start;
            let out = g.face_centres[f] - g.cell_centres[0];
            assert!(out.dot(&g.face_normal(f)) > 0.0);
        }
    }

    /// A physical curve named as the extrusion's caps: two patches of one
    /// name, the case's condition reaching the first only (found by a
    /// probe, 2026-12-01). Refused, naming the file.
    #[test]
    fn a_curve_named_front_and_back_is_refused() {
        let bad = PLANE.replace("\"right\"", &format!("\"{FRONT_AND_BACK}\""));
        assert_ne!(bad, PLANE);
        let e = read(&bad).expect_err("reserved name");
        assert!(e.to_string().contains("rename the curve"), "{e}");
    }

    /// A physical name in Latin-1 (found by a probe, 2026-12-01): it
    /// became a patch name no case could type.
    #[test]
    fn a_physical_name_that_is_not_utf8_is_refused() {
        let mut bytes = PLANE.as_bytes().to_vec();
        let at = PLANE.find("\"right\"").expect("right") + 2;
        bytes[at] = 0xe4; // 'ä' in Latin-1
        let e = read_gmsh_bytes(&bytes, Path::new("test.msh")).expect_err("not UTF-8");
        assert!(e.to_string().contains("not UTF-8"), "{e}");
    }

    #[test]
    fn a_plane_mesh_is_extruded_one_cell_thick() {
        let m = read(PLANE).expect("reads");
        assert_eq!(m.n_cells, 3);
        assert_eq!(m.n_points(), 12);
        // the triangle–triangle and triangle–quadrangle edges
        assert_eq!(m.n_internal_faces(), 2);
        let mut sizes = patch_sizes(&m);
        sizes.sort();
        assert_eq!(
            sizes,
            vec![
                ("bottom".into(), 2),
                ("defaultFaces".into(), 2),
                (FRONT_AND_BACK.into(), 6),
                ("left".into(), 1),
                ("right".into(), 1),
            ]
        );
        // area 2 × thickness 1, every cell right side up
        assert!((volume(&m) - 2.0 * PLANE_THICKNESS).abs() < 1e-12);
        let g = MeshGeometry::new(&m).expect("geometry");
        assert!(g.cell_volumes.iter().all(|&v| v > 0.0));
        let shapes = m.cell_shapes.as_ref().expect("shapes");
        let kinds: Vec<CellType> = shapes.iter().map(|s| s.kind).collect();
        assert_eq!(kinds, [CellType::Wedge, CellType::Wedge, CellType::Hexa]);
        assert_eq!(m.cell_zones.len(), 1);
        assert_eq!(m.cell_zones[0].name, "plate");
        assert_eq!(m.cell_zones[0].cells, [0, 1, 2]);
    }

    #[test]
    fn a_plane_mesh_off_the_xy_plane_is_rejected() {
        // node 6 lifted to z = 0.5
        let bad = PLANE.replace("2 1 0\n$EndNodes", "2 1 0.5\n$EndNodes");
        let e = read(&bad).expect_err("not plane");
        assert!(matches!(e, MeshError::Unsupported(_)), "{e}");
        assert!(e.to_string().contains("one plane z = const"), "{e}");
    }

    #[test]
    fn surface_only_mesh_is_rejected() {
        let bad = HEX
            .replace("6 7 1 7", "5 6 1 6")
            .replace("3 1 5 1\n7 10 20 30 40 50 60 70 80\n", "");
        let e = read(&bad).expect_err("2D only");
        assert!(matches!(e, MeshError::Unsupported(_)), "{e}");
        assert!(e.to_string().contains("no volume elements"), "{e}");
    }

    #[test]
    fn msh22_is_rejected_with_advice() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n";
        let e = read(text).expect_err("2.2");
        let s = e.to_string();
        assert!(
            s.contains("MSH 2.2 is not supported: re-export with Mesh.MshFileVersion = 4.1"),
            "{s}"
        );
        let e = read("$MeshFormat\n4 0 8\n$EndMeshFormat\n").expect_err("4.0");
        let s = e.to_string();
        assert!(
            s.contains("version 4") && s.contains("4.1 is required"),
            "{s}"
        );
    }

    #[test]
    fn truncated_empty_garbage_and_text_are_errors() {
        let half = &HEX.as_bytes()[..HEX.len() / 2];
        let e = read_gmsh_bytes(half, Path::new("half.msh")).expect_err("truncated");
        let s = e.to_string();
        assert!(s.contains("half.msh") && s.contains("truncated"), "{s}");
        // cut at every line as well: never a panic, always an error
        for (i, _) in HEX.match_indices('\n').step_by(3) {
            if i + 1 < HEX.len() - 1 {
                assert!(read_gmsh_bytes(&HEX.as_bytes()[..i + 1], Path::new("t.msh")).is_err());
            }
        }
        let e = read("").expect_err("empty");
        assert!(e.to_string().contains("empty"), "{e}");
        let mut garbage = Vec::new();
        let mut x: u32 = 12345;
        for _ in 0..4096 {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
            garbage.push((x >> 16) as u8);
        }
        let e = read_gmsh_bytes(&garbage, Path::new("g.msh")).expect_err("garbage");
        assert!(e.to_string().contains("$MeshFormat"), "{e}");
        // garbage after a valid header
        let mut g2 = b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n".to_vec();
        g2.extend_from_slice(&garbage);
        assert!(read_gmsh_bytes(&g2, Path::new("g2.msh")).is_err());
        let mut g3 = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n".to_vec();
        g3.extend_from_slice(&garbage);
        assert!(read_gmsh_bytes(&g3, Path::new("g3.msh")).is_err());
        let e = read("solid cube\n facet normal 0 0 1\nendsolid\n").expect_err("text");
        assert!(e.to_string().contains("$MeshFormat"), "{e}");
        assert!(read_gmsh(Path::new("/nonexistent/file.msh")).is_err());
    }

    fn data(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name)
    }

    #[test]
    fn gmsh_written_ascii_and_binary_agree() {
        let a = read_gmsh(&data("box_ascii.msh")).expect("ascii fixture");
        let b = read_gmsh(&data("box_binary.msh")).expect("binary fixture");
        assert!(a.n_cells > 50);
        assert_eq!(a.n_cells, b.n_cells);
        // ascii coordinates carry 16 significant digits
        assert_eq!(a.n_points(), b.n_points());
        for (p, q) in a.points.iter().zip(&b.points) {
            assert!((p - q).norm() < 1e-14);
        }
        assert_eq!(a.face_points, b.face_points);
        assert_eq!(a.owner, b.owner);
        assert_eq!(a.patches, b.patches);
        let names: Vec<&str> = a.patches.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(
            names,
            ["xmin", "xmax", "sides", "bottom", "top", "defaultFaces"]
        );
        let g = MeshGeometry::new(&a).expect("geometry");
        assert!((g.total_volume() - 0.125).abs() < 1e-12);
        let area = |name: &str| -> f64 {
            let p = &a.patches[a.patch_index(name).expect("patch")];
            p.faces().map(|f| g.face_mag(f)).sum()
        };
        assert!((area("xmin") - 0.125).abs() < 1e-12);
        assert!((area("bottom") - 0.5).abs() < 1e-12);
        assert!((area("defaultFaces") - 0.25).abs() < 1e-12);
        for f in a.patches[a.patch_index("defaultFaces").expect("d")].faces() {
            assert!((g.face_centres[f].y - 0.5).abs() < 1e-12);
            assert!(g.face_normal(f).y > 0.999);
        }
        assert_eq!(a.cell_zones.len(), 1);
        assert_eq!(a.cell_zones[0].name, "box");
        assert_eq!(a.cell_zones[0].cells.len(), a.n_cells);
    }

    #[test]
    fn truncated_binary_is_an_error() {
        let bytes = std::fs::read(data("box_binary.msh")).expect("fixture");
        for cut in [bytes.len() / 2, bytes.len() / 3, bytes.len() - 20, 40, 200] {
            let e = read_gmsh_bytes(&bytes[..cut], Path::new("cut.msh")).expect_err("cut");
            assert!(e.to_string().contains("cut.msh"), "{e}");
        }
        // flipped bytes inside the binary data: an error or a mesh, never a panic
        let mut x: u32 = 7;
        for _ in 0..50 {
            let mut b = bytes.clone();
            for _ in 0..8 {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                let i = 200 + (x as usize >> 8) % (b.len() - 200);
                b[i] ^= (x >> 3) as u8 | 1;
            }
            let _ = read_gmsh_bytes(&b, Path::new("flip.msh"));
        }
    }

    #[test]
    fn quarter_annulus_example() {
        let p =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/quarter-annulus/annulus.msh");
        if !p.exists() {
            eprintln!("skipped: {} not found", p.display());
            return;
        }
        let m = read_gmsh(&p).expect("annulus");
        assert_eq!(m.n_cells, 600);
        let mut names: Vec<(String, usize)> = patch_sizes(&m);
        names.sort();
        assert_eq!(
            names,
            vec![
                ("frontAndBack".into(), 1200),
                ("inner".into(), 30),
                ("outer".into(), 30),
                ("symx".into(), 20),
                ("symy".into(), 20),
            ]
        );
        let g = MeshGeometry::new(&m).expect("geometry");
        let exact = std::f64::consts::FRAC_PI_4 * 3.0 * 0.1;
        assert!((g.total_volume() - exact).abs() < 2e-3 * exact);
        let sx = &m.patches[m.patch_index("symx").expect("symx")];
        for f in sx.faces() {
            assert!(g.face_centres[f].x.abs() < 1e-9);
        }
        assert_eq!(m.cell_zones[0].name, "annulus");
    }
}
