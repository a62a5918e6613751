#!/usr/bin/env python3
"""Meshes of the strand-compacting case (thesis §5.4.3): a 1+6 strand of
Ø5 mm wires, lay length 250 mm, 170 mm of it, and the rigid die it is
drawn through, as hexahedral meshes in Gmsh MSH 4.1 (ascii). Python 3
only; the writer is the wire-drawing case's generator's
(../wire-drawing/wire.py).

    python3 strand.py                 # coarse: 96 cells per wire section, 2 mm layers
    python3 strand.py --factor 2      # every spacing halved

Writes core.msh, wire1.msh … wire6.msh and die.msh beside this script.
Units mm. The strand's axis is x, drawing direction +x. The die (rigid):
approach cone 2α1 = 14° for x in [-10, 0], bearing (land) Ø13.5 mm for x
in [0, 4], back relief 2α2 = 30° for x in [4, 7]; one cell thick, 96
sectors around.

Wires: the core on the axis; the six outer wires' centres on a right-hand
helix of radius 5 mm (touching the core) and lay length 250 mm, phases
k·60°. Each wire's section in a plane x = const is a disc of radius
2.5 mm (a hexagonal O-grid, `disc`), turned with its helix so the mesh
follows the wire; in those planes the seven discs touch each other, as the
wires do. The strand's nose is already compacted (as the wire-drawing
case's nose is already drawn): in the land and beyond the whole section
is scaled about the axis to the bearing's Ø13.5 mm (less a clearance of
10 µm), along the approach cone it follows the cone, and a 10 mm fillet
takes the cone into the Ø15 mm strand. The nose sits at x = 6 and the
tail at x = -164. Patches per wire: "front" (x = 6, pulled), "tail",
"surface". Die patches: "bore" (contact), "outer", "entry", "exit".
"""
import argparse
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "wire-drawing"))
from wire import Grid2d, sweep, write  # noqa: E402  (the drawing case's generator)

WIRE_RADIUS = 2.5
HELIX_RADIUS = 5.0
LAY_LENGTH = 250.0
STRAND_RADIUS = HELIX_RADIUS + WIRE_RADIUS
BEARING_RADIUS = 6.75
CLEARANCE = 0.01
TAN_APPROACH = math.tan(math.radians(7.0))
TAN_RELIEF = math.tan(math.radians(15.0))
FILLET = 10.0
CORE = 0.5
NOSE = 6.0
LENGTH = 170.0
DIE = (-10.0, 0.0, 4.0, 7.0)  # approach start, land start, land end, relief end


def envelope(x):
    """The strand's outer radius at x: the bearing's in the land and beyond,
    the approach cone's before it, a fillet into the full strand."""
    r_land = BEARING_RADIUS - CLEARANCE
    if x >= 0.0:
        return r_land
    x_kink = -(STRAND_RADIUS - r_land) / TAN_APPROACH
    t = FILLET * math.tan(math.radians(3.5))
    x_cone = x_kink + t * math.cos(math.radians(7.0))
    x_flat = x_kink - t
    if x >= x_cone:
        return r_land - x * TAN_APPROACH
    if x <= x_flat:
        return STRAND_RADIUS
    return STRAND_RADIUS - FILLET + math.sqrt(FILLET**2 - (x - x_flat) ** 2)


def disc(n, m):
    """Unit disc as a hexagonal O-grid, symmetric under turns of 60° as the
    strand is: a core hexagon (corners at radius CORE) of three rhombi of
    n x n cells and six blocks of n x m cells from its sides to the arc
    (6n faces on the arc). Points, counter-clockwise quads, arc edges.
    A quarter-disc O-grid (90° symmetry) on the core wire made the outer
    wires' forces differ in pairs (wires 1 and 4, 2 and 5, 3 and 6) by the
    facets facing them."""
    g = Grid2d()
    node, quad = g.node, g.quad

    def corner(i):
        a = math.pi / 3 * i
        return (CORE * math.cos(a), CORE * math.sin(a))

    arc = []

    for j in range(3):  # rhombus O, H(2j), H(2j+1), H(2j+2)
        h0, h2 = corner(2 * j), corner(2 * j + 2)
        grid = [[node(h0[0] * i / n + h2[0] * k / n, h0[1] * i / n + h2[1] * k / n)
                 for k in range(n + 1)] for i in range(n + 1)]
        for i in range(n):
            for k in range(n):
                quad(grid[i][k], grid[i + 1][k], grid[i + 1][k + 1], grid[i][k + 1])
    for i in range(6):  # block between side H(i)-H(i+1) and the arc
        h0, h1 = corner(i), corner(i + 1)
        grid = []
        for t in range(n + 1):
            f = t / n
            e = (h0[0] + f * (h1[0] - h0[0]), h0[1] + f * (h1[1] - h0[1]))
            a = math.pi / 3 * (i + f)
            grid.append([node((1 - g) * e[0] + g * math.cos(a), (1 - g) * e[1] + g * math.sin(a))
                         for g in (r / m for r in range(m + 1))])
        for t in range(n):
            for r in range(m):
                quad(grid[t][r], grid[t][r + 1], grid[t + 1][r + 1], grid[t + 1][r])
            arc.append((grid[t][m], grid[t + 1][m]))
    return g.points, g.quads, arc


