#!/usr/bin/env python3
"""Print every group, dataset and attribute of an fvc results file and check
it against the layout of CASE_FORMAT.md ("Results").

usage:  python3 scripts/check_h5.py RESULTS/<title>/<title>.h5 [--increments N] [--quiet]

Needs h5py (pip install h5py). Prints each object with its shape, type and
a few values (attributes in full), then checks:
  - /mesh/<body>/points (n_points x 3) and cells/{connectivity,offsets,types}
    with offsets from 0 to len(connectivity) and VTK codes 5,7,9,10,12,13,14,42;
  - /time/<k> with attributes time, outer_iterations, residual, converged;
  - per body: points (n_points x 3), displacement (n_cells x 3), stress
    (n_cells x 6), von_mises (n_cells, equal to the von Mises stress of
    `stress` to the precision stored), plastic_strain (n_cells) when present;
    point_displacement (n_points x 3) in files written before it was dropped;
  - per patch: face_centres (n x 3), contact_pressure (n, >= 0),
    contact_traction (n x 3), gap (n), one n per patch;
  - /history (rows x columns, with a `columns` attribute) when present;
  - /increments and /times when present: the k of every /time/<k> in the
    order written (increasing) and their times, equal to the attributes;
  - field datasets of files with that index (written since issue 45):
    attributes units and location, components (their column names) on
    those with columns;
  - with --increments N: exactly N increments.
Exits 1 if anything is missing or inconsistent.
"""
import argparse
import sys

import h5py
import numpy as np

BODY_FIELDS = {"points", "point_displacement", "displacement", "stress", "von_mises", "plastic_strain", "xdmf"}
PATCH_FIELDS = ("face_centres", "contact_pressure", "contact_traction", "gap")


