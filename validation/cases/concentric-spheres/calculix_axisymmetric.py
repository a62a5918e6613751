#!/usr/bin/env python3
"""Peer-code check for concentric-spheres (thesis §5.3.4; issue 7): writes a
CalculiX deck of the axisymmetric problem the benchmark is before buckling,
to compare the plate force with a converged finite-element solution. Not
run by the tests (it needs CalculiX, Debian package calculix-ccx).

Set-up, as validation/cases/concentric-spheres/axisymmetric.toml: x = radius,
y = axis (our z); hollow neo-Hookean bowls r 10-12 and 12-14 (y <= 0),
*HYPERELASTIC, NEO HOOKE with C10 = mu/2 = 0.1923 and D1 = 2/K = 2.4 (E = 1,
nu = 0.3); rim nodes u_y = 0, axis nodes u_x = 0; a plate of one layer of
elements at y in [-15, -14], every node driven (kinematically rigid) up by
dmax; two frictionless face-to-face contact pairs (plate / outer shell,
outer shell / inner shell), linear penalty K (default 1000 MPa/mm);
*STEP, NLGEOM with automatic increments of at most dt.

    python3 calculix_axisymmetric.py NR NT [--etype CAX8] [--dmax 4] \
        [--dt 0.1] [--delcon 0.02] [--out NAME]
    OMP_NUM_THREADS=1 ccx -i NAME

NR elements through each wall, NT along the meridian from pole to rim.
CalculiX reports the reactions of axisymmetric elements for a 2-degree
segment (checked on a cylinder compressed directly and through contact), so
the quarter model's force is 45 x |RF_y| of set NPLATE in NAME.dat.

Measured (CalculiX 2.20, delcon 0.02; quarter-model force in N at 1.5 / 2 /
3 / 4 mm):

    CAX8 4 x 30      0.5126  0.7213  1.1982
    CAX8 8 x 60      0.5124  0.7213  1.1963  1.7387
    CAX8 16 x 120    0.5123  0.7212  1.1967  1.7382
    CAX4 32 x 240    0.5125  0.7217  1.1975
    CAX4 3 x 15      0.5321  0.7562  1.2274          (coarse linear: stiff)

With friction between the shells (--mu 0.5) CalculiX needs a soft stick
slope (--kt, default 50) and small increments (--dt 0.02): at kt = 1000
it stopped in its first increments.

K = 100 / 10,000 instead of 1000 moves the force by at most 0.15 / 0.02 %;
swapping the shells' master and slave by 0.07 %; the default contact
convergence (no delcon) by at most 0.14 %. The converged force is 0.7 %
under the finite-volume axisymmetric section (16 x 120 cells per shell) and
6-10 % under the Abaqus/FEBio mean the benchmark's acceptance names
(validation::benchmarks::concentric_spheres::CALCULIX_AXISYMMETRIC).
"""
import argparse, math
p = argparse.ArgumentParser()
p.add_argument('nr', type=int); p.add_argument('nt', type=int)
p.add_argument('--etype', default='CAX8')
p.add_argument('--K', type=float, default=1000.0)
p.add_argument('--mu', type=float, default=0.0, help='Coulomb friction between the shells')
p.add_argument('--kt', type=float, default=50.0, help='stick slope of the friction, MPa/mm')
p.add_argument('--dmax', type=float, default=4.0)
p.add_argument('--dt', type=float, default=0.1)
p.add_argument('--grade', type=float, default=1.0)
p.add_argument('--plate_n', type=int, default=0)
p.add_argument('--slave', default='outer', help="which shell surface at r=12 is the slave: 'outer' (outer shell inner face) or 'inner'")
p.add_argument('--out', default=None)
p.add_argument('--ctype', default='SURFACE TO SURFACE')
p.add_argument('--hard', action='store_true')
p.add_argument('--Rn', type=float, default=0.0, help='if >0: *CONTROLS FIELD residual tolerance R_n (ccx default 0.005)')
p.add_argument('--delcon', type=float, default=0.02, help='if >0: *CONTROLS, PARAMETERS=CONTACT delcon (allowed relative change of # contact elements at convergence)')
p.add_argument('--small', action='store_true', help='SMALL SLIDING on contact pairs')
a = p.parse_args()
quad = a.etype.startswith('CAX8')
out = a.out or f"sph_{a.etype}_{a.nr}x{a.nt}_K{a.K:g}" + (f"_g{a.grade:g}" if a.grade != 1 else "")
nodes = []          # (id, x, y)
elems = []          # (id, [conn])
nid = [0]; eid = [0]
def addnode(x, y):
    nid[0] += 1; nodes.append((nid[0], x, y)); return nid[0]

