#!/usr/bin/env python3
"""Open an fvc results .xdmf in ParaView headless and check what it shows.

usage:  xvfb-run -a pvpython scripts/paraview_check.py RESULTS/<title>/<title>.xdmf

Needs ParaView (Debian: apt-get install -y paraview python3-paraview xvfb).
Opens the file with OpenDataFile (absolute path), updates every time step,
and prints per time step and block the number of cells and points and the
cell/point arrays. The expectation is read from the XDMF itself: every
grid (body or contact patch) of every time step must appear as a block
with its NumberOfElements cells and all its attributes, and ParaView must
report exactly the XDMF's time values. (The geometry is already the
deformed one: there is no displacement at points to warp by.)

OpenDataFile picks ParaView's Xdmf3ReaderS, which shows the grids as
unnamed pieces (matched here in file order) of one dataset: its surface
filter and MergeBlocks keep only the arrays all grids have, so the writer
gives every grid every field. The check is repeated with Xdmf3ReaderT
("Xdmf3 Reader T" in the GUI's reader dialog), which keeps the body and
patch names as block names.

Exits 1 on any mismatch, 2 if the file cannot be opened at all.
"""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

from paraview import simple
from paraview.simple import OpenDataFile
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkDataObjectTreeIterator


def expectation(path):
    """[(time or None, [(grid name, cells, {attribute names})])] from the XML."""
    top = ET.parse(path).getroot().find("Domain/Grid")
    if top is None:
        return []
    if top.get("CollectionType") == "Temporal":
        steps = top.findall("Grid")
    else:
        steps = [top]
    out = []
    for step in steps:
        t = step.find("Time")
        grids = []
        for g in step.iter("Grid"):
            if g.get("GridType", "Uniform") != "Uniform":
                continue
            topo = g.find("Topology")
            n = int(topo.get("NumberOfElements")) if topo is not None else -1
            grids.append((g.get("Name"), n, {a.get("Name") for a in g.findall("Attribute")}))
        out.append((float(t.get("Value")) if t is not None else None, grids))
    return out


def output(proxy):
    """The proxy's output data object (pvpython runs in built-in mode)."""
    return proxy.GetClientSideObject().GetOutputDataObject(0)


def leaves(data):
    """(name or None, dataset) of every leaf block, in order."""
    if not data.IsA("vtkCompositeDataSet"):
        yield ("", data)
        return
    it = vtkDataObjectTreeIterator()
    it.SetDataSet(data)
    it.VisitOnlyLeavesOn()
    it.SkipEmptyNodesOn()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        meta = it.GetCurrentMetaData()
        name = meta.Get(vtkCompositeDataSet.NAME()) if meta and meta.Has(vtkCompositeDataSet.NAME()) else None
        yield (name, it.GetCurrentDataObject())
        it.GoToNextItem()


def arrays(attrs):
    return sorted(attrs.GetArrayName(i) for i in range(attrs.GetNumberOfArrays()))


def check(reader, expected):
    """Updates every time step of `reader`; returns the problems found."""
    problems = []
    label = reader.GetXMLName()
    times = reader.TimestepValues if hasattr(reader, "TimestepValues") else []
    times = list(times) if hasattr(times, "__len__") else [times]
    want_times = [t for t, _ in expected if t is not None]
    if len(times) != len(want_times) or any(
        not math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300) for a, b in zip(times, want_times)
    ):
        problems.append(f"{label}: time steps {times} != XDMF {want_times}")
    print(f"{label}: {len(times)} time steps {times}")
    for t, grids in expected:
        if t is None:
            reader.UpdatePipeline()
        else:
            reader.UpdatePipeline(t)
        blocks = list(leaves(output(reader)))
        named = all(name is not None for name, _ in blocks)
        for i, (name, ds) in enumerate(blocks):
            print(
                f"  t = {t}: block {name if named else f'#{i}'}: {ds.GetNumberOfCells()} cells, "
                f"{ds.GetNumberOfPoints()} points; cell arrays {arrays(ds.GetCellData())}; "
                f"point arrays {arrays(ds.GetPointData())}"
            )
        if len(blocks) != len(grids):
            problems.append(f"{label} t = {t}: {len(blocks)} blocks, XDMF has {len(grids)} grids")
        # Xdmf3ReaderT names the blocks of later steps "<name>[<n>]"
        by_name = {re.sub(r"\[\d+\]$", "", name): ds for name, ds in blocks} if named else {}
        for i, (name, n, attrs) in enumerate(grids):
            if named:
                ds = by_name.get(name)
            else:
                ds = blocks[i][1] if i < len(blocks) else None
            if ds is None:
                problems.append(f"{label} t = {t}: block {name} missing")
                continue
            if ds.GetNumberOfCells() != n:
                problems.append(f"{label} t = {t}: block {name} has {ds.GetNumberOfCells()} cells, XDMF says {n}")
            have = set(arrays(ds.GetCellData())) | set(arrays(ds.GetPointData()))
            for a in sorted(attrs - have):
                problems.append(f"{label} t = {t}: block {name} lacks array {a}")
    return problems


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    path = os.path.abspath(sys.argv[1])
    expected = expectation(path)
    if not expected:
        print(f"{path}: no grids in the XDMF")
        return 2
    reader = OpenDataFile(path)
    if reader is None:
        print(f"ParaView cannot open {path}")
        return 2
    print(f"{path}: OpenDataFile chose {reader.GetXMLName()}")
    problems = check(reader, expected)
    if reader.GetXMLName() != "Xdmf3ReaderT" and hasattr(simple, "Xdmf3ReaderT"):
        problems += check(simple.Xdmf3ReaderT(FileName=[path]), expected)
    for p in problems:
        print("PROBLEM:", p)
    n_times = sum(1 for t, _ in expected if t is not None)
    print(f"{n_times} time steps x {len(expected[0][1])} grids checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
