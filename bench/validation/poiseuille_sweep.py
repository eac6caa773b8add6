#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Poiseuille start-up: error against resolution and sound speed, with cost (issue #20).

The channel of examples/poiseuille_tracer_2d.yaml without its tracer: SDPD at
k_B T = 0 (no noise: one realization per point), nu = 0.1, H = 1 between
stationary wall particles (4 rows), periodic in x, driven from rest by
g = 0.08 (u_max = g H^2 / (8 nu) = 0.1 with the no-slip planes at y = 0 and 1).
One `sadr sweep` runs the grid: spacing dx (zipped with the box, so the walls
keep 4 rows) x sound speed c0. Reference: the start-up series (Morris, Fox &
Zhu 1997, eq. 21) with walls at y = 0, 1; error = RMS over the fluid particles
of u_x - u(y, t), divided by the reference centre-line speed, at t_end. Two
errors add up: the wall treatment's (the no-slip planes of stationary wall
particles are not at 0 and 1; first order in dx) and weak compressibility's
(grows as c0 falls towards u_max: density variation ~ (u_max / c0)^2).

Cost: CPU time (user + sys) of every run's worker and services, from the
run's result.json (`cpu_s`), measured under whatever load the machine had;
wall times (run.json's coupling loop) are printed too and must be re-measured
in a quiet window before they are quoted.

    bench/validation/poiseuille_sweep.py [--bin build/release/bin] [--end 2]
        [--dx 0.1 0.05 0.025] [--c0 0.1 0.25 1 4 16 64] [--workers 1]
        [--plot docs/validation/poiseuille_c0_work_precision.png] [--json out.json]
"""
import argparse
import csv
import json
import math
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, run_measured  # noqa: E402

NU, G, H = 0.1, 0.08, 1.0

SCENE = """name: poiseuille_startup
dimension: 2
box: {lower: [0.0, -0.175], upper: [1.0, 1.175], periodic: [true, false]}
regions:
  - {name: lower_wall, shape: channel, axis: y, lower: -1.0, upper: 0.0}
  - {name: upper_wall, shape: channel, axis: y, lower: 1.0, upper: 2.0}
particles:
  spacing: 0.05
  density: 1.0
  fill:
    - {region: lower_wall, kind: wall}
    - {region: upper_wall, kind: wall}
    - {kind: fluid}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  reference_density: 1.0
  sound_speed: 1.0
  shear_viscosity: 0.1
  temperature: 0.0
  gravity: [0.08, 0.0]
species: []
time: {coupling_step: 0.1, end: 2.0}
output: {times: [2.0], formats: [csv]}
seed: 1997
"""


def startup(y, t, terms=200):
    """u_x(y, t) of plane Poiseuille flow started from rest, walls at 0 and H."""
    u = G / (2 * NU) * y * (H - y)
    for n in range(terms):
        k = (2 * n + 1) * math.pi / H
        u -= (4 * G * H**2 / (NU * math.pi**3 * (2 * n + 1) ** 3) * math.sin(k * y)
              * math.exp(-NU * k * k * t))
    return u


def sweep_file(dxs, c0s, end):
    """The sweep: dx zipped with the box (4 wall rows of spacing dx), x c0 (the grid)."""
    lower = [f"[0.0, {-3.5 * dx!r}]" for dx in dxs]
    upper = [f"[1.0, {1 + 3.5 * dx!r}]" for dx in dxs]
    return ("scene: scene.yaml\nrealizations: 1\nkeep: all\nseed: 1997\n"
            "parameters:\n  grid:\n"
            f"    fluid.sound_speed: [{', '.join(repr(c) for c in c0s)}]\n"
            "  zip:\n"
            f"    particles.spacing: [{', '.join(repr(d) for d in dxs)}]\n"
            f"    box.lower: [{', '.join(lower)}]\n"
            f"    box.upper: [{', '.join(upper)}]\n"
            f"    time.end: [{', '.join(repr(end) for _ in dxs)}]\n"
            f"    output.times: [{', '.join(f'[{end!r}]' for _ in dxs)}]\n")


def error_of(frame_csv, t):
    rows = [r for r in csv.DictReader(open(frame_csv)) if r["kind"] == "0"]
    ref_centre = startup(0.5 * H, t)
    sq = [(float(r["vx"]) - startup(float(r["y"]), t)) ** 2 for r in rows]
    rho = [float(r["density"]) for r in rows]
    return math.sqrt(sum(sq) / len(sq)) / ref_centre, len(rows), max(abs(x - 1) for x in rho)


QUICK_DX, FULL_DX = (0.1, 0.05, 0.025), (0.1, 0.05, 0.025, 0.0125)
C0S = (0.1, 0.25, 1.0, 4.0, 16.0, 64.0)


def run(bin_dir, dxs=QUICK_DX, c0s=C0S, end=2.0,
        workers=1):
    sadr = pathlib.Path(bin_dir) / "sadr"
    with tempfile.TemporaryDirectory(prefix="sadr-pois-sweep-") as d:
        d = pathlib.Path(d)
        (d / "scene.yaml").write_text(SCENE)
        (d / "sweep.yaml").write_text(sweep_file(dxs, c0s, end))
        cmd = [sadr, "sweep", d / "sweep.yaml", "-o", d / "out", "-q", "--workers", str(workers)]
        r = run_measured(cmd, log=d / "sweep.log")
        if r["rc"] not in (0, 3):  # 3: some runs failed (each is a row with its reason)
            sys.exit(f"poiseuille_sweep: sadr sweep exited {r['rc']}:\n"
                     + (d / "sweep.log").read_text())
        m = json.loads((d / "out" / "sweep.json").read_text())
        rows = []
        for run_ in m["runs"]:
            p = m["points"][run_["point"]]["values"]
            rd = d / "out" / run_["dir"]
            res = json.loads((rd / "result.json").read_text())
            if run_["state"] != "ok":
                rows.append({"dx": float(p["particles.spacing"]),
                             "c0": float(p["fluid.sound_speed"]), "failed": run_["reason"],
                             "exit_code": run_["exit_code"], "cpu_s": res.get("cpu_s", -1)})
                continue
            manifest = json.loads((rd / "run.json").read_text())
            last = sorted((rd / "frames").glob("frame_*.csv"))[-1]
            err, fluid, drho = error_of(last, end)
            rows.append({"dx": float(p["particles.spacing"]), "c0": float(p["fluid.sound_speed"]),
                         "fluid_particles": fluid, "error": err, "max_density_dev": drho,
                         "cpu_s": res["cpu_s"],
                         "wall_loop_s": manifest["timings_s"].get("coupling_loop", float("nan")),
                         "substeps": manifest.get("fluid_substeps")})
    return {"rows": rows, "end": end, "g": G, "nu": NU, "sweep_cpu_s": r["cpu_s"],
            "command": "bench/validation/poiseuille_sweep.py --end " + repr(end)
                       + " --dx " + " ".join(map(repr, dxs)) + " --c0 " + " ".join(map(repr, c0s)),
            "sweep_file": sweep_file(dxs, c0s, end)}


def dt_check(bin_dir, dx=0.025, c0=4.0, end=2.0, max_dt=2.5e-4):
    """The same point with the sub-step capped at max_dt (about a tenth of the
    viscous limit): separates the time-step error from the rest."""
    sadr = pathlib.Path(bin_dir) / "sadr"
    out = {}
    with tempfile.TemporaryDirectory(prefix="sadr-pois-dt-") as d:
        d = pathlib.Path(d)
        (d / "scene.yaml").write_text(SCENE)
        for cap in (0.0, max_dt):
            o = d / f"cap{cap!r}"
            r = run_measured([sadr, "run", d / "scene.yaml", "-q", "-o", o,
                              "--set", f"fluid.sound_speed={c0!r}",
                              "--set", f"particles.spacing={dx!r}",
                              "--set", f"box.lower=[0.0, {-3.5 * dx!r}]",
                              "--set", f"box.upper=[1.0, {1 + 3.5 * dx!r}]",
                              "--set", f"time.end={end!r}", "--set", f"output.times=[{end!r}]",
                              "--set", f"fluid.max_time_step={cap!r}"])
            if r["rc"]:
                sys.exit(f"poiseuille_sweep: dt check exited {r['rc']}")
            err, _, _ = error_of(sorted((o / "frames").glob("frame_*.csv"))[-1], end)
            out["limit" if cap == 0 else "capped"] = {"max_time_step": cap, "error": err,
                                                      "cpu_s": r["cpu_s"]}
    return {"dx": dx, "c0": c0, **out}


def plot(data, path):
    from wp_plots import finish, mark_front, pareto, plt

    rows = [r for r in data["rows"] if "failed" not in r]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, c0 in enumerate(sorted({r["c0"] for r in rows})):
        pts = sorted(((r["cpu_s"], r["error"], r["dx"]) for r in rows if r["c0"] == c0),
                     key=lambda p: -p[2])  # along the line: finer resolution
        a.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color=f"C{k}",
                 label=f"c0 = {c0:g} ({c0 / 0.1:g} u_max)")
        b.loglog([p[2] for p in pts], [p[1] for p in pts], "o-", color=f"C{k}",
                 label=f"c0 = {c0:g}")
    mark_front(a, pareto([(r["cpu_s"], r["error"]) for r in rows]), "Pareto front")
    a.set_xlabel("CPU time [s] (worker + services; loaded machine)")
    a.set_ylabel("RMS(u_x - u_ref) / u_ref(H/2)")
    a.set_title(f"Poiseuille start-up, t = {data['end']:g}: work-precision")
    b.set_xlabel("dx (H = 1)")
    b.set_ylabel("RMS(u_x - u_ref) / u_ref(H/2)")
    b.set_title("error against resolution, per sound speed")
    finish(fig, (a, b), path)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--end", type=float, default=2.0)
    ap.add_argument("--dx", type=float, nargs="+", default=list(QUICK_DX))
    ap.add_argument("--c0", type=float, nargs="+", default=list(C0S))
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--plot", default=None)
    ap.add_argument("--json", default=None)
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless every run finished and the observed order in dx is "
                         "0.8..1.2 at every c0 (ctest validation_poiseuille_sweep)")
    a = ap.parse_args()
    d = run(a.bin, a.dx, a.c0, a.end, a.workers)
    print("dx,c0,fluid_particles,error,max_density_dev,cpu_s,wall_loop_s")
    for r in d["rows"]:
        if "failed" in r:
            print(f"{r['dx']:g},{r['c0']:g},failed (exit {r['exit_code']}): {r['failed'][:200]}")
            continue
        print(f"{r['dx']:g},{r['c0']:g},{r['fluid_particles']},{r['error']:.3e},"
              f"{r['max_density_dev']:.2e},{r['cpu_s']:.2f},{r['wall_loop_s']:.2f}")
    if a.plot:
        plot(d, a.plot)
    if a.json:
        pathlib.Path(a.json).write_text(json.dumps(d, indent=1) + "\n")
    if a.check:
        from wp_sweeps import order

        bad = [r for r in d["rows"] if "failed" in r]
        orders = {}
        for c0 in sorted({r["c0"] for r in d["rows"]}):
            rs = sorted((r for r in d["rows"] if r["c0"] == c0 and "failed" not in r),
                        key=lambda r: r["dx"])
            orders[c0] = order([r["dx"] for r in rs], [r["error"] for r in rs])
        ok = not bad and all(0.8 <= o <= 1.2 for o in orders.values())
        print("check: observed order in dx per c0: "
              + ", ".join(f"{c}: {o:.2f}" for c, o in orders.items())
              + f"; failed runs: {len(bad)}: {'ok' if ok else 'FAILED'}")
        return 0 if ok else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
