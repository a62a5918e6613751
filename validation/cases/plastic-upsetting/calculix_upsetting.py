#!/usr/bin/env python3
"""CalculiX input for the plane-strain upsetting of validation/cases/plastic-upsetting
(half block 10 x 5, one element layer 0.5 thick with u_z = 0, J2 with linear
hardening, NLGEOM). Case A: the top stuck and moved down 1.5 (sticking.toml);
case B: a rigid platen pressing down 1.5 with mu = 0.1 (case.toml). Forces:
*NODE PRINT RF totals of the top (A) or the platen (B) in the .dat file.

usage: calculix_upsetting.py case(A|B) nx ny elem(C3D20R|C3D8I) [dtinit dtmax]
       [contact type] [penalty] [out.inp]; then ccx -i out
"""
import sys
case, nx, ny, el = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
dt0 = float(sys.argv[5]) if len(sys.argv) > 5 else 0.01
dtmax = float(sys.argv[6]) if len(sys.argv) > 6 else 0.02
ctype = sys.argv[7] if len(sys.argv) > 7 else 'NODE TO SURFACE'
kpen = float(sys.argv[8]) if len(sys.argv) > 8 else 1e7
L, H, T = 10.0, 5.0, 0.5
quad = el.startswith('C3D20')
nodes = {}  # (i,j,k) on refined grid -> id
coords = {}
def nid(i, j, k):
    key = (i, j, k)
    if key not in nodes:
        nodes[key] = len(nodes) + 1
    return nodes[key]
elems = []
r = 2 if quad else 1
for ey in range(ny):
    for ex in range(nx):
        i0, j0 = r*ex, r*ey
        if quad:
            c = [(0,0),(2,0),(2,2),(0,2)]
            lo = [nid(i0+a, j0+b, 0) for a,b in c]
            hi = [nid(i0+a, j0+b, 2) for a,b in c]
            m = [(1,0),(2,1),(1,2),(0,1)]
            mlo = [nid(i0+a, j0+b, 0) for a,b in m]
            mhi = [nid(i0+a, j0+b, 2) for a,b in m]
            mz = [nid(i0+a, j0+b, 1) for a,b in c]
            elems.append(lo+hi+mlo+mhi+mz)
        else:
            c = [(0,0),(1,0),(1,1),(0,1)]
            elems.append([nid(i0+a,j0+b,0) for a,b in c]+[nid(i0+a,j0+b,r) for a,b in c])
kmax = 2 if quad else 1
out = []
w = out.append
w('*HEADING\nupsetting case %s %dx%d %s' % (case, nx, ny, el))
w('*NODE, NSET=NALL')
for (i,j,k), n in sorted(nodes.items(), key=lambda t: t[1]):
    w('%d, %.10g, %.10g, %.10g' % (n, L*i/(r*nx), H*j/(r*ny), T*k/kmax))
w('*ELEMENT, TYPE=%s, ELSET=BLOCK' % el)
for e, conn in enumerate(elems, 1):
    s = [str(e)] + [str(x) for x in conn]
    # continuation lines max 16 entries per line
    w(', '.join(s[:16]) + (',' if len(s) > 16 else ''))
    if len(s) > 16: w(', '.join(s[16:]))
def nset(name, pred):
    ids = sorted(n for (i,j,k), n in nodes.items() if pred(i,j,k))
    w('*NSET, NSET=%s' % name)
    for a in range(0, len(ids), 10):
        w(', '.join(map(str, ids[a:a+10])) + ',')
nset('XSYM', lambda i,j,k: i == 0)
nset('YSYM', lambda i,j,k: j == 0)
nset('TOP', lambda i,j,k: j == r*ny)
nset('TOPZ0', lambda i,j,k: j == r*ny and k == 0)
w('*MATERIAL, NAME=STEEL\n*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.0\n2200., 2.0')
w('*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL')
ne = len(elems)
if case == 'B':
    # rigid platen: one layer of C3D8 elements, all nodes prescribed
    npx = 2*nx
    x0, x1 = -0.5, 20.0
    base = max(nodes.values())
    pn = {}
    w('*NODE, NSET=PLATN')
    cnt = base
    for j, y in enumerate([H, H+1.0]):
        for k, z in enumerate([-0.1, T+0.1]):
            for i in range(npx+1):
                cnt += 1; pn[(i,j,k)] = cnt
                w('%d, %.10g, %.10g, %.10g' % (cnt, x0+(x1-x0)*i/npx, y, z))
    w('*ELEMENT, TYPE=C3D8, ELSET=PLATEN')
    for i in range(npx):
        ne += 1
        c = [(0,0),(1,0),(1,1),(0,1)]
        conn = [pn[(i+a,b,0)] for a,b in c] + [pn[(i+a,b,1)] for a,b in c]
        w('%d, ' % ne + ', '.join(map(str, conn)))
    w('*MATERIAL, NAME=RIG\n*ELASTIC\n2e8, 0.3')
    w('*SOLID SECTION, ELSET=PLATEN, MATERIAL=RIG')
    # surfaces
    w('*SURFACE, NAME=MAST, TYPE=ELEMENT')
    for e in range(len(elems)+1, ne+1): w('%d, S3' % e)
    w('*SURFACE, NAME=SLAV, TYPE=ELEMENT')
    for e in range((ny-1)*nx+1, ny*nx+1): w('%d, S5' % e)
    w('*CONTACT PAIR, INTERACTION=SI, TYPE=%s' % ctype)
    w('SLAV, MAST')
    w('*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR')
    w('%g' % kpen)
    w('*FRICTION\n0.1, %g' % (kpen/10))
w('*AMPLITUDE, NAME=RAMP\n0., 0., 1., 1.')
tp=[round(0.02*i,4) for i in range(1,51)]
w('*TIME POINTS, NAME=TP')
for a in range(0,50,8): w(', '.join('%g'%x for x in tp[a:a+8]))
w('*BOUNDARY\nXSYM, 1, 1, 0.\nYSYM, 2, 2, 0.\nNALL, 3, 3, 0.')
if case == 'B':
    w('PLATN, 1, 1, 0.\nPLATN, 3, 3, 0.')
w('*STEP, NLGEOM, INC=100000')
w('*STATIC\n%g, 1.0, 1e-7, %g' % (dt0, dtmax))
w('*BOUNDARY, AMPLITUDE=RAMP')
if case == 'A':
    w('TOP, 1, 1, 0.\nTOP, 2, 2, -1.5')
else:
    w('PLATN, 2, 2, -1.5')
rset = 'TOP' if case == 'A' else 'PLATN'
w('*NODE PRINT, NSET=%s, TOTALS=ONLY' % rset)
w('RF')
if case == 'B':
    w('*NODE PRINT, NSET=TOPZ0, TIME POINTS=TP\nU')
    w('*CONTACT FILE, TIME POINTS=TP\nCDIS, CSTR')
w('*NODE FILE, TIME POINTS=TP\nU\n*EL FILE, TIME POINTS=TP\nS, PEEQ')
w('*END STEP')
open(sys.argv[9] if len(sys.argv) > 9 else 'out.inp', 'w').write('\n'.join(out) + '\n')
