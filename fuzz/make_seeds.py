#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (docs/fuzzing.md).

fuzz/corpus/{case,gmsh,polymesh}/seed-*: the project's own cases and meshes
(validation/cases, examples, fv-mesh/tests/data), shrunk to fit the targets'
bounds, and hand-made edge cases (truncated, counts too large, NaN, negative
tags, deep nesting, huge tables). Also fuzz/fixtures/polyMesh, the polyMesh
the case seeds refer to. Findings are added by hand as find-* files and are
not touched here. Run from the repository root: python3 fuzz/make_seeds.py
"""
import pathlib
import re
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
FUZZ = ROOT / "fuzz"
CORPUS = FUZZ / "corpus"
SEP = b"\0"  # fvc_fuzz::POLYMESH_SEPARATOR


def write(target, name, data):
    d = CORPUS / target
    d.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    (d / f"seed-{name}").write_bytes(data)


def clear_seeds():
    for p in CORPUS.glob("*/seed-*"):
        p.unlink()


def cuts(data, n):
    """`n` truncations of `data` spread over its length."""
    return [data[: len(data) * k // (n + 1)] for k in range(1, n + 1)]


# ---------------------------------------------------------------- polyMesh


def foam_header(cls, obj, note=None):
    note = f'    note        "{note}";\n' if note else ""
    return (
        "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
        f"    class       {cls};\n{note}    object      {obj};\n}}\n\n"
    )


def box_polymesh(nx, ny, nz, zones=True, compact=False):
    """A unit-spaced box of nx*ny*nz hexahedra in OpenFOAM order: internal
    faces in upper-triangular order, then the patches xmin..zmax."""
    pid = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    cid = lambda i, j, k: i + nx * (j + ny * k)
    points = [
        (i, j, k) for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)
    ]

    def quad(axis, i, j, k):
        # normal +axis at the lower corner (i, j, k)
        if axis == 0:
            return [pid(i, j, k), pid(i, j + 1, k), pid(i, j + 1, k + 1), pid(i, j, k + 1)]
        if axis == 1:
            return [pid(i, j, k), pid(i, j, k + 1), pid(i + 1, j, k + 1), pid(i + 1, j, k)]
        return [pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k), pid(i, j + 1, k)]

    faces, owner, neigh = [], [], []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = cid(i, j, k)
                if i + 1 < nx:
                    faces.append(quad(0, i + 1, j, k)); owner.append(c); neigh.append(cid(i + 1, j, k))
                if j + 1 < ny:
                    faces.append(quad(1, i, j + 1, k)); owner.append(c); neigh.append(cid(i, j + 1, k))
                if k + 1 < nz:
                    faces.append(quad(2, i, j, k + 1)); owner.append(c); neigh.append(cid(i, j, k + 1))
    patches = []
    for name, axis, lo in [("xmin", 0, 1), ("xmax", 0, 0), ("ymin", 1, 1), ("ymax", 1, 0), ("zmin", 2, 1), ("zmax", 2, 0)]:
        start = len(faces)
        n = [nx, ny, nz]
        a, b = [d for d in range(3) if d != axis]
        for u in range(n[b]):
            for v in range(n[a]):
                idx = [0, 0, 0]
                idx[a], idx[b] = v, u
                idx[axis] = 0 if lo else n[axis]
                cell = list(idx)
                cell[axis] = 0 if lo else n[axis] - 1
                f = quad(axis, *idx)
                faces.append(f[::-1] if lo else f)
                owner.append(cid(*cell))
        patches.append((name, start, len(faces) - start))
    n_cells = nx * ny * nz
    note = f"nPoints: {len(points)} nCells: {n_cells} nFaces: {len(faces)} nInternalFaces: {len(neigh)}"
    pts = foam_header("vectorField", "points") + f"{len(points)}\n(\n" + "".join(
        f"({x} {y} {z})\n" for x, y, z in points) + ")\n"
    if compact:
        offs = [0]
        for f in faces:
            offs.append(offs[-1] + len(f))
        fcs = foam_header("faceCompactList", "faces") + f"{len(offs)}\n(\n" + "\n".join(map(str, offs)) + "\n)\n"
        labels = [p for f in faces for p in f]
        fcs += f"{len(labels)}\n(\n" + "\n".join(map(str, labels)) + "\n)\n"
    else:
        fcs = foam_header("faceList", "faces") + f"{len(faces)}\n(\n" + "".join(
            f"4({' '.join(map(str, f))})\n" for f in faces) + ")\n"
    own = foam_header("labelList", "owner", note) + f"{len(owner)}\n(\n" + "\n".join(map(str, owner)) + "\n)\n"
    nei = foam_header("labelList", "neighbour", note) + f"{len(neigh)}\n(\n" + "\n".join(map(str, neigh)) + "\n)\n"
    bnd = foam_header("polyBoundaryMesh", "boundary") + f"{len(patches)}\n(\n" + "".join(
        f"    {n}\n    {{\n        type            patch;\n        nFaces          {s};\n        startFace       {st};\n    }}\n"
        for n, st, s in patches) + ")\n"
    files = [pts, fcs, own, nei, bnd]
    if zones:
        half = n_cells // 2
        z = foam_header("regIOobject", "cellZones") + "2\n(\n"
        z += f"lower\n{{\n    type cellZone;\n    cellLabels List<label> {half}({' '.join(map(str, range(half)))});\n}}\n"
        z += f"upper\n{{\n    type cellZone;\n    cellLabels List<label> {n_cells - half}({' '.join(map(str, range(half, n_cells)))});\n}}\n)\n"
        files.append(z)
    return [f.encode() for f in files]


def polymesh_seeds():
    names = ["points", "faces", "owner", "neighbour", "boundary", "cellZones"]
    fix = FUZZ / "fixtures" / "polyMesh"
    fix.mkdir(parents=True, exist_ok=True)
    for name, data in zip(names, box_polymesh(2, 1, 1)):
        (fix / name).write_bytes(data)
    base = box_polymesh(2, 1, 1)
    write("polymesh", "box-2x1x1", SEP.join(base))
    write("polymesh", "box-2x2x2", SEP.join(box_polymesh(2, 2, 2)))
    write("polymesh", "box-3x2x1-nozones", SEP.join(box_polymesh(3, 2, 1, zones=False)))
    write("polymesh", "box-2x1x1-compact", SEP.join(box_polymesh(2, 1, 1, compact=True)))
    write("polymesh", "box-1x1x1", SEP.join(box_polymesh(1, 1, 1)))
    write("polymesh", "empty", b"")
    write("polymesh", "four-files", SEP.join(base[:4]))
    for i, name in enumerate(names):
        for k, cut in enumerate(cuts(base[i], 3)):
            f = list(base)
            f[i] = cut
            write("polymesh", f"cut-{name}-{k}", SEP.join(f))

    def edit(tag, i, old, new, count=1):
        f = list(base)
        assert old in f[i], (tag, old)
        f[i] = f[i].replace(old, new, count)
        write("polymesh", tag, SEP.join(f))

    edit("points-count-huge", 0, b"12\n(", b"999999999999\n(")
    edit("points-count-negative", 0, b"12\n(", b"-12\n(")
    edit("points-nan", 0, b"(1 0 0)", b"(nan 0 0)")
    edit("points-inf", 0, b"(1 0 0)", b"(1e999 0 0)")
    edit("points-uniform-huge", 0, b"12\n(", b"4000000000{(0 0 0)}\n(")
    edit("points-binary", 0, b"format      ascii", b"format      binary")
    edit("points-unterminated-comment", 0, b"12\n(", b"/* 12\n(")
    edit("points-unterminated-string", 0, b"12\n(", b"\"12\n(")
    edit("faces-count-huge", 1, b"11\n(", b"99999999999999\n(")
    edit("faces-uniform-face", 1, b"4(1 7 6 0)", b"100000{0}")
    edit("faces-negative-label", 1, b"4(1 4 10 7)", b"4(-1 4 10 7)")
    edit("faces-label-past-points", 1, b"4(1 4 10 7)", b"4(1 4 10 700)")
    edit("faces-two-points", 1, b"4(1 4 10 7)", b"2(1 4)")
    edit("faces-label-i64-max", 1, b"4(1 4 10 7)", b"4(1 4 10 9223372036854775807)")
    edit("faces-label-past-i64", 1, b"4(1 4 10 7)", b"4(1 4 10 99999999999999999999)")
    edit("owner-negative", 2, b"\n0\n", b"\n-5\n")
    edit("owner-note-wrong", 2, b"nCells: 2", b"nCells: 99999999999999999999")
    edit("neighbour-same-as-owner", 3, b"1\n(\n1\n)", b"1\n(\n0\n)")
    edit("neighbour-padded", 3, b"1\n(\n1\n)", b"11\n(\n1\n-1\n-1\n-1\n-1\n-1\n-1\n-1\n-1\n-1\n-1\n)")
    edit("neighbour-too-many", 3, b"1\n(\n1\n)", b"12{1}")
    edit("boundary-nfaces-huge", 4, b"nFaces          1;", b"nFaces          9223372036854775807;")
    edit("boundary-startface-huge", 4, b"startFace       3;", b"startFace       9223372036854775807;")
    edit("boundary-nfaces-negative", 4, b"nFaces          1;", b"nFaces          -1;")
    edit("boundary-duplicate-name", 4, b"xmax", b"xmin")
    edit("boundary-nested-dict", 4, b"type            patch;", b"sub { a { b { c 1; } } }\n type patch;")
    edit("boundary-deep-parens", 4, b"type            patch;", b"type " + b"(" * 2000 + b")" * 2000 + b" patch;")
    edit("boundary-unbalanced", 4, b"type            patch;", b"type ) patch;")
    edit("cellzones-label-past-cells", 5, b"List<label> 1(1)", b"List<label> 1(7)")
    edit("cellzones-uniform-huge", 5, b"List<label> 1(1)", b"List<label> 4000000000{1}")
    edit("cellzones-duplicate", 5, b"upper", b"lower")
    edit("cellzones-empty", 5, b"List<label> 1(1)", b"List<label> 0()")


# ---------------------------------------------------------------- Gmsh

GMSH_FILES = [
    "fv-mesh/tests/data/box_ascii.msh",
    "fv-mesh/tests/data/box_binary.msh",
    "fv-mesh/tests/data/plate_2d.msh",
    "fv-mesh/tests/data/two_cubes_apart.msh",
    "fv-mesh/tests/data/two_cubes_mid.msh",
    "validation/cases/axisymmetric-bar/bar.msh",
    "validation/cases/axisymmetric-bar/bar-offset.msh",
    "examples/shallow-ironing/block.msh",
    "examples/die-drawing/cylinder.msh",
    "examples/die-drawing/die.msh",
]


def gmsh_seeds():
    for f in GMSH_FILES:
        p = ROOT / f
        write("gmsh", f"{p.parent.name}-{p.name}", p.read_bytes())
    plate = (ROOT / "fv-mesh/tests/data/plate_2d.msh").read_bytes()
    cubes = (ROOT / "fv-mesh/tests/data/two_cubes_mid.msh").read_bytes()
    binary = (ROOT / "fv-mesh/tests/data/box_binary.msh").read_bytes()
    for k, c in enumerate(cuts(cubes, 6)):
        write("gmsh", f"cubes-cut-{k}", c + b"\n$EndElements\n")
    for k, c in enumerate(cuts(binary, 6)):
        write("gmsh", f"binary-cut-{k}", c + b"\n$EndElements\n")
    write("gmsh", "empty", b"")
    write("gmsh", "whitespace", b" \n\t\n")
    write("gmsh", "text", b"hello world\n")

    def edit(tag, base, old, new):
        assert old in base, (tag, old)
        write("gmsh", tag, base.replace(old, new, 1))

    edit("version-22", plate, b"4.1 0 8", b"2.2 0 8")
    edit("version-40", plate, b"4.1 0 8", b"4.0 0 8")
    edit("version-nan", plate, b"4.1 0 8", b"nan 0 8")
    edit("datasize-4", plate, b"4.1 0 8", b"4.1 0 4")
    edit("datasize-huge", plate, b"4.1 0 8", b"4.1 0 99999999999999999999")
    edit("filetype-binary", plate, b"4.1 0 8", b"4.1 1 8")
    edit("names-count-huge", plate, b"$PhysicalNames\n4\n", b"$PhysicalNames\n999999999999\n")
    edit("names-count-negative", plate, b"$PhysicalNames\n4\n", b"$PhysicalNames\n-4\n")
    edit("names-unterminated", plate, b'"left"', b'"left')
    edit("names-negative-tag", plate, b'1 1 "left"', b'1 -1 "left"')
    edit("names-dimension-9", plate, b'1 1 "left"', b'9 1 "left"')
    edit("entities-count-huge", plate, b"0 3 1 0\n", b"0 3 999999999999 0\n")
    edit("entities-negative-physical", plate, b"1 0 0 0 2 1 0 1 4 0", b"1 0 0 0 2 1 0 1 -4 0")
    edit("nodes-count-huge", plate, b"1 6 1 6\n", b"1 999999999999999 1 6\n")
    edit("nodes-blocks-huge", plate, b"1 6 1 6\n", b"99999999999 6 1 6\n")
    edit("nodes-block-count-huge", plate, b"2 1 0 6\n", b"2 1 0 999999999999\n")
    edit("nodes-tag-zero", plate, b"\n1\n2\n", b"\n0\n2\n")
    edit("nodes-tag-negative", plate, b"\n1\n2\n", b"\n-1\n2\n")
    edit("nodes-tag-duplicate", plate, b"\n1\n2\n", b"\n1\n1\n")
    edit("nodes-tag-huge", plate, b"\n1\n2\n", b"\n18446744073709551615\n2\n")
    edit("nodes-nan", plate, b"1 0 0\n", b"nan 0 0\n")
    edit("nodes-inf", plate, b"1 0 0\n", b"inf 0 0\n")
    edit("nodes-parametric", plate, b"2 1 0 6\n", b"2 1 1 6\n")
    edit("nodes-off-plane", plate, b"1 0 0\n", b"1 0 5\n")
    edit("elements-count-huge", plate, b"5 7 1 7\n", b"5 999999999999999 1 7\n")
    edit("elements-blocks-huge", plate, b"5 7 1 7\n", b"99999999999 7 1 7\n")
    edit("elements-block-count-huge", plate, b"2 1 3 1\n", b"2 1 3 99999999999\n")
    edit("elements-node-missing", plate, b"5 2 3 6 5", b"5 2 3 6 77")
    edit("elements-node-negative", plate, b"5 2 3 6 5", b"5 2 3 6 -5")
    edit("elements-type-unknown", plate, b"2 1 3 1\n", b"2 1 999 1\n")
    edit("elements-type-second-order", plate, b"2 1 3 1\n", b"2 1 10 1\n")
    edit("elements-type-negative", plate, b"2 1 3 1\n", b"2 1 -3 1\n")
    edit("elements-degenerate-quad", plate, b"5 2 3 6 5", b"5 2 2 2 2")
    edit("partitioned", plate, b"$Entities", b"$PartitionedEntities\n$EndPartitionedEntities\n$Entities")
    edit("no-end-nodes", plate, b"$EndNodes\n", b"")
    edit("two-formats", plate, b"$EndMeshFormat\n", b"$EndMeshFormat\n$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
    edit("cubes-hex-repeated-node", cubes, b"4 3 1 2 4 7 6 5 8", b"4 3 3 3 3 3 3 3 3")
    edit("cubes-no-volume", cubes, b"3 1 5 1\n4 3 1 2 4 7 6 5 8 \n3 2 5 1\n5 7 6 5 8 11 9 10 12 \n", b"")
    # binary: the $Nodes header's numNodes (a size_t) set huge
    i = binary.index(b"$Nodes\n") + len(b"$Nodes\n")
    b = bytearray(binary)
    b[i + 8 : i + 16] = struct.pack("<Q", 2**62)
    write("gmsh", "binary-nodes-count-huge", bytes(b))
    b = bytearray(binary)
    b[i : i + 8] = struct.pack("<Q", 2**62)
    write("gmsh", "binary-node-blocks-huge", bytes(b))
    j = binary.index(b"$Elements\n") + len(b"$Elements\n")
    b = bytearray(binary)
    b[j : j + 8] = struct.pack("<Q", 2**62)
    write("gmsh", "binary-element-blocks-huge", bytes(b))


# ---------------------------------------------------------------- case

CASE_DIRS = ["validation/cases", "examples"]


def shrink_case(text):
    """A project case fitted to the case target: no comments, meshes from
    the fixtures, at most 4 cells a direction, few increments."""
    lines = [l for l in text.splitlines() if not l.lstrip().startswith("#")]
    text = "\n".join(l for l in lines if l.strip()) + "\n"
    if re.search(r'file\s*=\s*"', text):
        # Gmsh meshes → stacked generated boxes, the patch names mapped to
        # the box's (so that the conditions and contacts are checked)
        k = iter(range(100))
        text = re.sub(r'mesh\s*=\s*\{\s*file\s*=[^}]*\}',
                      lambda m: (lambda z: f'mesh = {{ generator = "box", min = [0, 0, {z}], max = [1, 1, {z + 1}], cells = [2, 2, 2] }}')(next(k)),
                      text)
        names = []
        for n in re.findall(r'\[body\.boundary\.([A-Za-z0-9_-]+)\]', text) + re.findall(r'"[A-Za-z0-9_-]+/([A-Za-z0-9_-]+)"', text):
            if n not in names:
                names.append(n)
        box = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
        for i, n in enumerate(names):
            new = box[i % 6]
            text = re.sub(r'\[body\.boundary\.' + re.escape(n) + r'\]', f"[body.boundary.{new}]", text)
            text = re.sub(r'("[A-Za-z0-9_-]+/)' + re.escape(n) + '"', lambda m: m.group(1) + new + '"', text)
    text = re.sub(r'polymesh\s*=\s*"[^"]*"', 'polymesh = "polyMesh"', text)
    text = re.sub(r"cells\s*=\s*\[([^\]]*)\]",
                  lambda m: "cells = [" + ", ".join(str(min(int(x), 4) if int(x) % 2 == 0 else min(int(x), 3)) for x in m.group(1).split(",")) + "]",
                  text)
    text = re.sub(r"steps\s*=\s*\d+", "steps = 2", text)
    return text


VALID = {
    "box-generator": """title = "t"
