#!/usr/bin/env python3
"""Independent reference for nafems-punch: an axisymmetric finite-element
solution of the same problem with biquadratic (Q9) elements, written only to
check the finite-volume results and the benchmark references. Not run by the
tests (it needs numpy and scipy).

Set-up as in case.toml: punch radius 50 mm, height 100 mm, bottom edge
filleted with R 10 mm (flat part radius 40 mm), E = 210 GPa, 100 MPa on its
top; foundation radius 100 mm, height 200 mm, bottom fixed, side free,
E = 70 GPa; ν = 0.3; small strain, one increment.

Contact: the punch's bottom nodes against the flat top edge of the
foundation (node to segment; the master is flat, so the vertical gap is the
normal gap), Lagrange multipliers with an active set; Coulomb friction by a
stick/slip active set (stick: tangential multiplier, slip: μλ against the
slip). Pressure from the multipliers with the consistent surface mass matrix.

    python3 fe_reference.py H MU     # H: element size at the contact (mm)
    python3 fe_reference.py disc H   # the foundation alone, pressure on a disc

Measured (frictionless / μ = 0.1), foundation on the axis:

    H      u_y (mm)             p (MPa)
    1      -0.134167 -0.132006  87.51 88.97
    0.5    -0.133918 -0.131738  87.20 88.63
    0.25   -0.133932 -0.131758  87.22 88.65

The foundation alone under 156.25 MPa over r < 40 mm (no contact; the
same load as the punch's, foundation-disc.toml) converges to (H = 0.25; H = 1
and 0.5 differ by < 0.003 %) u_y = -0.165254, -0.162780, -0.154943,
-0.139988, -0.128134 mm at r = 0, 10, 20, 30, 35 mm.
"""
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

GP = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
GW = np.array([5.0, 8.0, 5.0]) / 9.0


def graded(h, uniform, total, g):
    """Element boundaries: size h up to `uniform`, then growing by g to `total`."""
    x = list(np.linspace(0.0, uniform, int(round(uniform / h)) + 1)) if uniform > 0 else [0.0]
    d = h
    while x[-1] < total - 1e-9:
        d *= g
        x.append(min(x[-1] + d, total))
    if len(x) > 2 and total - x[-2] < 0.5 * d:
        x.pop(-2)
    return np.array(x)


def with_mid(x):
    out = np.empty(2 * len(x) - 1)
    out[0::2] = x
    out[1::2] = 0.5 * (x[:-1] + x[1:])
    return out


def line3(t):
    return np.array([0.5 * t * (t - 1), 1 - t * t, 0.5 * t * (t + 1)]), np.array([t - 0.5, -2 * t, t + 0.5])


def q9_shape(xi, eta):
    lx, dlx = line3(xi)
    ly, dly = line3(eta)
    return np.outer(ly, lx).ravel(), np.outer(ly, dlx).ravel(), np.outer(dly, lx).ravel()


def grid_body(X, Y):
    """Q9 elements of a node grid (rows along eta, columns along xi, 2m+1 x 2n+1)."""
    ny, nx = X.shape
    idx = np.arange(nx * ny).reshape(ny, nx)
    els = [idx[j:j + 3, i:i + 3].ravel() for j in range(0, ny - 2, 2) for i in range(0, nx - 2, 2)]
    return np.column_stack([X.ravel(), Y.ravel()]), np.array(els), idx


def stiffness(nodes, els, E, nu):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.array([[lam + 2 * mu, lam, lam, 0], [lam, lam + 2 * mu, lam, 0],
                  [lam, lam, lam + 2 * mu, 0], [0, 0, 0, mu]])
    ne = len(els)
    Ke = np.zeros((ne, 18, 18))
    xe = nodes[els]
    for a, wa in zip(GP, GW):
        for b, wb in zip(GP, GW):
            N, dNx, dNy = q9_shape(a, b)
            J = np.stack([np.einsum('k,ekd->ed', dNx, xe), np.einsum('k,ekd->ed', dNy, xe)], axis=1)
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
            dNr = (J[:, 1, 1, None] * dNx - J[:, 0, 1, None] * dNy) / det[:, None]
            dNz = (-J[:, 1, 0, None] * dNx + J[:, 0, 0, None] * dNy) / det[:, None]
            r = xe[:, :, 0] @ N
            B = np.zeros((ne, 4, 18))
            B[:, 0, 0::2] = dNr           # ε_rr
            B[:, 1, 1::2] = dNz           # ε_zz
            B[:, 2, 0::2] = N[None, :] / r[:, None]  # ε_θθ
            B[:, 3, 0::2] = dNz           # γ_rz
            B[:, 3, 1::2] = dNr
            Ke += np.einsum('eia,ij,ejb->eab', B, D, B) * (2 * np.pi * r * det * wa * wb)[:, None, None]
    dof = np.zeros((ne, 18), int)
    dof[:, 0::2] = 2 * els
    dof[:, 1::2] = 2 * els + 1
    n = 2 * len(nodes)
    I = np.repeat(dof, 18, axis=1).ravel()
    J = np.tile(dof, (1, 18)).ravel()
    return sp.coo_matrix((Ke.ravel(), (I, J)), shape=(n, n)).tocsr()


