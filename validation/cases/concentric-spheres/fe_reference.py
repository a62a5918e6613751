#!/usr/bin/env python3
"""Independent check for concentric-spheres: a thick hollow hemisphere
(r 12-14 mm, the outer sphere) under a pole load, solved by an axisymmetric
finite-element model with 8-node serendipity quadrilaterals (3 x 3 Gauss
points), written only to check the finite-volume solver on the shells'
bending. Not run by the tests (it needs numpy).

Set-up (pole-load.toml): bowl below z = 0, linear elastic, E = 1 MPa,
nu = 0.3, small strain; the rim z = 0 on rollers (u_z = 0, the symmetry
condition of the benchmark); a pressure of 1e-3 MPa on the outer surface
within 15 degrees of the pole.

    python3 fe_reference.py NR NT          # NR x NT elements (NT: multiple of 6)
    python3 fe_reference.py mesh NR NT > pole-load.msh
                                           # the finite-volume wedge (Gmsh 4.1)

Measured, u_z at the poles (mm) and u_r at the outer rim:

    NR x NT    outer pole (z = -14)   inner pole (z = -12)   rim r = 14
    4 x 30     4.736327e-2            4.851769e-2            4.630138e-3
    6 x 60     4.736706e-2            4.851862e-2            4.630098e-3
    8 x 90     4.736760e-2            4.851889e-2            4.630093e-3

The finite-volume wedge of pole-load.toml (8 x 90 cells; boundary faces
nearest the poles and farthest on the rim) gives 4.7569e-2, 4.8708e-2,
4.6220e-3 (+0.43, +0.39, -0.17 %); its point values (interpolated from the
cells) with 16 x 180 cells 4.7378e-2, 4.8500e-2, 4.6232e-3 (+0.02, -0.04,
-0.15 %).
"""
import math
import sys

R0, R1 = 12.0, 14.0
E, NU, P = 1.0, 0.3, 1e-3
CAP_DEG = 15.0
HALF_ANGLE = math.radians(2.5)


def fe(nr, nt):
    import numpy as np

    ni, nj = 2 * nr + 1, 2 * nt + 1
    gid = -np.ones((ni, nj), int)
    x = []
    for i in range(ni):
        for j in range(nj):
            if i % 2 == 1 and j % 2 == 1:
                continue  # serendipity: no centre node
            r = R0 + (R1 - R0) * i / (ni - 1)
            ph = math.pi / 2 * j / (nj - 1)
            gid[i, j] = len(x)
            x.append((r * math.sin(ph), -r * math.cos(ph)))
    x = np.array(x)
    ndof = 2 * len(x)
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    mids = [(0, -1), (1, 0), (0, 1), (-1, 0)]

    def shape(s, t):
        n = np.zeros(8)
        dn = np.zeros((8, 2))
        for a, (sa, ta) in enumerate(corners):
            n[a] = 0.25 * (1 + s * sa) * (1 + t * ta) * (s * sa + t * ta - 1)
            dn[a] = (0.25 * sa * (1 + t * ta) * (2 * s * sa + t * ta),
                     0.25 * ta * (1 + s * sa) * (s * sa + 2 * t * ta))
        for a, (sa, ta) in enumerate(mids, start=4):
            if sa == 0:
                n[a] = 0.5 * (1 - s * s) * (1 + t * ta)
                dn[a] = (-s * (1 + t * ta), 0.5 * ta * (1 - s * s))
            else:
                n[a] = 0.5 * (1 + s * sa) * (1 - t * t)
                dn[a] = (0.5 * sa * (1 - t * t), -t * (1 + s * sa))
        return n, dn

    c = E / ((1 + NU) * (1 - 2 * NU))
    # strains (rr, zz, theta-theta, rz)
    d = c * np.array([[1 - NU, NU, NU, 0], [NU, 1 - NU, NU, 0],
                      [NU, NU, 1 - NU, 0], [0, 0, 0, (1 - 2 * NU) / 2]])
    g = math.sqrt(0.6)
    gauss = [(-g, 5 / 9), (0.0, 8 / 9), (g, 5 / 9)]
    k = np.zeros((ndof, ndof))
    f = np.zeros(ndof)
    for ei in range(nr):
        for ej in range(nt):
            i0, j0 = 2 * ei, 2 * ej
            conn = [gid[i0, j0], gid[i0 + 2, j0], gid[i0 + 2, j0 + 2], gid[i0, j0 + 2],
                    gid[i0 + 1, j0], gid[i0 + 2, j0 + 1], gid[i0 + 1, j0 + 2], gid[i0, j0 + 1]]
            xe = x[conn]
            dofs = np.array([[2 * a, 2 * a + 1] for a in conn]).ravel()
            ke = np.zeros((16, 16))
            for s, ws in gauss:
                for t, wt in gauss:
                    n, dn = shape(s, t)
                    jac = dn.T @ xe
                    dnx = dn @ np.linalg.inv(jac).T
                    r = n @ xe[:, 0]
                    b = np.zeros((4, 16))
                    b[0, 0::2] = dnx[:, 0]
                    b[1, 1::2] = dnx[:, 1]
                    b[2, 0::2] = n / r
                    b[3, 0::2] = dnx[:, 1]
                    b[3, 1::2] = dnx[:, 0]
                    ke += b.T @ d @ b * r * np.linalg.det(jac) * ws * wt
            k[np.ix_(dofs, dofs)] += ke
            if ei == nr - 1 and (ej + 1) * 90.0 / nt <= CAP_DEG + 1e-9:
                edge = [gid[ni - 1, j0], gid[ni - 1, j0 + 1], gid[ni - 1, j0 + 2]]
                xe2 = x[edge]
                for s, w in gauss:
                    l = np.array([0.5 * s * (s - 1), 1 - s * s, 0.5 * s * (s + 1)])
                    dl = np.array([s - 0.5, -2 * s, s + 0.5])
                    xs, tg = l @ xe2, dl @ xe2
                    nv = np.array([tg[1], -tg[0]])  # |tangent| ds folded in
                    if nv @ xs < 0:
                        nv = -nv
                    for a in range(3):
                        f[2 * edge[a]:2 * edge[a] + 2] += -P * nv * l[a] * xs[0] * w
    fixed = [2 * a for a in range(len(x)) if abs(x[a, 0]) < 1e-12]
    fixed += [2 * a + 1 for a in range(len(x)) if abs(x[a, 1]) < 1e-12]
    free = np.setdiff1d(np.arange(ndof), fixed)
    u = np.zeros(ndof)
    u[free] = np.linalg.solve(k[np.ix_(free, free)], f[free])
    print("outer pole u_z = %.6e, inner pole u_z = %.6e, rim u_r = %.6e" % (
        u[2 * gid[ni - 1, 0] + 1], u[2 * gid[0, 0] + 1], u[2 * gid[ni - 1, nj - 1]]))


