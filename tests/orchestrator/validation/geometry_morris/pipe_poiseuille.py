#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""3D Hagen-Poiseuille flow in a circular pipe made from a mesh file, with Morris walls from the
geometry (ctest -L validation: geometry_morris_pipe_*).

The pipe (radius R = 0.5, axis z) is the fluid body `{type: mesh, file: pipe.stl}` (or pipe.msh,
examples/data/meshes/make_meshes.py); the box is periodic along z (10 spacings long) and the flow
is driven by the body force g along z (fluid.gravity), sdpd, no thermal noise, h = 3 dx,
rho = 1, eta = nu = 0.1, g = 1.6 (u(0) = g R^2 / (4 nu) = 1, Re = u(0) R / nu = 5), c0 = 10.
From rest the slowest mode decays as exp(-5.78 nu t / R^2): at t = 4 it is below 1e-4 u(0).
The final frame is compared with u(r) = g (R^2 - r^2) / (4 nu):

  L2 = sqrt(sum_i V_i (u_i - u(r_i))^2 / sum_i V_i) / u(0)   over the fluid particles
  flux = sum_i V_i u_i / L_z   against   pi g R^4 / (8 nu)

and the test fails unless L2 <= --l2-tol and |flux / exact - 1| <= --flux-tol.

    /usr/bin/python3 pipe_poiseuille.py --sadr build/ci/bin/sadr --mesh stl --across 16
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

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
MESHES = os.path.join(ROOT, "examples", "data", "meshes")
R, RHO, ETA, G, C0 = 0.5, 1.0, 0.1, 1.6, 10.0
NU = ETA / RHO
EXTRA = []

SCENE = """name: pipe_poiseuille_{mesh}_{across}_{wall}
dimension: 3
box:
  lower: [{lo}, {lo}, 0.0]
  upper: [{hi}, {hi}, {lz}]
  periodic: [false, false, true]
geometry:
  spacing: {dx}
  bodies:
    - name: pipe
      role: fluid
      shape: {shape}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  reference_density: {rho}
  sound_speed: {c0}
  shear_viscosity: {eta}
  gravity: [0.0, 0.0, {g}]
  wall_model: {wall}
time:
  coupling_step: {tau}
  end: {end}
output:
  times: [{t_check}]
  include_initial: false
  formats: [csv]
"""


def final_frame(run_dir):
    frames = sorted(f for f in os.listdir(run_dir) if f.endswith(".csv") and f.startswith("frame"))
    if not frames:
        frames = sorted(os.path.join(dp, f) for dp, _, fs in os.walk(run_dir) for f in fs
                        if f.endswith(".csv"))
        return frames
    return [os.path.join(run_dir, f) for f in frames]


def measure(path, lz):
    with open(path) as f:
        header = f.readline().strip().split(",")
    a = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    col = {k: i for i, k in enumerate(header)}
    fluid = a[:, col["kind"]] == 0
    x, y = a[fluid, col["x"]], a[fluid, col["y"]]
    u = a[fluid, col["vz"]]
    v = a[fluid, col["mass"]] / a[fluid, col["density"]]
    r = np.hypot(x, y)
    exact = G * (R * R - r * r) / (4 * NU)
    u0 = G * R * R / (4 * NU)
    l2 = math.sqrt(np.sum(v * (u - exact) ** 2) / np.sum(v)) / u0
    flux = np.sum(v * u) / lz
    flux_exact = math.pi * G * R ** 4 / (8 * NU)
    radial = math.sqrt(np.sum(v * (a[fluid, col["vx"]] ** 2 + a[fluid, col["vy"]] ** 2)) /
                       np.sum(v)) / u0
    # least squares u = a + b r^2: b / (-g / (4 nu)) is the viscosity ratio nu / nu_effective,
    # u(R) = a + b R^2 the slip at the surface (both 1 and 0 for the exact profile)
    fit = np.linalg.lstsq(np.stack([np.ones_like(r), r * r], axis=1) * np.sqrt(v)[:, None],
                          u * np.sqrt(v), rcond=None)[0]
    curvature_ratio = fit[1] / (-G / (4 * NU))
    slip = (fit[0] + fit[1] * R * R) / u0
    return {"curvature_ratio": float(curvature_ratio), "slip": float(slip),
            "time": float(a[0, col["time"]]), "fluid_particles": int(fluid.sum()),
            "particles": int(a.shape[0]), "l2": l2, "flux": flux, "flux_exact": flux_exact,
            "flux_error": flux / flux_exact - 1, "radial_rms": radial,
            "max_density_deviation": float(np.max(np.abs(a[fluid, col["density"]] / RHO - 1)))}


