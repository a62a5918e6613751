#!/usr/bin/env python3
"""CalculiX input for validation/cases/plastic-upsetting/quarter-3d.toml: a
quarter of a square J2 billet (10 x 10 x 5, symmetry planes x, y, z = 0,
NLGEOM, linear hardening) upset by 1.5 by a rigid platen (C3D8 plate made
rigid by *RIGID BODY) with Coulomb friction mu; surface-to-surface penalty
contact (slope K, stick slope LAMBDA), increments of 0.01-0.02, output at
t = 0.1, 0.2, ..., 1.0 (*NODE PRINT RF on the plane z = 0).

usage: calculix_upsetting_3d.py ELTYPE MU NAME [K] [LAMBDA] [NX NY NZ]
       ELTYPE in C3D20R, C3D20, C3D8I, C3D8, C3D8R; then ccx -i NAME
"""
import sys

el = sys.argv[1] if len(sys.argv) > 1 else "C3D20R"
mu = float(sys.argv[2]) if len(sys.argv) > 2 else 0.1
name = sys.argv[3] if len(sys.argv) > 3 else f"billet_{el}_mu{mu}"
K = float(sys.argv[4]) if len(sys.argv) > 4 else 1e6
LAM = float(sys.argv[5]) if len(sys.argv) > 5 else 1e6
NX, NY, NZ = (int(v) for v in sys.argv[6:9]) if len(sys.argv) > 8 else (16, 16, 8)
LX, LY, LZ = 10.0, 10.0, 5.0
DZ = 1.5
quad = el.startswith("C3D20")

# node lattice: quadratic -> doubled lattice
m = 2 if quad else 1
GX, GY, GZ = m * NX + 1, m * NY + 1, m * NZ + 1


def nid(i, j, k):
    return 1 + i + GX * (j + GY * k)


used = set()
elems = []
for k in range(NZ):
    for j in range(NY):
        for i in range(NX):
            a, b, c = m * i, m * j, m * k
            d = m
            corners = [(a, b, c), (a + d, b, c), (a + d, b + d, c), (a, b + d, c),
                       (a, b, c + d), (a + d, b, c + d), (a + d, b + d, c + d), (a, b + d, c + d)]
            conn = [nid(*p) for p in corners]
            if quad:
                h = 1
                mids = [(a + h, b, c), (a + d, b + h, c), (a + h, b + d, c), (a, b + h, c),
                        (a + h, b, c + d), (a + d, b + h, c + d), (a + h, b + d, c + d), (a, b + h, c + d),
                        (a, b, c + h), (a + d, b, c + h), (a + d, b + d, c + h), (a, b + d, c + h)]
                conn += [nid(*p) for p in mids]
            used.update(conn)
            elems.append((len(elems) + 1, conn, k == NZ - 1))

