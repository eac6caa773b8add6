#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Steady 2D Poiseuille advection-diffusion reference for tdpd_adr_validation_test.cpp.

    u(y) dC/dx = D (d2C/dx2 + d2C/dy2),  u = 4 U y (H - y) / H^2,  D = U H / Pe
    on x in [0, Lc], y in [0, H]:  C(0, y) = 0 (inflow buffer edge), dC/dx(Lc, y) = 0 (outlet,
    the seam cut), C(x, H) = 1 (upper wall), dC/dy(x, 0) = 0 (lower wall).

Cell-centred finite volumes: 5-point diffusion, second-order upwind advection (u >= 0; central
in the first column), boundary values through ghost cells, direct sparse solve (scipy SuperLU).
The grid is refined 4 times by 2 (bins stay aligned with cells); the bin averages on the finest
grid are written, and the observed order and an order-1 error estimate of the bin averages are
printed (docs/tdpd.md). Uses numpy/scipy only (Debian /usr/bin/python3).

    /usr/bin/python3 poiseuille_adr_ref.py [--out data/poiseuille_adr_ref.csv] [--U 6.66]
"""
import argparse
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

SPACING = 4.0 ** (-1.0 / 3.0)
H = 16 * SPACING
LX = 80 * SPACING
RC = 1.58
LC = LX - RC  # channel length after the inflow buffer
BX, BY = 43, 16  # bins (x, y); the test compares the first 40 in x


def solve(pe, u_max, m):
    """Bin averages (BX x BY) of the FV solution with m x m cells per bin."""
    nx, ny = BX * m, BY * m
    dx, dy = LC / nx, H / ny
    d = u_max * H / pe
    y = (np.arange(ny) + 0.5) * dy
    u = 4.0 * u_max * y * (H - y) / H**2
    idx = np.arange(nx * ny).reshape(nx, ny)
    rows, cols, vals = [], [], []
    rhs = np.zeros(nx * ny)

    def add(r, c, v):
        rows.append(r)
        cols.append(c)
        vals.append(v)

    ax, ay = d / dx**2, d / dy**2
    for i in range(nx):
        for j in range(ny):
            r = idx[i, j]
            diag = 0.0
            # x diffusion: inlet Dirichlet 0 (ghost -C), outlet Neumann (ghost = C)
            if i > 0:
                add(r, idx[i - 1, j], ax)
                diag -= ax
            else:
                diag -= 2.0 * ax
            if i < nx - 1:
                add(r, idx[i + 1, j], ax)
                diag -= ax
            # y diffusion: bottom Neumann, top Dirichlet 1 (ghost 2 - C)
            if j > 0:
                add(r, idx[i, j - 1], ay)
                diag -= ay
            if j < ny - 1:
                add(r, idx[i, j + 1], ay)
                diag -= ay
            else:
                diag -= 2.0 * ay
                rhs[r] -= 2.0 * ay
            # advection -u dC/dx on the left-hand side: D lap C - u C_x = 0
            uj = u[j]
            if i >= 2:
                diag -= uj * 3.0 / (2 * dx)
                add(r, idx[i - 1, j], uj * 4.0 / (2 * dx))
                add(r, idx[i - 2, j], -uj * 1.0 / (2 * dx))
            elif i == 1:  # C_{-1} ghost = -C_0
                diag -= uj * 3.0 / (2 * dx)
                add(r, idx[0, j], uj * (4.0 + 1.0) / (2 * dx))
            else:  # central with the ghost: (C_1 + C_0) / (2 dx)
                add(r, idx[1, j], -uj / (2 * dx))
                diag -= uj / (2 * dx)
            add(r, r, diag)
    a = sp.csc_matrix((vals, (rows, cols)), shape=(nx * ny, nx * ny))
    c = spla.spsolve(a, rhs).reshape(nx, ny)
    return c.reshape(BX, m, BY, m).mean(axis=(1, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--out", default="data/poiseuille_adr_ref.csv")
    ap.add_argument("--U", type=float, default=6.66)
    ap.add_argument("--levels", default="2,4,8,16")
    a = ap.parse_args()
    levels = [int(v) for v in a.levels.split(",")]
    lines = [
        "# Steady 2D Poiseuille advection-diffusion bin averages (tests/fluid_tdpd/poiseuille_adr_ref.py)",
        "# command: " + " ".join(sys.argv),
        f"# H = {H:.6f}, Lc = {LC:.6f} (x from the inflow buffer edge), U = {a.U}, D = U H / Pe;"
        f" bins {BX} x {BY}; finest grid {levels[-1]} x {levels[-1]} cells per bin",
        "# column pe: Peclet number U H / D",
        "# column ix: bin index along x (width Lc / 43)",
        "# column iy: bin index along y (width H / 16)",
        "# column c_ref: bin average of C (finest grid)",
        "# column err_est: |finest - previous| (error estimate for observed order >= 1)",
        "pe,ix,iy,c_ref,err_est",
    ]
    for pe in (10.0, 100.0, 1000.0):
        sols = [solve(pe, a.U, m) for m in levels]
        diffs = [np.abs(sols[k + 1] - sols[k])[:40].max() for k in range(len(sols) - 1)]
        orders = [np.log2(diffs[k] / diffs[k + 1]) for k in range(len(diffs) - 1)]
        # Observed order in the max norm is 1-1.5 (corner singularity at the inlet / upper
        # wall, bin (0, 15)); the estimate uses order 1: |finest - previous|.
        est = np.abs(sols[-1] - sols[-2])
        loc = np.unravel_index(np.argmax(np.abs(sols[-1] - sols[-2])[:40]), (40, BY))
        l2 = [np.sqrt(np.mean((sols[k + 1] - sols[k])[:40] ** 2)) for k in range(len(sols) - 1)]
        print(f"Pe {pe:g}: RMS bin change {['%.2e' % v for v in l2]}, max at bin {loc}")
        print(f"Pe {pe:g}: max bin change between levels {['%.2e' % v for v in diffs]},"
              f" observed order {['%.2f' % v for v in orders]}, max error estimate (order 1)"
              f" {est[:40].max():.2e}", flush=True)
        for ix in range(BX):
            for iy in range(BY):
                lines.append(f"{pe:g},{ix},{iy},{sols[-1][ix, iy]:.8f},{est[ix, iy]:.2e}")
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
