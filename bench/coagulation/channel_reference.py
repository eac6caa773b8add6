#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Eulerian reference of the coagulation channel (examples/coagulation_cascade_prescribed.yaml).

The continuum problem the prescribed scene discretises with particles, solved by finite volumes
on a Cartesian grid and classical RK4 in time (method of lines; an implicit solver's sparse LU
of the 23-species blocks cost ~6 s per factorisation here): the 23 transported species of li2015
Table III (tests/data/refs/coagulation/cascade_reference.py, the one home of the model) in the
x-y section of the channel, Poiseuille flow u(y) = 4 u_max y (20 - y) / 400 between the no-slip
planes y = 0 and y = 20, D_i = 138.6 / Sc_i, no flux through the fluid's edges y = -0.5 and
20.5 (the volumes of the first and last particle rows end there), every species held at C_i0
in the inlet buffer x < 2.9, and the Table IV injury terms times L / delta (L = 100, delta = 1)
in the layer -0.5 < y < -0.5 + delta, 10 < x < 20 (delta = 1: the scene's `injury` row; the
probe averages over the same layer). Advection: upwind-biased
third-order faces (kappa = 1/3), outflow at x = LX (default 40: downstream of the probe, which
it cannot reach against the flow over the run but by diffusion, sqrt(2 D t) < 3 at t = 600).

  /usr/bin/python3 bench/coagulation/channel_reference.py --h 0.5 --dt 0.05 --end 600 --out ref.csv

RK4 is stable for |lambda dt| < 2.78; the fastest reaction rates are ~4 per time unit (thrombin
and Xa inhibition by antithrombin), diffusion D / h^2 <= 0.04 at h = 0.5, advection CFL
u_max dt / h = 0.014: dt = 0.05 is well inside; halving dt checks the time error.