nodes = {}
for n in used:
    q = n - 1
    i = q % GX
    j = (q // GX) % GY
    k = q // (GX * GY)
    nodes[n] = (LX * i / (GX - 1), LY * j / (GY - 1), LZ * k / (GZ - 1))

# platen: PXxPY x1 C3D8 over [0,25]^2, z in [5,6]
PX = PY = 5
PL = 25.0
p0 = max(nodes) + 1
pn = {}
for k in range(2):
    for j in range(PY + 1):
        for i in range(PX + 1):
            pn[(i, j, k)] = p0 + i + (PX + 1) * (j + (PY + 1) * k)
pel = []
e0 = len(elems) + 1
for j in range(PY):
    for i in range(PX):
        conn = [pn[(i, j, 0)], pn[(i + 1, j, 0)], pn[(i + 1, j + 1, 0)], pn[(i, j + 1, 0)],
                pn[(i, j, 1)], pn[(i + 1, j, 1)], pn[(i + 1, j + 1, 1)], pn[(i, j + 1, 1)]]
        pel.append((e0 + len(pel), conn))
REF = p0 + 2 * (PX + 1) * (PY + 1)
ROT = REF + 1

L = []
w = L.append
w("*HEADING")
w(f"Quarter billet upsetting, {el}, mu={mu}")
w("*NODE, NSET=NALL")
for n in sorted(nodes):
    x, y, z = nodes[n]
    w(f"{n}, {x:.10g}, {y:.10g}, {z:.10g}")
w("*NODE, NSET=NPLATEN")
for (i, j, k), n in sorted(pn.items(), key=lambda t: t[1]):
    w(f"{n}, {PL * i / PX:.10g}, {PL * j / PY:.10g}, {LZ + k:.10g}")
w("*NODE")
w(f"{REF}, 0, 0, {LZ}")
w(f"{ROT}, 0, 0, {LZ}")
w(f"*ELEMENT, TYPE={el}, ELSET=EBILLET")
for e, conn, _ in elems:
    s = ", ".join(str(c) for c in conn)
    if quad:  # max 16 entries per line
        first = conn[:15]
        rest = conn[15:]
        w(f"{e}, " + ", ".join(map(str, first)) + ",")
        w(", ".join(map(str, rest)))
    else:
        w(f"{e}, {s}")
w("*ELEMENT, TYPE=C3D8, ELSET=EPLATEN")
for e, conn in pel:
    w(f"{e}, " + ", ".join(map(str, conn)))


def nset(nm, ids):
    w(f"*NSET, NSET={nm}")
    ids = sorted(ids)
    for i in range(0, len(ids), 10):
        w(", ".join(map(str, ids[i:i + 10])))


tol = 1e-8
nset("NX0", [n for n, p in nodes.items() if abs(p[0]) < tol])
nset("NY0", [n for n, p in nodes.items() if abs(p[1]) < tol])
nset("NZ0", [n for n, p in nodes.items() if abs(p[2]) < tol])
nset("NTOP", [n for n, p in nodes.items() if abs(p[2] - LZ) < tol])
nset("NREF", [REF])

w("*SURFACE, NAME=SBTOP, TYPE=ELEMENT")
for e, conn, top in elems:
    if top:
        w(f"{e}, S2")
w("*SURFACE, NAME=SPLAT, TYPE=ELEMENT")
for e, conn in pel:
    w(f"{e}, S1")

w("*MATERIAL, NAME=STEEL")
w("*ELASTIC")
w("200000., 0.3")
w("*PLASTIC")
w("200., 0.")
w("2200., 2.")
w("*MATERIAL, NAME=RIGIDMAT")
w("*ELASTIC")
w("200000., 0.3")
w("*SOLID SECTION, ELSET=EBILLET, MATERIAL=STEEL")
w("*SOLID SECTION, ELSET=EPLATEN, MATERIAL=RIGIDMAT")
w(f"*RIGID BODY, NSET=NPLATEN, REF NODE={REF}, ROT NODE={ROT}")

w("*SURFACE INTERACTION, NAME=SI1")
w("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR")
w(f"{K:g}")
if mu > 0:
    w("*FRICTION")
    w(f"{mu:g}, {LAM:g}")
w("*CONTACT PAIR, INTERACTION=SI1, TYPE=SURFACE TO SURFACE")
w("SBTOP, SPLAT")

w("*BOUNDARY")
w("NX0, 1, 1, 0.")
w("NY0, 2, 2, 0.")
w("NZ0, 3, 3, 0.")
w(f"{REF}, 1, 2, 0.")
w(f"{ROT}, 1, 3, 0.")
w("*AMPLITUDE, NAME=RAMP")
w("0., 0., 1., 1.")
w("*TIME POINTS, NAME=T1")
w(", ".join(f"{0.1 * i:.1f}" for i in range(1, 6)))
w(", ".join(f"{0.1 * i:.1f}" for i in range(6, 11)))
w("*STEP, NLGEOM, INC=2000")
w("*STATIC")
w("0.01, 1.0, 1e-6, 0.02")
w("*BOUNDARY, AMPLITUDE=RAMP")
w(f"{REF}, 3, 3, {-DZ}")
w("*NODE PRINT, NSET=NZ0, TOTALS=ONLY, TIME POINTS=T1")
w("RF")
w("*NODE PRINT, NSET=NREF, TIME POINTS=T1")
w("U, RF")
w("*CONTACT PRINT, TIME POINTS=T1, SLAVE=SBTOP, MASTER=SPLAT")
w("CF")
w("*NODE FILE, TIME POINTS=T1")
w("U, RF")
w("*EL FILE, TIME POINTS=T1")
w("S, PEEQ")
w("*CONTACT FILE, TIME POINTS=T1")
w("CDIS, CSTR")
w("*END STEP")

with open(name + ".inp", "w") as f:
    f.write("\n".join(L) + "\n")
print(name + ".inp", len(nodes), "nodes", len(elems), "elements")
