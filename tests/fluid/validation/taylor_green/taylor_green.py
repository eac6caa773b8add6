#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""2D Taylor-Green vortex, Re = 100, with the sdpd backend, with and without the transport
velocity (fluid.parameters transport_velocity; ctest -L validation: taylor_green_tvf).

Periodic box of side L = 1, U = 1, rho_0 = 1, eta = nu = U L / Re = 0.01, c_0 = 10 U, Lucy
kernel, h = 3 dx, no thermal noise, default density mode (continuity). The exact solution is

  u = -U cos(2 pi x) sin(2 pi y) e^{-8 pi^2 nu t},  v = U sin(2 pi x) cos(2 pi y) e^{-8 pi^2 nu t},
  p = -(rho U^2 / 4) (cos(4 pi x) + cos(4 pi y)) e^{-16 pi^2 nu t},

and the kinetic energy decays as E(0) e^{-16 pi^2 nu t}. The script writes a particle file
(cell-centred n x n lattice, velocities and the exact pressure's Tait density at t = 0,
mass rho dx^2) and runs `sadr run` to t_end = 2 / (16 pi^2 nu) (E down by e^-2), frames every
t_end / 20. Errors, over the fluid particles (V_i = m_i / rho_i):

  E curve: sqrt(sum_k (E_k - E_0 e^{-16 pi^2 nu t_k})^2 / sum_k (E_0 e^{-16 pi^2 nu t_k})^2)
           over the frames, E_0 the particles' own initial energy;
  field:   sqrt(sum_i V_i |v_i - v_exact(x_i, t_end)|^2 / sum_i V_i |v_exact(x_i, t_end)|^2).

It also prints the particle distribution at t_end: the smallest nearest-neighbour distance and
the standard deviation of the nearest-neighbour distances, in units of dx.

Fails unless every error is at most --tol-on (runs with the transport velocity) or --tol-off
(without) and, with --expect-tvf-better, the transport velocity's field error at the finest
resolution is below that without it.

    /usr/bin/python3 taylor_green.py --sadr build/ci/bin/sadr --n 30 50 80
"""
import argparse
import glob
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
from sadr.frames import read_frame  # noqa: E402

L, U, RHO, RE, C0 = 1.0, 1.0, 1.0, 100.0, 10.0
NU = U * L / RE
DECAY_E = 16 * math.pi ** 2 * NU / L ** 2  # kinetic energy decay rate
T_END = 2.0 / DECAY_E

SCENE = """name: taylor_green_{n}_{tag}
dimension: 2
box:
  lower: [0.0, 0.0]
  upper: [{L}, {L}]
  periodic: [true, true]
particles:
  file: particles.csv
fluid:
  backend: sdpd
  smoothing_length: {h}
  reference_density: {rho}
  sound_speed: {c0}
  shear_viscosity: {eta}
  parameters: {{transport_velocity: {tvf}}}
time:
  coupling_step: {tau}
  end: {end}
output:
  every: {every}
  formats: [csv]