def edge_integrals(nodes, edge):
    """Consistent load vector per unit pressure and surface mass matrix of an
    edge of quadratic segments (weights 2πr ds)."""
    m = len(edge)
    load = np.zeros(m)
    M = np.zeros((m, m))
    for k in range(0, m - 2, 2):
        x = nodes[edge[k:k + 3]]
        for t, w in zip(GP, GW):
            N, dN = line3(t)
            wr = 2 * np.pi * (N @ x[:, 0]) * np.linalg.norm(dN @ x) * w
            load[k:k + 3] += N * wr
            M[k:k + 3, k:k + 3] += np.outer(N, N) * wr
    return load, M


def build(h, g=1.1):
    # foundation: r in [0, 100] (size h to r = 45), z in [-200, 0]
    R = with_mid(graded(h, 45, 100, g))
    Z = -with_mid(graded(h, 0, 200, g))[::-1]
    nf, ef, idf = grid_body(*np.meshgrid(R, Z))
    # punch: Coons patch on (ξ, η) ∈ [0,1]²; bottom = flat + fillet by arc
    # length s, corners (0,0), (50,10), (50,100), (0,100)
    L = 40 + 5 * np.pi
    S = with_mid(graded(h, 45, L, g))
    T = with_mid(graded(h, 0, 90, g)) / 90.0
    xi = S / L
    bx = np.where(S <= 40, S, 40 + 10 * np.sin((S - 40) / 10))
    by = np.where(S <= 40, 0.0, 10 - 10 * np.cos((S - 40) / 10))
    XI, ET = np.meshgrid(xi, T)
    BX, BY = np.meshgrid(bx, T)[0], np.meshgrid(by, T)[0]
    X = (1 - ET) * BX + ET * 50 * XI + XI * 50 - XI * (1 - ET) * 50 - XI * ET * 50
    Y = (1 - ET) * BY + ET * 100 + (1 - XI) * 100 * ET + XI * (10 + 90 * ET) \
        - (XI * (1 - ET) * 10 + XI * ET * 100 + (1 - XI) * ET * 100)
    npn, ep, idp = grid_body(X, Y)
    return (nf, ef, idf), (npn, ep, idp)