Writes the probe series (the mean over the cells of 14 < x < 16, -0.5 < y < 0.5, the
injury centre of bench/coagulation/plot_cascade.py) of every species at every --every, and
prints the features plot_cascade.py prints.
"""
import argparse
import importlib.util
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location(
    "cascade_reference", REPO / "tests/data/refs/coagulation/cascade_reference.py")
ref = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ref)

U_MAX = 0.1386
INLET = 2.9
PROBE = (14.0, 16.0)
INJURY = (10.0, 20.0)


def build(h, lx, delta):
    nx, ny = int(round(lx / h)), int(round(21.0 / h))
    xc = (np.arange(nx) + 0.5) * h
    yc = -0.5 + (np.arange(ny) + 0.5) * h
    u = np.clip(4.0 * U_MAX * yc * (20.0 - yc) / 400.0, 0.0, None)
    d = np.array([dd for _, dd, _ in ref.diffusivities()])
    c0 = np.array([c for _, _, c, _ in ref.SPECIES])
    held = xc < INLET
    inj = np.zeros((nx, ny), bool)
    inj[np.ix_((xc > INJURY[0]) & (xc < INJURY[1]), (yc > -0.5) & (yc < -0.5 + delta))] = True
    probe = np.zeros((nx, ny), bool)
    probe[np.ix_((xc > PROBE[0]) & (xc < PROBE[1]), (yc > -0.5) & (yc < -0.5 + delta))] = True
    return nx, ny, xc, yc, u, d, c0, held, inj, probe


def make_rhs(h, delta, nx, ny, u, d, c0, held, inj):
    p = ref.rate_parameters()
    f = ref.L_INJURY / delta
    ns = len(c0)
    inflow = c0[:, None] * np.ones(ny)[None, :]

    def rhs(t, yv):
        c = yv.reshape(ns, nx, ny)
        dc = ref.table3_rates(p, c)
        ci = c[:, inj]
        di = np.zeros_like(ci)
        ref.add_injury_rates(p, t, ci, di, f)
        dc[:, inj] += di
        # advection along x: faces i - 1/2 for i = 0..nx (kappa = 1/3 upwind-biased, u >= 0)
        ext = np.concatenate([inflow[:, None], inflow[:, None], c, c[:, -1:]], axis=1)
        # ext index k = cell k - 2; face i - 1/2 between cells i - 1 (k = i + 1) and i (k = i + 2)
        cm, cc, cp = ext[:, 0:nx + 1], ext[:, 1:nx + 2], ext[:, 2:nx + 3]
        face = cc + (cp - cc) / 3.0 + (cc - cm) / 6.0
        face[:, -1] = c[:, -1]  # outflow: first-order upwind at the last face
        flux = face * u[None, None, :]
        dc -= (flux[:, 1:] - flux[:, :-1]) / h
        # diffusion: no flux at y = -0.5, 20.5; zero gradient at x = LX; held cells at x = 0
        lap = np.zeros_like(c)
        lap[:, 1:-1] += c[:, 2:] - 2 * c[:, 1:-1] + c[:, :-2]
        lap[:, 0] += c[:, 1] - c[:, 0] + (inflow - c[:, 0])
        lap[:, -1] += c[:, -2] - c[:, -1]
        lap[:, :, 1:-1] += c[:, :, 2:] - 2 * c[:, :, 1:-1] + c[:, :, :-2]
        lap[:, :, 0] += c[:, :, 1] - c[:, :, 0]
        lap[:, :, -1] += c[:, :, -2] - c[:, :, -1]
        dc += d[:, None, None] * lap / h**2
        dc[:, held, :] = 0.0
        return dc.ravel()

    return rhs


def rk4(rhs, y, times, dt):
    """Classical RK4 with fixed steps landing on every output time; returns (species..., time)."""
    out = [y.copy()]
    t = times[0]
    for t_next in times[1:]:
        n = max(1, int(round((t_next - t) / dt)))
        h = (t_next - t) / n
        for _ in range(n):
            k1 = rhs(t, y)
            k2 = rhs(t + h / 2, y + h / 2 * k1)
            k3 = rhs(t + h / 2, y + h / 2 * k2)
            k4 = rhs(t + h, y + h * k3)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += h
        t = t_next
        if not np.all(np.isfinite(y)):
            raise SystemExit(f"RK4: non-finite state at t = {t:g} (dt = {dt:g})")
        out.append(y.copy())
    return np.array(out).T


def features(t, iia, ia, at, apc):
    k = int(np.argmax(iia))
    return (f"thrombin: max {iia[k]:.4g} at t = {t[k]:g}, {iia[-1]:.4g} at t = {t[-1]:g}; "
            f"fibrin {ia[0]:.4g} -> {ia[-1]:.4g} (last 20 %: "
            f"{(ia[-1] - ia[int(0.8 * (len(t) - 1))]) / ia[-1]:+.1%}); antithrombin min "
            f"{at.min():.5g}; APC max {apc.max():.4g}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--h", type=float, default=0.5, help="cell size (x and y)")
    ap.add_argument("--lx", type=float, default=40.0)
    ap.add_argument("--end", type=float, default=600.0)
    ap.add_argument("--every", type=float, default=10.0)
    ap.add_argument("--dt", type=float, default=0.05, help="RK4 step")
    ap.add_argument("--delta", type=float, default=1.0,
                    help="thickness of the layer that receives the injury flux (the scene's: 1)")
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    nx, ny, xc, yc, u, d, c0, held, inj, probe = build(args.h, args.lx, args.delta)
    ns = len(c0)
    y0 = np.broadcast_to(c0[:, None, None], (ns, nx, ny)).ravel().copy()
    times = np.arange(0.0, args.end + 1e-9, args.every)
    t0 = time.process_time()
    sol = rk4(make_rhs(args.h, args.delta, nx, ny, u, d, c0, held, inj), y0, times, args.dt)
    cpu = time.process_time() - t0
    c = sol.reshape(ns, nx, ny, -1)
    series = c[:, probe, :].mean(axis=1)  # (species, time)
    names = [s[0] for s in ref.SPECIES]
    col = {n: series[k] for k, n in enumerate(names)}
    print(f"h = {args.h:g}, dt = {args.dt:g}: {nx} x {ny} cells, {ns * nx * ny} unknowns, "
          f"{cpu:.0f} s CPU")
    print(features(times, col["IIa"], col["Ia"], col["ATIII"], col["APC"]))
    if args.out:
        with open(args.out, "w") as fo:
            fo.write(f"# bench/coagulation/channel_reference.py --h {args.h:g} --lx {args.lx:g} "
                     f"--end {args.end:g} --every {args.every:g} --dt {args.dt:g} --delta "
                     f"{args.delta:g}: the "
                     f"probe {PROBE[0]:g} < x < {PROBE[1]:g}, -0.5 < y < {args.delta - 0.5:g} "
                     "[nM]\n")
            fo.write("t," + ",".join(names) + "\n")
            for k, t in enumerate(times):
                fo.write(f"{t:g}," + ",".join(f"{series[s, k]:.8e}" for s in range(ns)) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
