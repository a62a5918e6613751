#!/usr/bin/env python3
"""Wire of the wire-drawing case (thesis §5.4.1): a quarter of a Ø2 mm wire,
12 mm long, whose nose is already drawn into the die, as a hexahedral mesh
in Gmsh MSH 4.1 (ascii). No dependency beyond Python 3.

    python3 wire.py                      # coarse: 4 x 4 + 2 x 4 x 3 per section, 60 layers, 2,400 cells
    python3 wire.py --refine 1 -o wire-medium.msh   # every spacing halved: 19,200 cells

Units mm. The wire axis is x, drawing direction +x; the quarter y >= 0,
z >= 0 (symmetry planes y = 0 and z = 0). The die (die.geo) has its
approach cone (half angle 6°) for x in [-2, 0], the bearing (land) of
radius 0.86 for x in [0, 0.45] and the back relief (half angle 15°) from
x = 0.45 on.

Radius profile of the wire, nose (x = 0.8) to tail (x = -11.2):
  r = 0.858 from the nose to x = 0 (in the land and the back relief),
  r = 0.858 - x tan 6° along the approach cone,
  a fillet of radius 10 mm from the cone into the cylinder r = 1 (the cone
  would reach r = 1 at x = -1.351; the fillet lies inside the cone, out of
  contact, and leaves no kink in the wire's surface),
  r = 1 up to the tail.
The nose is 2 µm (CLEARANCE) inside the die's bore: the wire's points lie
on circles, the die's faces are chords of its circles (16 per quarter,
1 µm inside at their middle), and a wire meshed exactly on the bore would
start 1 µm into the die, which the penalty of a 190 GPa wire over 0.1 mm
cells turns into 2 GPa of contact pressure before anything is drawn. The
gap closes within the first increment (8.3 µm of reduction per 83 µm
drawn along the cone).
The layers are 0.2 mm apart and one falls on x = 0, the die's edge
between approach and land, so the wire's faceted surface follows it.

Cross-section (quarter disc, unit radius, scaled by r(x)): an O-grid of a
core square [0, 0.5]^2 with n x n cells and two blocks of n x m cells
between the square's outer sides and the arc, which carries 2n faces.
Coarse n = 4, m = 3: 40 cells per section.

Patches: "pulled" (the nose end x = 0.8, drawn), "upstream" (the tail,
back tension), "outer" (the lateral surface, contact), "symmetry-y"
(y = 0), "symmetry-z" (z = 0). Volume "wire".
"""
import argparse
import math

NOSE = 0.8
LENGTH = 12.0
R_WIRE = 1.0
R_BEARING = 0.86
TAN_APPROACH = math.tan(math.radians(6.0))
FILLET = 10.0
CORE = 0.5
CLEARANCE = 0.002


def radius(x):
    """The wire's radius at x (mm), as in the module doc."""
    r_land = R_BEARING - CLEARANCE
    if x >= 0.0:
        return r_land
    x_kink = -(R_WIRE - r_land) / TAN_APPROACH  # the cone reaches r = 1
    half = math.radians(3.0)  # half of the 6° turn
    t = FILLET * math.tan(half)  # tangent length of the fillet
    x_cone = x_kink + t * math.cos(math.radians(6.0))  # fillet meets the cone
    x_flat = x_kink - t  # fillet meets the cylinder
    if x >= x_cone:
        return r_land - x * TAN_APPROACH
    if x <= x_flat:
        return R_WIRE
    return R_WIRE - FILLET + math.sqrt(FILLET**2 - (x - x_flat) ** 2)


class Grid2d:
    """Points of a plane section, merged where they coincide, and its
    quads turned counter-clockwise (shared with the rolling and strand
    generators)."""

    def __init__(self):
        self.points, self.index, self.quads = [], {}, []

    def node(self, y, z):
        key = (round(y, 9), round(z, 9))
        if key not in self.index:
            self.index[key] = len(self.points)
            self.points.append((y, z))
        return self.index[key]

    def quad(self, a, b, c, d):
        q = [a, b, c, d]
        area = 0.0
        for s in range(4):
            (y0, z0), (y1, z1) = self.points[q[s]], self.points[q[(s + 1) % 4]]
            area += y0 * z1 - y1 * z0
        self.quads.append(q if area > 0 else q[::-1])


def section(n, m):
    """Unit quarter-disc O-grid: points (y, z) and counter-clockwise quads.

    Also the quads' edges on the arc (for the "outer" patch) as index pairs.
    """
    g = Grid2d()
    node = g.node
    grid = {}
    for i in range(n + 1):
        for j in range(n + 1):
            grid["c", i, j] = node(CORE * i / n, CORE * j / n)
    for j in range(n + 1):  # block A: right of the core, arc 0..45°
        th = math.radians(45.0 * j / n)
        for k in range(m + 1):
            f = k / m
            grid["a", j, k] = node(
                (1 - f) * CORE + f * math.cos(th), (1 - f) * CORE * j / n + f * math.sin(th)
            )
    for i in range(n + 1):  # block B: above the core, arc 90..45°
        th = math.radians(90.0 - 45.0 * i / n)
        for k in range(m + 1):
            f = k / m
            grid["b", i, k] = node(
                (1 - f) * CORE * i / n + f * math.cos(th), (1 - f) * CORE + f * math.sin(th)
            )
    arc = []
    quad = g.quad

    for i in range(n):
        for j in range(n):
            quad(grid["c", i, j], grid["c", i + 1, j], grid["c", i + 1, j + 1], grid["c", i, j + 1])
    for b in "ab":
        for s in range(n):
            for k in range(m):
                quad(grid[b, s, k], grid[b, s, k + 1], grid[b, s + 1, k + 1], grid[b, s + 1, k])
            arc.append((grid[b, s, m], grid[b, s + 1, m]))
    return g.points, g.quads, arc


