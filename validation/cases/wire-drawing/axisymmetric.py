#!/usr/bin/env python3
"""Axisymmetric wire and die of the wire-drawing case (thesis §5.4.1): the
r-x sections of wire.py's wire and die.geo's die, each revolved by ±2.5°
about the x axis into a one-cell wedge, in Gmsh MSH 4.1 (ascii). The
problem is axisymmetric, so these wedges solve the quarter model's problem
at a small fraction of its cells, and the wire can be refined far beyond
what the 3-D quarter allows: a mesh-convergence study of the drawing force.

    python3 axisymmetric.py                 # wire 8 x 60 cells, die 30 x 6
    python3 axisymmetric.py --refine 2      # every wire spacing halved twice
    python3 axisymmetric.py --refine 2 --die-refine 1

writes `wire-axi.msh` and `die-axi.msh` (options -w, -d). The quarter
model's force is the wedge's × 90°/5° = 18.

Wire: the radius profile of wire.py (nose drawn into the die, 10 mm
fillet), 60 layers of 0.2 mm (one on x = 0, the die's edge between
approach and land) by 8 cells radially, uniform in r / r(x); the cells on
the axis are prisms. Patches "pulled", "upstream", "outer", "front",
"back".

Die: die.geo's three blocks (approach 20, land 5, back relief 5 cells
along the bore; 6 radially, growing by 1.3 from the bore to the outer
radius 2.5). `--die-refine k` halves those spacings k times (the radial
growth becomes 1.3^(1/2^k)). Patches "contact", "outer", "entry", "exit",
"front", "back".
"""
import argparse
import math

from wire import LENGTH, NOSE, R_BEARING, TAN_APPROACH, radius, write

HALF_ANGLE = math.radians(2.5)
TAN_RELIEF = math.tan(math.radians(15.0))
LAND = 0.45
X_ENTRY = -2.0
X_EXIT = LAND + 0.6
R_OUTER = 2.5


def revolve(section, quads, across, ends, lateral):
    """A one-cell wedge from a structured r-x section: `section[i][j]` is the
    point (x, r) at index i along x and j across (j = 0 the inner side),
    `quads` the section's cell count (ni, nj). Points with r = 0 lie on the
    axis, shared by both wedge planes, and make their cells prisms.
    Patches: `ends` (the i = ni side, the i = 0 side), `lateral` (j = nj), "front"
    (+2.5°), "back" (−2.5°); with `across` also the j = 0 side."""
    ni, nj = quads
    nodes, tag = [], {}

    def node(i, j, side):
        x, r = section[i][j]
        key = (i, j, 0 if r == 0.0 else side)
        if key not in tag:
            phi = side * HALF_ANGLE
            nodes.append((x, r * math.cos(phi), r * math.sin(phi)))
            tag[key] = len(nodes)
        return tag[key]

    cells = []
    patches = {name: [] for name in (*ends, lateral, *([across] if across else []), "front", "back")}
    for i in range(ni):
        for j in range(nj):
            # the section's quad counter-clockwise in (x, r): its normal +phi
            q = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            back = [node(a, b, -1) for a, b in q]
            front = [node(a, b, 1) for a, b in q]
            if section[i][j][1] == 0.0:  # on the axis: a prism
                cells.append([back[0], back[3], front[3], back[1], back[2], front[2]])
            else:
                cells.append(back + front)
            patches["back"].append(back[::-1])
            patches["front"].append(front)

    def side(edges, name):
        """Faces of section edges a -> b (the body on their left), turned
        outward; none along the axis."""
        for a, b in edges:
            pa, pb = [node(*a, -1), node(*b, -1)], [node(*a, 1), node(*b, 1)]
            if pa == pb:  # the edge lies on the axis
                continue
            if pa[0] == pb[0]:  # a on the axis: a triangle
                patches[name].append([pa[0], pa[1], pb[1]])
            elif pa[1] == pb[1]:  # b on the axis
                patches[name].append([pa[0], pa[1], pb[0]])
            else:
                patches[name].append([pa[0], pa[1], pb[1], pb[0]])

    side([((i + 1, nj), (i, nj)) for i in range(ni)], lateral)
    side([((0, j + 1), (0, j)) for j in range(nj)], ends[1])
    side([((ni, j), (ni, j + 1)) for j in range(nj)], ends[0])
    if across:
        side([((i, 0), (i + 1, 0)) for i in range(ni)], across)
    return nodes, cells, patches


def wire_section(refine):
    """Wire: layers of 0.2 mm / 2^refine, 8 · 2^refine cells radially."""
    layers, nr = 60 << refine, 8 << refine
    xs = [NOSE - LENGTH + LENGTH * i / layers for i in range(layers + 1)]
    return [[(x, radius(x) * j / nr) for j in range(nr + 1)] for x in xs], (layers, nr)


def die_section(refine):
    """Die: die.geo's blocks, their spacings halved `refine` times."""
    bore = [
        (X_ENTRY, R_BEARING - X_ENTRY * TAN_APPROACH),
        (0.0, R_BEARING),
        (LAND, R_BEARING),
        (X_EXIT, R_BEARING + (X_EXIT - LAND) * TAN_RELIEF),
    ]
    counts = [20 << refine, 5 << refine, 5 << refine]
    nr, growth = 6 << refine, 1.3 ** (1.0 / (1 << refine))
    t = [(growth**j - 1) / (growth**nr - 1) for j in range(nr + 1)]
    section = []
    for k, n in enumerate(counts):
        (x0, r0), (x1, r1) = bore[k], bore[k + 1]
        for i in range(0 if k == 0 else 1, n + 1):
            s = i / n
            x, r = x0 + s * (x1 - x0), r0 + s * (r1 - r0)
            section.append([(x, r + tj * (R_OUTER - r)) for tj in t])
    return section, (sum(counts), nr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--refine", type=int, default=0, help="halvings of the wire's spacings")
    ap.add_argument("--die-refine", type=int, default=0, help="halvings of the die's spacings")
    ap.add_argument("-w", "--wire", default="wire-axi.msh")
    ap.add_argument("-d", "--die", default="die-axi.msh")
    a = ap.parse_args()
    section, quads = wire_section(a.refine)
    nodes, cells, patches = revolve(section, quads, None, ("pulled", "upstream"), "outer")
    write(a.wire, nodes, cells, patches)
    print(f"{a.wire}: {len(cells)} cells, {len(nodes)} nodes")
    section, quads = die_section(a.die_refine)
    # the die's section runs from the bore (j = 0) out: "contact" is the
    # j = 0 side, "outer" the j = nj side
    nodes, cells, patches = revolve(section, quads, "contact", ("exit", "entry"), "outer")
    write(a.die, nodes, cells, patches, volume="die")
    print(f"{a.die}: {len(cells)} cells, {len(nodes)} nodes")


if __name__ == "__main__":
    main()