def wire(k, n, m, layers):
    """Wire k (0: the core, 1–6: the outer wires): nodes, hexahedra, patches."""
    frames = []
    for l in range(layers + 1):
        x = NOSE - LENGTH + LENGTH * l / layers
        s = envelope(x) / STRAND_RADIUS
        turn = 2.0 * math.pi * x / LAY_LENGTH + (k - 1) * math.pi / 3.0
        c, sn = math.cos(turn), math.sin(turn)
        cy, cz = (0.0, 0.0) if k == 0 else (HELIX_RADIUS * c, HELIX_RADIUS * sn)
        frames.append((x, s, c, sn, cy, cz))

    def place(l, y, z):
        x, s, c, sn, cy, cz = frames[l]
        yr, zr = c * y - sn * z, sn * y + c * z
        return (x, s * (cy + WIRE_RADIUS * yr), s * (cz + WIRE_RADIUS * zr))

    return sweep(disc(n, m), layers, place, ("front", "tail"), "surface", False)


def die(factor):
    """The rigid die: its bore profile revolved, one cell thick."""
    a0, l0, l1, r1 = DIE
    profile = []

    def segment(x0, x1, cells):
        for i in range(cells):
            profile.append(x0 + (x1 - x0) * i / cells)

    segment(a0, l0, round(20 * factor))
    segment(l0, l1, round(8 * factor))
    segment(l1, r1, round(6 * factor))
    profile.append(r1)

    def bore(x):
        if x < l0:
            return BEARING_RADIUS + (l0 - x) * TAN_APPROACH
        if x <= l1:
            return BEARING_RADIUS
        return BEARING_RADIUS + (x - l1) * TAN_RELIEF

    sectors = round(96 * factor)
    nx = len(profile)
    nodes = []
    for j in range(sectors):
        th = 2.0 * math.pi * j / sectors
        for x in profile:
            for dr in (0.0, 1.0):
                r = bore(x) + dr
                nodes.append((x, r * math.cos(th), r * math.sin(th)))

    def tag(j, i, o):
        return ((j % sectors) * nx + i) * 2 + o + 1

    hexes = []
    patches = {"bore": [], "outer": [], "entry": [], "exit": []}
    for j in range(sectors):
        for i in range(nx - 1):
            # bottom face (sector j) and top face (sector j + 1), each
            # ordered (i, in), (i + 1, in), (i + 1, out), (i, out)
            bottom = [tag(j, i, 0), tag(j, i + 1, 0), tag(j, i + 1, 1), tag(j, i, 1)]
            top = [tag(j + 1, i, 0), tag(j + 1, i + 1, 0), tag(j + 1, i + 1, 1), tag(j + 1, i, 1)]
            hexes.append(bottom + top)
            patches["bore"].append([tag(j, i, 0), tag(j + 1, i, 0), tag(j + 1, i + 1, 0), tag(j, i + 1, 0)])
            patches["outer"].append([tag(j, i, 1), tag(j, i + 1, 1), tag(j + 1, i + 1, 1), tag(j + 1, i, 1)])
        patches["entry"].append([tag(j, 0, 0), tag(j, 0, 1), tag(j + 1, 0, 1), tag(j + 1, 0, 0)])
        last = nx - 1
        patches["exit"].append([tag(j, last, 0), tag(j + 1, last, 0), tag(j + 1, last, 1), tag(j, last, 1)])
    return nodes, hexes, patches


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--factor", type=int, default=1, help="divides every spacing")
    ap.add_argument("-d", "--directory", default=os.path.dirname(os.path.abspath(__file__)))
    a = ap.parse_args()
    n, m, layers = 4 * a.factor, 2 * a.factor, round(LENGTH / 2) * a.factor
    for k in range(7):
        name = "core" if k == 0 else f"wire{k}"
        nodes, hexes, patches = wire(k, n, m, layers)
        path = os.path.join(a.directory, f"{name}.msh")
        write(path, nodes, hexes, patches)
        print(f"{path}: {len(hexes)} hexahedra")
    nodes, hexes, patches = die(a.factor)
    path = os.path.join(a.directory, "die.msh")
    write(path, nodes, hexes, patches)
    print(f"{path}: {len(hexes)} hexahedra")


if __name__ == "__main__":
    main()