[time]
end = 1.0
steps = 1
[[body]]
name = "b"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [2, 2, 2] }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.xmax]
type = "traction"
value = [1, 0, 0]
""",
    "gmsh-fixture": """title = "g"
[time]
end = 1.0
steps = 2
[[body]]
name = "b"
mesh = { file = "box.msh", scale = 2, translate = [1, 0, 0] }
material = { model = "neo-hookean", E = 1e3, nu = 0.3 }
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.xmax]
type = "displacement"
value = [0.01, 0, 0]
""",
    "polymesh-fixture": """title = "p"
[time]
end = 1.0
steps = 1
[[body]]
name = "lower"
mesh = { polymesh = "polyMesh", zone = "lower" }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[[body]]
name = "upper"
mesh = { polymesh = "polyMesh", zone = "upper" }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.xmax]
type = "displacement"
value = [0, 0, 0]
""",
    "two-blocks-contact": """title = "c"
[time]
end = 1.0
steps = 2
[[body]]
name = "lower"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [2, 2, 2] }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[[body]]
name = "upper"
mesh = { generator = "box", min = [0, 0, 1], max = [1, 1, 2], cells = [2, 2, 1] }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.zmax]
type = "displacement"
value = [0, 0, -0.01]
[[contact]]
master = "lower/zmax"
slave = "upper/zmin"
friction = 0.2
""",
    "plate-2d": """title = "plate"