"""


def exact_velocity(x, y, t):
    k = 2 * math.pi / L
    d = math.exp(-0.5 * DECAY_E * t)
    return (-U * np.cos(k * x) * np.sin(k * y) * d, U * np.sin(k * x) * np.cos(k * y) * d)


def write_particles(path, n):
    dx = L / n
    c = (np.arange(n) + 0.5) * dx
    x, y = np.meshgrid(c, c, indexing="ij")
    x, y = x.ravel(), y.ravel()
    u, v = exact_velocity(x, y, 0.0)
    p = -(RHO * U * U / 4) * (np.cos(4 * math.pi * x / L) + np.cos(4 * math.pi * y / L))
    b = RHO * C0 * C0 / 7.0  # Tait, gamma = 7 (tait_eos.hpp)
    rho = RHO * (1.0 + p / b) ** (1.0 / 7.0)
    mass = rho * dx * dx
    with open(path, "w") as f:
        f.write("x,y,z,mass,density,kind,vx,vy,vz\n")
        for i in range(len(x)):
            f.write("%r,%r,0,%r,%r,fluid,%r,%r,0\n" % (x[i], y[i], mass[i], rho[i], u[i], v[i]))
    return dx


def errors(frames):
    times, energies = [], []
    for fr in frames:
        m = fr.kinds == 0
        vel = fr.velocity[m]
        times.append(fr.time)
        energies.append(0.5 * float(np.sum(fr.mass[m] * np.sum(vel[:, :2] ** 2, axis=1))))
    times, energies = np.array(times), np.array(energies)
    exact = energies[0] * np.exp(-DECAY_E * times)
    e_err = math.sqrt(np.sum((energies - exact) ** 2) / np.sum(exact ** 2))
    last = frames[-1]
    m = last.kinds == 0
    vol = last.mass[m] / last.density[m]
    ue, ve = exact_velocity(last.positions[m, 0], last.positions[m, 1], last.time)
    du = last.velocity[m, 0] - ue
    dv = last.velocity[m, 1] - ve
    f_err = math.sqrt(np.sum(vol * (du ** 2 + dv ** 2)) / np.sum(vol * (ue ** 2 + ve ** 2)))
    # particle distribution: nearest-neighbour distances / dx (1 and 0 spread on the lattice)
    pos = np.mod(last.positions[m, :2], L)
    dist = cKDTree(pos, boxsize=L).query(pos, k=2)[0][:, 1] * math.sqrt(len(pos)) / L
    return {"energy_l2": e_err, "field_l2": f_err, "t_end": float(last.time),
            "energy_ratio_end": float(energies[-1] / exact[-1]),
            "nn_min": float(dist.min()), "nn_spread": float(np.std(dist))}


def run(sadr, n, tvf, work):
    d = os.path.join(work, "tg_%d_%s" % (n, tvf))
    os.makedirs(d)
    dx = write_particles(os.path.join(d, "particles.csv"), n)
    scene = SCENE.format(n=n, tag=tvf, L=L, h=3 * dx, rho=RHO, c0=C0, eta=RHO * NU, tvf=tvf,
                         tau=T_END / 40, end=T_END, every=T_END / 20)
    path = os.path.join(d, "scene.yaml")
    with open(path, "w") as f:
        f.write(scene)
    out = os.path.join(d, "out")
    cmd = [sadr, "run", path, "-o", out]
    print(" ".join(cmd), flush=True)
    t0 = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - t0
    files = sorted(glob.glob(os.path.join(out, "**", "frame_*.csv"), recursive=True))
    m = errors([read_frame(p) for p in files])
    m.update({"n": n, "transport_velocity": tvf, "particles": n * n, "frames": len(files),
              "wall_seconds": round(wall, 1)})
    return m


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sadr", required=True)
    ap.add_argument("--n", type=int, nargs="+", default=[30, 50, 80])
    ap.add_argument("--tvf", nargs="+", default=["off", "on"], choices=["off", "on"])
    ap.add_argument("--tol-off", type=float, default=1.0, help="largest error without TVF")
    ap.add_argument("--tol-on", type=float, default=1.0, help="largest error with TVF")
    ap.add_argument("--expect-tvf-better", action="store_true")
    ap.add_argument("--json", default="")
    args = ap.parse_args()
    results = []
    with tempfile.TemporaryDirectory(prefix="sadr_tg_") as work:
        for n in args.n:
            for tvf in args.tvf:
                m = run(args.sadr, n, tvf, work)
                results.append(m)
                print("taylor_green n=%d^2 tvf=%s E_L2=%.4f field_L2=%.4f E_end/exact=%.4f "
                      "nn_min/dx=%.3f nn_std/dx=%.3f wall=%.1fs" % (
                          n, tvf, m["energy_l2"], m["field_l2"], m["energy_ratio_end"],
                          m["nn_min"], m["nn_spread"], m["wall_seconds"]), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    ok = True
    for m in results:
        tol = args.tol_on if m["transport_velocity"] == "on" else args.tol_off
        if not (m["energy_l2"] <= tol and m["field_l2"] <= tol):
            print("FAIL: n=%d tvf=%s: E_L2 %.4f, field_L2 %.4f (tol %g)" % (
                m["n"], m["transport_velocity"], m["energy_l2"], m["field_l2"], tol))
            ok = False
    if args.expect_tvf_better:
        finest = max(args.n)
        f = {m["transport_velocity"]: m["field_l2"] for m in results if m["n"] == finest}
        if not f.get("on", 1e9) < f.get("off", -1):
            print("FAIL: at n=%d the transport velocity does not lower the field error: %s" % (
                finest, f))
            ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