def shell(r0, r1, nr, nt):
    """structured CAX grid on r in [r0,r1], phi in [0,pi/2] (phi measured from the pole (0,-r))."""
    m = 2 if quad else 1
    Ni, Nj = m*nr, m*nt
    N = {}
    for j in range(Nj+1):
        phi = 0.5*math.pi*(j/Nj)**a.grade
        for i in range(Ni+1):
            if quad and i % 2 == 1 and j % 2 == 1: continue
            r = r0 + (r1-r0)*i/Ni
            x = r*math.sin(phi); y = -r*math.cos(phi)
            if j == 0: x = 0.0
            if j == Nj: y = 0.0
            N[(i, j)] = addnode(x, y)
    E = []; faces = {'in': [], 'out': []}
    for j in range(nt):
        for i in range(nr):
            I, J = m*i, m*j
            if quad:
                c = [N[(I,J)], N[(I+2,J)], N[(I+2,J+2)], N[(I,J+2)],
                     N[(I+1,J)], N[(I+2,J+1)], N[(I+1,J+2)], N[(I,J+1)]]
            else:
                c = [N[(I,J)], N[(I+1,J)], N[(I+1,J+1)], N[(I,J+1)]]
            eid[0] += 1; elems.append((eid[0], c)); E.append(eid[0])
            if i == 0: faces['in'].append(eid[0])        # face 4 (4-1): r = r0
            if i == nr-1: faces['out'].append(eid[0])    # face 2 (2-3): r = r1
    axis = [N[k] for k in N if k[1] == 0]
    rim = [N[k] for k in N if k[1] == Nj]
    return E, faces, axis, rim

Ein, Fin, AXin, RIMin = shell(10.0, 12.0, a.nr, a.nt)
Eout, Fout, AXout, RIMout = shell(12.0, 14.0, a.nr, a.nt)
# plate: x in [0,18], y in [-15,-14]; one element thick, all nodes driven kinematically
npl = a.plate_n or (a.nt if quad else 2 * a.nt)   # plate (master) elements over 18 mm, as fine as the shells' surface
m = 2 if quad else 1
PL = {}
for j in range(m+1):
    for i in range(m*npl+1):
        if quad and i % 2 == 1 and j % 2 == 1: continue
        PL[(i, j)] = addnode(18.0*i/(m*npl), -15.0 + 1.0*j/m)
Epl = []
for i in range(npl):
    I = m*i
    if quad:
        c = [PL[(I,0)], PL[(I+2,0)], PL[(I+2,2)], PL[(I,2)], PL[(I+1,0)], PL[(I+2,1)], PL[(I+1,2)], PL[(I,1)]]
    else:
        c = [PL[(I,0)], PL[(I+1,0)], PL[(I+1,1)], PL[(I,1)]]
    eid[0] += 1; elems.append((eid[0], c)); Epl.append(eid[0])

def lst(v, n=8):
    v = list(v); return "\n".join(", ".join(map(str, v[k:k+n])) for k in range(0, len(v), n))
L = []
L.append(f"** generated by calculix_axisymmetric.py {a.nr} {a.nt} etype={a.etype} K={a.K} dmax={a.dmax} dt={a.dt} grade={a.grade}")
L.append("*NODE, NSET=NALL")
L += [f"{i}, {x:.12f}, {y:.12f}" for i, x, y in nodes]
ed = dict(elems)
for name, E in (('EIN', Ein), ('EOUT', Eout), ('EPLATE', Epl)):
    L.append(f"*ELEMENT, TYPE={a.etype}, ELSET={name}")
    L += [f"{e}, " + ", ".join(map(str, ed[e])) for e in E]