def sweep(section, layers, place, ends, lateral, symmetry):
    """Hexahedra of a plane section swept through layers 0..layers:
    `place(l, y, z)` puts a section point in layer l. Patches: `ends`
    (the last layer's, the first's), `lateral` (the section's arc edges,
    swept) and, with `symmetry`, "symmetry-y" and "symmetry-z" (the
    section's edges on y = 0 and z = 0)."""
    sec, quads, arc = section
    ns = len(sec)
    nodes = [place(l, y, z) for l in range(layers + 1) for (y, z) in sec]

    def tag(l, p):
        return l * ns + p + 1

    hexes = [
        [tag(l, p) for p in q] + [tag(l + 1, p) for p in q]
        for l in range(layers)
        for q in quads
    ]
    names = list(ends) + [lateral] + (["symmetry-y", "symmetry-z"] if symmetry else [])
    patches = {name: [] for name in names}
    patches[ends[1]] = [[tag(0, p) for p in q[::-1]] for q in quads]
    patches[ends[0]] = [[tag(layers, p) for p in q] for q in quads]

    def outward(l, a, b, out):
        """The lateral quad of section edge a-b in layer l, its normal along out."""
        (y0, z0), (y1, z1) = sec[a], sec[b]
        # the quad a, a', b', b has the normal (edge a->b) x (+x) in (y, z)
        if (z1 - z0) * out[0] - (y1 - y0) * out[1] < 0:
            a, b = b, a
        return [tag(l, a), tag(l + 1, a), tag(l + 1, b), tag(l, b)]

    for l in range(layers):
        for a, b in arc:
            mid = [(sec[a][c] + sec[b][c]) / 2 for c in range(2)]
            patches[lateral].append(outward(l, a, b, mid))
        if not symmetry:
            continue
        for q in quads:
            for s in range(4):
                a, b = q[s], q[(s + 1) % 4]
                for name, axis in (("symmetry-y", 0), ("symmetry-z", 1)):
                    if abs(sec[a][axis]) < 1e-12 and abs(sec[b][axis]) < 1e-12:
                        out = (-1.0, 0.0) if axis == 0 else (0.0, -1.0)
                        patches[name].append(outward(l, a, b, out))
    return nodes, hexes, patches


def build(refine):
    n, m, layers = 4 << refine, 3 << refine, 60 << refine
    xs = [NOSE - LENGTH + LENGTH * l / layers for l in range(layers + 1)]
    rs = [radius(x) for x in xs]
    return sweep(
        section(n, m),
        layers,
        lambda l, y, z: (xs[l], rs[l] * y, rs[l] * z),
        ("pulled", "upstream"),
        "outer",
        True,
    )


# Gmsh element types by node count: faces (triangle, quadrangle) and cells
# (prism, hexahedron).
FACE_TYPE = {3: 2, 4: 3}
CELL_TYPE = {6: 6, 8: 5}


def blocks(elements, types):
    """The elements grouped by Gmsh type, in the order of `types`."""
    by_type = {t: [] for t in types.values()}
    for el in elements:
        by_type[types[len(el)]].append(el)
    return [(t, els) for t, els in by_type.items() if els]


def write(path, nodes, hexes, patches, volume="wire"):
    """Gmsh MSH 4.1 (ascii): one physical surface per patch (triangles and
    quadrangles), one physical volume (prisms and hexahedra)."""
    names = list(patches)
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n")
        f.write(f"{len(names) + 1}\n")
        for t, name in enumerate(names, 1):
            f.write(f'2 {t} "{name}"\n')
        f.write(f'3 {len(names) + 1} "{volume}"\n$EndPhysicalNames\n$Entities\n')
        lo = [min(p[a] for p in nodes) for a in range(3)]
        hi = [max(p[a] for p in nodes) for a in range(3)]
        box = " ".join(f"{v:.9g}" for v in lo + hi)
        f.write(f"0 0 {len(names)} 1\n")
        for t in range(1, len(names) + 1):
            f.write(f"{t} {box} 1 {t} 0\n")
        f.write(f"1 {box} 1 {len(names) + 1} 0\n$EndEntities\n")
        f.write(f"$Nodes\n1 {len(nodes)} 1 {len(nodes)}\n3 1 0 {len(nodes)}\n")
        f.writelines(f"{t}\n" for t in range(1, len(nodes) + 1))
        f.writelines(f"{x:.12g} {y:.12g} {z:.12g}\n" for (x, y, z) in nodes)
        f.write("$EndNodes\n")
        entity_blocks = [
            (2, t, gtype, els)
            for t, name in enumerate(names, 1)
            for gtype, els in blocks(patches[name], FACE_TYPE)
        ] + [(3, 1, gtype, els) for gtype, els in blocks(hexes, CELL_TYPE)]
        n_el = sum(len(els) for *_, els in entity_blocks)
        f.write(f"$Elements\n{len(entity_blocks)} {n_el} 1 {n_el}\n")
        e = 1
        for dim, tag, gtype, els in entity_blocks:
            f.write(f"{dim} {tag} {gtype} {len(els)}\n")
            for el in els:
                f.write(f"{e} {' '.join(map(str, el))}\n")
                e += 1
        f.write("$EndElements\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--refine", type=int, default=0, help="halvings of every spacing")
    ap.add_argument("-o", "--output", default="wire.msh")
    a = ap.parse_args()
    nodes, hexes, patches = build(a.refine)
    write(a.output, nodes, hexes, patches)
    print(f"{a.output}: {len(hexes)} hexahedra, {len(nodes)} nodes")


if __name__ == "__main__":
    main()
