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
from wire import section, write  # noqa: E402  (the drawing case's generator)

RADIUS = 1.35
LENGTH = 80.0
X_TAIL = -70.0


def build(factor):
    n, m, layers = (round(c * factor) for c in (6, 4, 240))
    sec, quads, arc = section(n, m)
    ns = len(sec)
    nodes = []
    for l in range(layers + 1):
        x = X_TAIL + LENGTH * l / layers
        nodes += [(x, RADIUS * y, RADIUS * z) for (y, z) in sec]

    def tag(l, p):
        return l * ns + p + 1

    hexes = [[tag(l, p) for p in q] + [tag(l + 1, p) for p in q] for l in range(layers) for q in quads]
    patches = {name: [] for name in ("front", "tail", "outer", "symmetry-y", "symmetry-z")}
    patches["tail"] = [[tag(0, p) for p in q[::-1]] for q in quads]
    patches["front"] = [[tag(layers, p) for p in q] for q in quads]

    def lateral(l, a, b, out):
        (y0, z0), (y1, z1) = sec[a], sec[b]
        if (z1 - z0) * out[0] - (y1 - y0) * out[1] < 0:
            a, b = b, a
        return [tag(l, a), tag(l + 1, a), tag(l + 1, b), tag(l, b)]

    for l in range(layers):
        for a, b in arc:
            mid = [(sec[a][c] + sec[b][c]) / 2 for c in range(2)]
            patches["outer"].append(lateral(l, a, b, mid))
        for q in quads:
            for s in range(4):
                a, b = q[s], q[(s + 1) % 4]
                for name, axis in (("symmetry-y", 0), ("symmetry-z", 1)):
                    if abs(sec[a][axis]) < 1e-12 and abs(sec[b][axis]) < 1e-12:
                        out = (-1.0, 0.0) if axis == 0 else (0.0, -1.0)
                        patches[name].append(lateral(l, a, b, out))
    return nodes, hexes, patches


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