def run(sadr, mesh, across, wall, end, workdir):
    dx = 2 * R / across
    h = 3 * dx
    half = R + h + 2 * dx
    half = dx * math.ceil(half / dx)  # whole cells: the lattice symmetric about the axis
    mesh_file = os.path.join(MESHES, "pipe." + mesh)
    shape = "{type: mesh, file: %s}" % mesh_file
    lz = 10 * dx  # a periodic axis must be at least 3 kernel supports (9 dx) long
    scene = SCENE.format(mesh=mesh, across=across, wall=wall, lo=-half, hi=half, lz=lz, dx=dx,
                         shape=shape, rho=RHO, c0=C0, eta=ETA, g=G, tau=0.05, end=end,
                         t_check=end)
    path = os.path.join(workdir, "pipe_%s_%d_%s.yaml" % (mesh, across, wall))
    with open(path, "w") as f:
        f.write(scene)
    out = os.path.join(workdir, "run_%s_%d_%s" % (mesh, across, wall))
    cmd = [sadr, "run", path, "-o", out] + EXTRA
    print(" ".join(cmd), flush=True)
    t0 = time.time()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall_time = time.time() - t0
    frames = final_frame(out)
    m = measure(frames[-1], lz)
    m.update({"mesh": mesh, "across": across, "dx": dx, "wall_model": wall, "end": end,
              "wall_seconds": round(wall_time, 1)})
    return m


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sadr", required=True)
    ap.add_argument("--mesh", default="stl", choices=["stl", "msh", "both"])
    ap.add_argument("--across", type=int, nargs="+", default=[16])
    ap.add_argument("--wall-model", nargs="+", default=["morris"])
    ap.add_argument("--end", type=float, default=4.0)
    ap.add_argument("--l2-tol", type=float, default=0.02)
    ap.add_argument("--flux-tol", type=float, default=0.02)
    ap.add_argument("--json", default="")
    ap.add_argument("--set", action="append", default=[],
                    help="an override passed to sadr run (PATH=VALUE), e.g. fluid.h_over_dx=2.5")
    args = ap.parse_args()
    global EXTRA
    EXTRA = [x for o in args.set for x in ("--set", o)]
    meshes = ["stl", "msh"] if args.mesh == "both" else [args.mesh]
    results = []
    with tempfile.TemporaryDirectory(prefix="sadr_pipe_") as work:
        for wall in args.wall_model:
            for n in args.across:
                for mesh in meshes:
                    m = run(args.sadr, mesh, n, wall, args.end, work)
                    results.append(m)
                    print("pipe mesh=%s across=%d wall=%s particles=%d fluid=%d L2=%.4f "
                          "flux_error=%+.4f fit: curvature/exact=%.4f slip u(R)/u0=%+.4f "
                          "radial_rms=%.2e max|rho-1|=%.2e wall=%.1fs" % (
                              mesh, n, wall, m["particles"], m["fluid_particles"], m["l2"],
                              m["flux_error"], m["curvature_ratio"], m["slip"], m["radial_rms"],
                              m["max_density_deviation"], m["wall_seconds"]), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    ok = True
    for m in results:
        if m["wall_model"] not in ("morris", "adami"):
            continue
        if not (m["l2"] <= args.l2_tol and abs(m["flux_error"]) <= args.flux_tol):
            print("FAIL: %s across %d: L2 %.4f (tol %g), flux error %+.4f (tol %g)" % (
                m["mesh"], m["across"], m["l2"], args.l2_tol, m["flux_error"], args.flux_tol))
            ok = False
    if len(meshes) == 2:
        for n in args.across:
            pair = [m for m in results if m["across"] == n and m["wall_model"] == "morris"]
            if len(pair) == 2:
                print("stl vs msh at %d across: L2 %.5f vs %.5f, flux error %+.5f vs %+.5f" % (
                    n, pair[0]["l2"], pair[1]["l2"], pair[0]["flux_error"], pair[1]["flux_error"]))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