def show(value, n=6):
    a = np.asarray(value)
    if a.dtype.kind in "OSU":
        a = np.array([x.decode() if isinstance(x, bytes) else x for x in a.ravel()]).reshape(a.shape)
    flat = a.ravel()
    text = ", ".join(str(x) for x in flat[:n])
    return f"[{text}{', ...' if flat.size > n else ''}]" if a.ndim else str(a)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--increments", type=int, help="expected number of increments")
    ap.add_argument("--quiet", action="store_true", help="only the checks, no listing")
    opts = ap.parse_args()
    quiet, want = opts.quiet, opts.increments
    problems = []
    f = h5py.File(opts.file, "r")

    def visit(name, obj):
        if quiet:
            return
        if isinstance(obj, h5py.Dataset):
            extra = ""
            if obj.chunks:
                extra = f", chunks {obj.chunks}, maxshape {obj.maxshape}"
            print(f"/{name}  dataset {obj.shape} {obj.dtype}{extra}  {show(obj[()])}")
        else:
            print(f"/{name}  group")
        for k, v in obj.attrs.items():
            print(f"/{name}  @{k} = {show(v, 50)}")

    if not quiet:
        for k, v in f.attrs.items():
            print(f"/  @{k} = {show(v, 50)}")
    f.visititems(visit)

    def need(group, key, shape=None):
        if key not in group:
            problems.append(f"missing {group.name}/{key}")
            return None
        d = group[key]
        if shape is not None and d.shape != shape:
            problems.append(f"{d.name}: shape {d.shape}, expected {shape}")
        return d

    meshes = {}
    for body, g in f.get("mesh", {}).items():
        pts = need(g, "points")
        conn = need(g, "cells/connectivity")
        off = need(g, "cells/offsets")
        types = need(g, "cells/types")
        if pts is None or off is None or types is None or conn is None:
            continue
        np_, nc = pts.shape[0], types.shape[0]
        if pts.shape != (np_, 3):
            problems.append(f"{pts.name}: shape {pts.shape}")
        o = off[()]
        if off.shape != (nc + 1,) or o[0] != 0 or o[-1] != conn.shape[0] or np.any(np.diff(o.astype(np.int64)) < 0):
            problems.append(f"{off.name}: not {nc + 1} increasing offsets from 0 to {conn.shape[0]}")
        bad = set(np.unique(types[()]).tolist()) - {5, 7, 9, 10, 12, 13, 14, 42}
        if bad:
            problems.append(f"{types.name}: unknown VTK codes {sorted(bad)}")
        if conn.shape[0] and conn[()].max() >= np_:
            problems.append(f"{conn.name}: point index out of range")
        meshes[body] = (np_, nc)
    if not meshes:
        problems.append("no /mesh/<body> groups")

    steps = sorted(f.get("time", {}).keys(), key=int)
    if want is not None and len(steps) != want:
        problems.append(f"{len(steps)} increments, expected {want}")
    patch_faces = {}
    for k in steps:
        g = f["time"][k]
        for a in ("time", "outer_iterations", "residual", "converged"):
            if a not in g.attrs:
                problems.append(f"/time/{k} lacks attribute {a}")
        for body, (np_, nc) in meshes.items():
            if body not in g:
                problems.append(f"missing /time/{k}/{body}")
                continue
            b = g[body]
            need(b, "points", (np_, 3))
            if "point_displacement" in b:
                need(b, "point_displacement", (np_, 3))
            need(b, "displacement", (nc, 3))
            s = need(b, "stress", (nc, 6))
            vm = need(b, "von_mises", (nc,))
            if "plastic_strain" in b:
                need(b, "plastic_strain", (nc,))
            if s is not None and vm is not None and s.shape == (nc, 6) and vm.shape == (nc,):
                x = s[()].astype(np.float64)
                ref = np.sqrt(
                    0.5 * ((x[:, 0] - x[:, 1]) ** 2 + (x[:, 1] - x[:, 2]) ** 2 + (x[:, 2] - x[:, 0]) ** 2)
                    + 3 * (x[:, 3] ** 2 + x[:, 4] ** 2 + x[:, 5] ** 2)
                )
                # stored in single precision, von_mises is rounded from the
                # double stress, not computed from the rounded one
                eps = np.finfo(np.promote_types(s.dtype, vm.dtype)).eps
                scale = np.abs(x).max(initial=0.0)
                if not np.allclose(vm[()], ref, rtol=max(8 * eps, 1e-12), atol=8 * eps * scale):
                    problems.append(f"{vm.name} differs from the von Mises stress of {s.name}")
            for patch in sorted(set(b.keys()) - BODY_FIELDS):
                p = b[patch]
                n = p["contact_pressure"].shape[0] if "contact_pressure" in p else None
                if n is None:
                    problems.append(f"missing {p.name}/contact_pressure")
                    continue
                need(p, "face_centres", (n, 3))
                need(p, "contact_traction", (n, 3))
                need(p, "gap", (n,))
                if np.any(p["contact_pressure"][()] < 0):
                    problems.append(f"{p.name}/contact_pressure has negative values")
                key = f"{body}/{patch}"
                if patch_faces.setdefault(key, n) != n:
                    problems.append(f"{p.name}: {n} faces, earlier increments had {patch_faces[key]}")

    if "increments" in f or "times" in f:
        ks = f["increments"][()] if "increments" in f else None
        ts = f["times"][()] if "times" in f else None
        if ks is None or ts is None:
            problems.append("/increments and /times come together")
        elif list(ks) != sorted(int(k) for k in steps) or len(ts) != len(ks):
            problems.append(f"/increments {list(ks)[:5]}... does not list the {len(steps)} /time groups in order")
        else:
            for k, t in zip(ks, ts):
                if f["time"][str(k)].attrs["time"] != t:
                    problems.append(f"/times: increment {k} at {t}, its group says {f['time'][str(k)].attrs['time']}")
    for k in steps[-1:] if "increments" in f else []:
        for body in meshes:
            if body not in f["time"][k]:
                continue
            b = f["time"][k][body]
            fields = [b[n] for n in ("points", "displacement", "stress", "von_mises", "point_displacement") if n in b]
            fields += [b[p][n] for p in set(b.keys()) - BODY_FIELDS for n in PATCH_FIELDS if n in b[p]]
            for d in fields:
                for a in ("units", "location"):
                    if a not in d.attrs:
                        problems.append(f"{d.name} lacks attribute {a}")
                if d.ndim == 2 and len(d.attrs.get("components", [])) != d.shape[1]:
                    problems.append(f"{d.name}: components do not name its {d.shape[1]} columns")

    if "history" in f:
        h = f["history"]
        cols = h.attrs.get("columns")
        if cols is None:
            problems.append("/history lacks attribute columns")
        elif h.ndim != 2 or h.shape[1] != len(cols):
            problems.append(f"/history shape {h.shape} does not match {len(cols)} columns")

    print(f"{opts.file}: {len(meshes)} bodies, {len(steps)} increments, {len(patch_faces)} patches")
    for p in problems:
        print("PROBLEM:", p)
    print(f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