def solve(h, mu, p=100.0):
    (nf, ef, idf), (npn, ep, idp) = build(h)
    nF, nP = 2 * len(nf), 2 * len(npn)
    K = sp.block_diag([stiffness(nf, ef, 70000.0, 0.3), stiffness(npn, ep, 210000.0, 0.3)]).tocsr()
    f = np.zeros(nF + nP)
    top = idp[-1, :]
    load, _ = edge_integrals(npn, top)
    f[nF + 2 * top + 1] -= p * load
    fixed = set(2 * idf[0, :]) | set(2 * idf[0, :] + 1) | set(2 * idf[:, 0]) | set(nF + 2 * idp[:, 0])
    free = np.array(sorted(set(range(nF + nP)) - fixed))
    # contact rows: normal (C) and radial (T) relative displacement, punch minus foundation
    slave = idp[0, :]
    ftop = idf[-1, :]
    rtop = nf[ftop, 0]
    C = sp.lil_matrix((len(slave), nF + nP))
    T = sp.lil_matrix((len(slave), nF + nP))
    gaps = npn[slave, 1].copy()
    rs = npn[slave, 0]
    for k, nid in enumerate(slave):
        j = min(max(0, np.searchsorted(rtop, rs[k]) - 1), len(rtop) - 2)
        j -= j % 2
        x3 = rtop[j:j + 3]
        N, _ = line3(2 * (rs[k] - x3[0]) / (x3[2] - x3[0]) - 1)
        C[k, nF + 2 * nid + 1] = 1.0
        T[k, nF + 2 * nid] = 1.0
        for i in range(3):
            C[k, 2 * ftop[j + i] + 1] = -N[i]
            T[k, 2 * ftop[j + i]] = -N[i]
    C = C.tocsr()[:, free]
    T = T.tocsr()[:, free]
    Kff = K[free][:, free]
    ff = f[free]
    far = rs > 48  # never in contact; keeps the active set small
    on_axis = rs < 1e-9  # its tangential row is empty (both u_r fixed)
    active = rs < 40
    stick = active & ~on_axis & (mu > 0)
    s = np.zeros(len(slave))
    for _ in range(200):
        ia = np.where(active)[0]
        ist = np.where(stick & active)[0]
        isl = np.where(active & ~stick & ~on_axis)[0] if mu > 0 else np.array([], int)
        G = sp.lil_matrix((len(free), len(ia)))
        col = {k: c for c, k in enumerate(ia)}
        for k in isl:  # slip: friction μ s λ along T on both bodies
            G[:, col[k]] = T[k].T * (mu * s[k])
        upper = -C[ia].T + G.tocsr()
        if len(ist):
            A = sp.bmat([[Kff, upper, -T[ist].T], [C[ia], None, None], [T[ist], None, None]], format='csc')
        else:
            A = sp.bmat([[Kff, upper], [C[ia], None]], format='csc')
        x = spl.spsolve(A, np.concatenate([ff, -gaps[ia], np.zeros(len(ist))]))
        u = x[:len(free)]
        lam = np.zeros(len(slave))
        lam[ia] = x[len(free):len(free) + len(ia)]
        tau = np.zeros(len(slave))
        tau[ist] = x[len(free) + len(ia):]
        gn = C @ u + gaps
        gt = T @ u
        new = active.copy()
        new[active & (lam < 0)] = False
        new[~active & ~far & (gn < -1e-10)] = True
        nst, ns = stick.copy(), s.copy()
        if mu > 0:
            for k in ist:
                if abs(tau[k]) > mu * max(lam[k], 0.0) * (1 + 1e-9):
                    nst[k], ns[k] = False, -np.sign(tau[k])
            for k in isl:
                # the friction force on the punch, −μ s λ, must oppose its slip g_t
                if gt[k] * s[k] < 0:
                    nst[k] = True
            nst[new & ~active] = True
            nst[on_axis] = False
        if (new == active).all() and (nst[new] == stick[new]).all():
            break
        active, stick, s = new, nst, ns
    U = np.zeros(nF + nP)
    U[free] = u
    _, M = edge_integrals(npn, slave)
    pr = np.linalg.solve(M, lam)
    print(f"h = {h}, μ = {mu}: F/applied = {lam.sum() / (p * np.pi * 2500):.5f}, "
          f"u_y(axis) = {U[2 * ftop[0] + 1]:.6f} mm, p(axis) = {pr[0]:.2f} MPa, "
          f"last contact node r = {rs[active].max():.3f} mm")
    return rs, pr, nf[ftop, 0], U[2 * ftop + 1], U[2 * ftop]


def disc(h, p=156.25, a=40.0):
    """The foundation alone, pressure p on r < a, bottom fixed, side free."""
    R = with_mid(np.concatenate([np.linspace(0, a, int(round(a / h)) + 1), graded(h, 0, 100 - a, 1.1)[1:] + a]))
    Z = -with_mid(graded(h, 0, 200, 1.1))[::-1]
    nf, ef, idf = grid_body(*np.meshgrid(R, Z))
    K = stiffness(nf, ef, 70000.0, 0.3)
    f = np.zeros(2 * len(nf))
    top = idf[-1, :]
    k = int(np.argmin(abs(nf[top, 0] - a)))
    load, _ = edge_integrals(nf, top[:k + 1])
    f[2 * top[:k + 1] + 1] -= p * load
    fixed = set(2 * idf[0, :]) | set(2 * idf[0, :] + 1) | set(2 * idf[:, 0])
    free = np.array(sorted(set(range(2 * len(nf))) - fixed))
    u = np.zeros(2 * len(nf))
    u[free] = spl.spsolve(K[free][:, free].tocsc(), f[free])
    r, uy = nf[top, 0], u[2 * top + 1]
    print(f"disc, h = {h}: u_y at r = 0, 10, 20, 30, 35 mm: "
          + ", ".join(f"{np.interp(x, r, uy):.6f}" for x in [0, 10, 20, 30, 35]))
    return r, uy


if __name__ == '__main__':
    if len(sys.argv) > 1 and sys.argv[1] == 'disc':
        disc(float(sys.argv[2]) if len(sys.argv) > 2 else 1.0)
        sys.exit()
    solve(float(sys.argv[1]) if len(sys.argv) > 1 else 1.0,
          float(sys.argv[2]) if len(sys.argv) > 2 else 0.0)
