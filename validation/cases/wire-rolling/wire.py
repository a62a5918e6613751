#!/usr/bin/env python3
"""Wire of the wire-rolling case (thesis §5.4.2): a quarter of a Ø2.7 mm
wire, 80 mm long, as a hexahedral mesh in Gmsh MSH 4.1 (ascii). Python 3
only; the cross-section and the writer are those of the wire-drawing
case's generator (../wire-drawing/wire.py).

    python3 wire.py                                 # coarse: 84 cells per section, 240 layers, 20,160 cells
    python3 wire.py --factor 1.5 -o wire-medium.msh   # spacings / 1.5: 189 per section, 360 layers, 68,040 cells

Units mm. The wire axis is x, rolling direction +x; the rolls press along
y (the roll of this quarter above, y > 0) and their axes are parallel to z.
The quarter y >= 0, z >= 0: "symmetry-y" is the plane y = 0 between the
two rolls, "symmetry-z" the plane z = 0 through the wire's axis across the
rolls' width. The wire lies from x = X_TAIL to X_TAIL + 80 with the roll
bite at x = 0. Patches "front" (x = X_TAIL + 80), "tail", "outer" (the
lateral surface), "symmetry-y", "symmetry-z". Volume "wire".

Cross-section: the O-grid of ../wire-drawing/wire.py, a core square of
n x n cells and two blocks of n x m cells to the arc, n = 6, m = 4 (84
cells; the thesis's coarse wire has 81 per section in 240 layers, 19,440
cells). The section's point at angle 0 lies on the y axis, so the wire's
top line (y = 1.35, z = 0) is on the circle where the roll first touches.
"""
import argparse
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "wire-drawing"))
from wire import section, sweep, write  # noqa: E402  (the drawing case's generator)

RADIUS = 1.35
LENGTH = 80.0
X_TAIL = -70.0


def build(factor):
    n, m, layers = (round(c * factor) for c in (6, 4, 240))
    return sweep(
        section(n, m),
        layers,
        lambda l, y, z: (X_TAIL + LENGTH * l / layers, RADIUS * y, RADIUS * z),
        ("front", "tail"),
        "outer",
        True,
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--factor", type=float, default=1.0, help="divides every spacing")
    ap.add_argument("-o", "--output", default="wire.msh")
    a = ap.parse_args()
    nodes, hexes, patches = build(a.factor)
    write(a.output, nodes, hexes, patches)
    print(f"{a.output}: {len(hexes)} hexahedra, {len(nodes)} nodes")


if __name__ == "__main__":
    main()