[analysis]
kind = "static"
[time]
end = 1.0
steps = 1
[[body]]
name = "plate"
mesh = { file = "plate.msh" }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.left]
type = "displacement"
value = [0, 0, 0]
""",
    "cubes-regions": """title = "r"
[time]
end = 1.0
steps = 1
[[body]]
name = "a"
mesh = { file = "cubes.msh", zone = "solid" }
material = { model = "linear-elastic", E = 1e3, nu = 0.3 }
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
""",
}


def case_seeds():
    for d in CASE_DIRS:
        for p in sorted((ROOT / d).glob("*/*.toml")):
            write("case", f"{p.parent.name}-{p.stem}", shrink_case(p.read_text()))
    for name, text in VALID.items():
        write("case", f"valid-{name}", text)
    base = VALID["two-blocks-contact"]
    for k, c in enumerate(cuts(base.encode(), 5)):
        write("case", f"cut-{k}", c)

    def edit(tag, old, new, text=base):
        assert old in text, (tag, old)
        write("case", tag, text.replace(old, new, 1))

    edit("nan-modulus", "E = 1e3", "E = nan")
    edit("inf-friction", "friction = 0.2", "friction = inf")
    edit("negative-cells", "cells = [2, 2, 2]", "cells = [-2, 2, 2]")
    edit("cells-huge", "cells = [2, 2, 2]", "cells = [4294967296, 4294967296, 4294967296]")
    edit("cells-i64-max", "cells = [2, 2, 2]", "cells = [9223372036854775807, 1, 1]")
    edit("box-inverted", "max = [1, 1, 1]", "max = [-1, 1, 1]")
    edit("box-nan", "max = [1, 1, 1]", "max = [nan, 1, 1]")
    edit("steps-huge", "steps = 2", "steps = 9223372036854775807")
    edit("step-tiny", "steps = 2", "step = 1e-300")
    edit("intervals-empty", "end = 1.0\nsteps = 2", "intervals = []")
    edit("time-table", "value = [0, 0, -0.01]",
         "value = { table = [" + ", ".join(f"[{t / 100}, [0, 0, {-t / 1e4}]]" for t in range(101)) + "] }")
    edit("time-table-huge", "value = [0, 0, -0.01]",
         "value = { table = [" + ", ".join(f"[{t}, [0, 0, 0]]" for t in range(5000)) + "] }")
    edit("time-table-unsorted", "value = [0, 0, -0.01]",
         "value = { table = [[1, [0, 0, 0]], [0, [0, 0, 1]]] }")
    edit("unknown-key", "friction = 0.2", "friction = 0.2\nfrobnicate = 1")
    edit("duplicate-key", "friction = 0.2", "friction = 0.2\nfriction = 0.3")
    edit("same-body-contact", 'slave = "upper/zmin"', 'slave = "lower/zmax"')
    edit("unknown-patch", 'slave = "upper/zmin"', 'slave = "upper/nowhere"')
    edit("overlap", "min = [0, 0, 1]", "min = [0, 0, 0.5]")
    edit("mesh-absolute-path", 'mesh = { generator = "box", min = [0, 0, 1]',
         'mesh = { file = "/nonexistent/x.msh" }\nm = { generator = "box", min = [0, 0, 1]')
    edit("nu-half", "nu = 0.3", "nu = 0.5")
    edit("rigid-both", 'name = "lower"', 'name = "lower"\nrigid = true')
    write("case", "deep-array", "title = \"d\"\nx = " + "[" * 5000 + "]" * 5000 + "\n")
    write("case", "deep-inline-table", "title = \"d\"\nx = " + "{a = " * 5000 + "1" + "}" * 5000 + "\n")
    write("case", "deep-dotted-key", "title = \"d\"\n" + ".".join(["a"] * 5000) + " = 1\n")
    write("case", "deep-table-header", "title = \"d\"\n[" + ".".join(["a"] * 5000) + "]\n")
    write("case", "many-bodies", 'title = "m"\n[time]\nend = 1\nsteps = 1\n' + "".join(
        f'[[body]]\nname = "b{i}"\nmesh = {{ generator = "box", min = [{i}, 0, 0], max = [{i + 1}, 1, 1], cells = [1, 1, 1] }}\n'
        f'material = {{ model = "linear-elastic", E = 1e3, nu = 0.3 }}\n' for i in range(200)))
    write("case", "invalid-utf8", base.encode().replace(b'"c"', b'"\xff\xfe"'))
    write("case", "bom", b"\xef\xbb\xbf" + base.encode())
    write("case", "empty", b"")
    write("case", "nul-bytes", base.encode().replace(b"\n", b"\0\n", 3))


if __name__ == "__main__":
    clear_seeds()
    polymesh_seeds()
    gmsh_seeds()
    case_seeds()
    for t in ["case", "gmsh", "polymesh"]:
        files = list((CORPUS / t).iterdir())
        print(t, len(files), "files", sum(f.stat().st_size for f in files), "bytes")