def mesh(nr, nt):
    """The finite-volume wedge: +-2.5 degrees about z, prisms at the pole;
    patches inner, outer, cap (outer within CAP_DEG of the pole), rim,
    front, back."""
    pts, at = [], {}
    for i in range(nr + 1):
        r = R0 + (R1 - R0) * i / nr
        for j in range(nt + 1):
            ph = math.pi / 2 * j / nt
            rho, z = r * math.sin(ph), -r * math.cos(ph)
            for sd in (-1, 1):
                if j == 0 and sd == 1:
                    at[(i, j, sd)] = at[(i, j, -1)]
                    continue
                pts.append((rho * math.cos(HALF_ANGLE), sd * rho * math.sin(HALF_ANGLE), z))
                at[(i, j, sd)] = len(pts)
    groups = {n: [] for n in ("inner", "outer", "cap", "rim", "front", "back")}
    cells = []
    for i in range(nr):
        for j in range(nt):
            q = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            lo = [at[p + (-1,)] for p in q]
            hi = [at[p + (1,)] for p in q]
            if j == 0:
                cells.append((6, [lo[0], lo[3], hi[3], lo[1], lo[2], hi[2]]))
            else:
                cells.append((5, lo + hi))
            groups["back"].append(lo)
            groups["front"].append(hi)
    for j in range(nt):
        for i, name in ((0, "inner"), (nr, "outer")):
            if name == "outer" and (j + 1) * 90.0 / nt <= CAP_DEG + 1e-9:
                name = "cap"
            a, b = (i, j), (i, j + 1)
            face = [at[a + (-1,)], at[b + (-1,)], at[b + (1,)]]
            if j > 0:
                face.append(at[a + (1,)])
            groups[name].append(face)
    for i in range(nr):
        a, b = (i, nt), (i + 1, nt)
        groups["rim"].append([at[a + (-1,)], at[b + (-1,)], at[b + (1,)], at[a + (1,)]])
    names = list(groups)
    out = sys.stdout.write
    out("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % (len(names) + 1))
    for t, n in enumerate(names, start=1):
        out('2 %d "%s"\n' % (t, n))
    out('3 100 "shell"\n$EndPhysicalNames\n$Entities\n0 0 %d 1\n' % len(names))
    for t in range(1, len(names) + 1):
        out("%d 0 0 0 0 0 0 1 %d 0\n" % (t, t))
    out("100 0 0 0 0 0 0 1 100 0\n$EndEntities\n")
    out("$Nodes\n1 %d 1 %d\n3 100 0 %d\n" % (len(pts), len(pts), len(pts)))
    out("".join("%d\n" % (k + 1) for k in range(len(pts))))
    out("".join("%.12g %.12g %.12g\n" % p for p in pts))
    out("$EndNodes\n$Elements\n")
    blocks = [(3, 100, 6, [c for t, c in cells if t == 6]), (3, 100, 5, [c for t, c in cells if t == 5])]
    for t, n in enumerate(names, start=1):
        for nn, ty in ((3, 2), (4, 3)):
            faces = [fc for fc in groups[n] if len(fc) == nn]
            if faces:
                blocks.append((2, t, ty, faces))
    total = sum(len(b[3]) for b in blocks)
    out("%d %d 1 %d\n" % (len(blocks), total, total))
    tag = 1
    for dim, ent, ty, els in blocks:
        out("%d %d %d %d\n" % (dim, ent, ty, len(els)))
        for e in els:
            out("%d %s\n" % (tag, " ".join(map(str, e))))
            tag += 1
    out("$EndElements\n")


if __name__ == "__main__":
    if sys.argv[1] == "mesh":
        mesh(int(sys.argv[2]), int(sys.argv[3]))
    else:
        fe(int(sys.argv[1]), int(sys.argv[2]))
