#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Steady diffusion of a stochastic species between two concentric spheres, Dirichlet walls with
and without Morris extrapolation from the geometry (ctest -L validation:
geometry_morris_spheres).

Fluid body: the sphere r < R2 = 1.0; solid: the sphere r < R1 = 0.4 (both made by `geometry`,
dx = 0.08, h = 3 dx, walls h deep). Species c (stochastic, kappa = 1, no reactions) is held at
`count: C1` molecules per wall particle on every wall particle of the inner sphere and at 0 on
the container's wall particles (`dirichlet`). The SSA's Morris walls follow fluid.wall_model,
which only sdpd offers (the static backend has the stationary model alone), so the fluid is sdpd
at rest (no body force, k_B T = 0). The steady mean is the harmonic profile

    c(r) = A + B / r,   c(R1) = C1 / dx^3,  c(R2) = 0

(with Morris walls the held values sit on the surfaces r = R1, R2; without, on the wall
particles). The slowest mode decays at kappa (pi / (R2 - R1))^2 = 27 per unit time: from t = 0.4
(amplitude < 2e-5 of C1) the frames every 0.05 to t_end are averaged (time average of one
realization, the frames 1.8 relaxation times apart). Per shell of width dx between R1 and R2:
mean concentration sum X_i / sum V_i against the volume-weighted mean of c(r_i); the error is

    E = sqrt(sum_s W_s (cbar_s - c_s)^2 / sum_s W_s) / c(R1),   W_s the shell's fluid volume

The test fails unless E(morris) <= --morris-tol (default 0.045: the measured 0.0335 x 1.3) and
E(morris) < 0.75 E(stationary) (measured 0.0335 against 0.0571). The sampling noise of E, from
the two halves of the frames, is printed (about 2e-4, far below both margins; the run is
reproducible from its seed).

    /usr/bin/python3 concentric_spheres.py --sadr build/ci/bin/sadr
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

R1, R2, DX, KAPPA, C1 = 0.4, 1.0, 0.08, 1.0, 20

SCENE = """name: concentric_spheres_{wall}
dimension: 3
box:
  lower: [-1.4, -1.4, -1.4]
  upper: [1.4, 1.4, 1.4]
geometry:
  spacing: {dx}
  bodies:
    - name: gap
      role: fluid
      shape: {{type: sphere, center: [0, 0, 0], radius: {r2}}}
      wall_layer: container
      layer_thickness: 1.0
    - name: core
      role: solid
      shape: {{type: sphere, center: [0, 0, 0], radius: {r1}}}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  sound_speed: 1.0
  shear_viscosity: 0.5
  wall_model: {wall}
species:
  - name: c
    diffusivity: {kappa}
    boundaries:
      - {{region: core, condition: dirichlet, count: {c1}}}
      - {{region: container, condition: dirichlet, count: 0}}
time:
  coupling_step: 0.01
  end: {end}
output:
  times: [{times}]
  include_initial: false
  formats: [csv]
seed: {seed}
"""


def analyse(frames):
    per_frame = []
    for path in frames:
        with open(path) as f:
            header = f.readline().strip().split(",")
        a = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        col = {k: i for i, k in enumerate(header)}
        fluid = a[:, col["kind"]] == 0
        r = np.sqrt(a[fluid, col["x"]] ** 2 + a[fluid, col["y"]] ** 2 + a[fluid, col["z"]] ** 2)
        vol = a[fluid, col["mass"]] / a[fluid, col["density"]]
        x = a[fluid, col["c"]]  # a stochastic species is written as copy numbers X_i
        per_frame.append((r, vol, x))
    c_in = C1 / DX ** 3
    b = c_in / (1 / R1 - 1 / R2)
    a0 = -b / R2
    edges = np.arange(R1, R2 + 1e-9, DX)

    def error(sel):
        num = den = 0.0
        shells = []
        for lo, hi in zip(edges[:-1], edges[1:]):
            xs = vs = refs = 0.0
            for k in sel:
                r, vol, x = per_frame[k]
                m = (r >= lo) & (r < hi)
                xs += x[m].sum()
                vs += vol[m].sum()
                refs += (vol[m] * (a0 + b / r[m])).sum()
            if vs == 0:
                continue
            cbar, cref = xs / vs, refs / vs
            w = vs / len(sel)
            num += w * (cbar - cref) ** 2
            den += w
            shells.append((0.5 * (lo + hi), cbar / c_in, cref / c_in))
        return math.sqrt(num / den) / c_in, shells
    e, shells = error(range(len(per_frame)))
    # sampling noise: the spread of E over halves of the frames
    half = len(per_frame) // 2
    e1, _ = error(range(half))
    e2, _ = error(range(half, len(per_frame)))
    return e, abs(e1 - e2) / 2, shells, len(per_frame[0][0])


def run(sadr, wall, end, seed, workdir):
    times = ", ".join("%.2f" % t for t in np.arange(0.4, end + 1e-9, 0.05))
    scene = SCENE.format(wall=wall, dx=DX, r1=R1, r2=R2, kappa=KAPPA, c1=C1, end=end,
                         times=times, seed=seed)
    path = os.path.join(workdir, "spheres_%s.yaml" % wall)
    with open(path, "w") as f:
        f.write(scene)
    out = os.path.join(workdir, "run_%s" % wall)
    cmd = [sadr, "run", path, "-o", out]
    print(" ".join(cmd), flush=True)
    t0 = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall_s = time.time() - t0
    frames = sorted(os.path.join(dp, f) for dp, _, fs in os.walk(out) for f in fs
                    if f.endswith(".csv") and "frame" in f)
    e, noise, shells, nfluid = analyse(frames)
    return {"wall_model": wall, "error": e, "noise": noise, "frames": len(frames),
            "fluid_particles": nfluid, "wall_seconds": round(wall_s, 1), "shells": shells}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sadr", required=True)
    ap.add_argument("--end", type=float, default=1.4)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--morris-tol", type=float, default=0.045)
    ap.add_argument("--json", default="")
    args = ap.parse_args()
    res = {}
    with tempfile.TemporaryDirectory(prefix="sadr_spheres_") as work:
        for wall in ["morris", "stationary"]:
            m = run(args.sadr, wall, args.end, args.seed, work)
            res[wall] = m
            print("spheres wall=%s fluid=%d frames=%d E=%.4f (noise ~%.4f) wall=%.1fs" % (
                wall, m["fluid_particles"], m["frames"], m["error"], m["noise"],
                m["wall_seconds"]), flush=True)
            for r, cbar, cref in m["shells"]:
                print("  r=%.3f c/c1=%.4f exact=%.4f" % (r, cbar, cref))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=1)
    em, es = res["morris"]["error"], res["stationary"]["error"]
    ok = em <= args.morris_tol and em < 0.75 * es
    if not ok:
        print("FAIL: E(morris) %.4f (tol %g), E(stationary) %.4f" % (em, args.morris_tol, es))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