L.append("*NSET, NSET=NPLATE"); L.append(lst(PL.values()))
L.append("*NSET, NSET=NAXIS"); L.append(lst(AXin + AXout))
L.append("*NSET, NSET=NRIM"); L.append(lst(RIMin + RIMout))
L.append("*SURFACE, NAME=S_IN_OUT, TYPE=ELEMENT");  L += [f"{e}, S2" for e in Fin['out']]
L.append("*SURFACE, NAME=S_OUT_IN, TYPE=ELEMENT");  L += [f"{e}, S4" for e in Fout['in']]
L.append("*SURFACE, NAME=S_OUT_OUT, TYPE=ELEMENT"); L += [f"{e}, S2" for e in Fout['out']]
L.append("*SURFACE, NAME=S_PLATE, TYPE=ELEMENT");   L += [f"{e}, S3" for e in Epl]
L.append("""*MATERIAL, NAME=NH
*HYPERELASTIC, NEO HOOKE
0.1923076923, 2.4
*MATERIAL, NAME=STIFF
*ELASTIC
1.0e4, 0.3
*SOLID SECTION, ELSET=EIN, MATERIAL=NH
*SOLID SECTION, ELSET=EOUT, MATERIAL=NH
*SOLID SECTION, ELSET=EPLATE, MATERIAL=STIFF""")
# SI: plate / outer shell, frictionless; SS: between the shells, Coulomb mu
for name, mu in (("SI", 0.0), ("SS", a.mu)):
    L.append(f"*SURFACE INTERACTION, NAME={name}")
    if a.hard: L.append("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD")
    else: L.append("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR"); L.append(f"{a.K:g}")
    if mu > 0: L.append("*FRICTION"); L.append(f"{mu:g}, {a.kt:g}")
L.append(f"*CONTACT PAIR, INTERACTION=SI, TYPE={a.ctype}" + (", SMALL SLIDING" if a.small else ""))
L.append("S_OUT_OUT, S_PLATE")
L.append(f"*CONTACT PAIR, INTERACTION=SS, TYPE={a.ctype}" + (", SMALL SLIDING" if a.small else ""))
L.append("S_OUT_IN, S_IN_OUT" if a.slave == 'outer' else "S_IN_OUT, S_OUT_IN")
L.append("*BOUNDARY\nNAXIS, 1, 1, 0.\nNRIM, 2, 2, 0.\nNPLATE, 1, 1, 0.")
# Output at fixed plate displacements; with friction every increment instead
# (there *TIME POINTS made CalculiX 2.20 take a zero increment and stop).
tp = sorted(set([round(0.25*k, 6) for k in range(1, int(round(a.dmax/0.25))+1)] + [1.5]))
if a.mu == 0:
    L.append("*TIME POINTS, NAME=TP"); L.append(lst([f"{t:g}" for t in tp if t <= a.dmax + 1e-9]))
at = "TIME POINTS=TP" if a.mu == 0 else "FREQUENCY=1"
L.append("*STEP, NLGEOM, INC=100000")
if a.delcon > 0: L.append(f"*CONTROLS, PARAMETERS=CONTACT\n{a.delcon:g}")
if a.Rn > 0: L.append(f"*CONTROLS, PARAMETERS=FIELD\n{a.Rn:g}, 0.02")
L.append(f"*STATIC\n{a.dt:g}, {a.dmax:g}, 1e-8, {a.dt:g}")
L.append(f"*BOUNDARY\nNPLATE, 2, 2, {a.dmax:g}")
L.append(f"*NODE PRINT, NSET=NPLATE, TOTALS=ONLY, {at}\nRF")
L.append(f"*NODE FILE, {at}\nU\n*EL FILE, {at}\nS\n*CONTACT FILE, {at}\nCDIS, CSTR")
L.append("*END STEP")
open(out + ".inp", "w").write("\n".join(L) + "\n")
print(out, len(nodes), "nodes", len(elems), "elements")
