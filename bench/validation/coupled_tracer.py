#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Coupled stochastic case: a tracer in a flow, error against R and resolution (issue #20).

A periodic 1D SDPD fluid at rest and k_B T = 0 is accelerated uniformly by a
body force g: every particle moves by s(t) = g t^2 / 2, the lattice
translates rigidly, and the stochastic tracer A (n0 molecules per particle in
the stripe a <= x <= b at t = 0, diffusivity D, NSM on the particle graph
that the SSA rebuilds from the fluid's positions each coupling step) is carried
along. Exact answer: the periodic stripe solution of the heat equation,
shifted by s(t), with the diffusivity the particle graph converges to,
kappa_eff = ratio D (ratio 0.901 at h = 2 dx, eps_h = 0.01 in 1D:
tests/data/refs/sph_consistency.csv, docs/ssa-core.md); the error against D
itself (the documented regularisation bias) is reported too:
    c(x, t) / c0 = 1/2 sum_k [erf((x - s - a + k) / sqrt(4 D t)) - erf((x - s - b + k) / sqrt(4 D t))].
Error of the ensemble mean of the first r realizations at t_end:
    RMS_i (E_r[X_i] / n0 - c(x_i, t) / c0),
with its noise level sqrt(mean_i var_i / r) / n0 (the error expected from
noise alone): the error falls as 1 / sqrt(r) to the discretisation floor of
the particle graph, which falls with dx. One `sadr sweep` runs the grid
(spacing x R realizations); a second sweep varies the coupling step tau at
the finest spacing (the graph is rebuilt at every coupling step; here it is a
pure translation, so tau must not change the answer beyond noise).

Cost: CPU time (user + sys) of each run's worker and services (result.json
`cpu_s`) on a loaded machine; wall times must be re-measured in a quiet window.

    bench/validation/coupled_tracer.py [--bin build/release/bin] [--dx 1/16 1/32 1/64 1/128]
        [--realizations 64] [--plot docs/validation/coupled_tracer.png] [--json out.json]
"""
import argparse
import csv
import json
import math
import pathlib
import sys
import tempfile
from fractions import Fraction

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, run_measured  # noqa: E402

D, G, N0, A, B, T_END = 0.01, 0.2, 1000, 0.25, 0.5, 1.0
QUICK_DX, QUICK_R = ("1/16", "1/32", "1/64"), 32
FULL_DX, FULL_R = ("1/16", "1/32", "1/64", "1/128"), 256

SCENE = f"""name: tracer_in_flow
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [true]}}
regions:
  - {{name: stripe, shape: box, lower: [{A}], upper: [{B}]}}
particles: {{spacing: 0.0625, density: 1.0, fill: [{{kind: fluid}}]}}
fluid:
  backend: sdpd
  h_over_dx: 2.0
  reference_density: 1.0
  sound_speed: 1.0
  shear_viscosity: 0.1
  temperature: 0.0
  gravity: [{G}]
species:
  - {{name: A, stochastic: true, diffusivity: {D}, initial: [{{region: stripe, count: {N0}}}]}}
time: {{coupling_step: 0.05, end: {T_END}}}
output: {{times: [{T_END}], formats: [csv]}}
seed: 2020
"""


def kappa_ratio(h_over_dx=2.0, eps=0.01, dim=1):
    """kappa_eff / kappa of the particle graph's Laplacian on a regular lattice
    (tests/data/refs/sph_consistency.csv, docs/ssa-core.md): the operator's limit."""
    table = ROOT / "tests/data/refs/sph_consistency.csv"
    for row in csv.DictReader(line for line in open(table) if not line.startswith("#")):
        if (int(row["dim"]) == dim and float(row["eps"]) == eps
                and row["h_over_dx"] != "inf" and abs(float(row["h_over_dx"]) - h_over_dx) < 1e-9):
            return float(row["kappa_eff_over_kappa"])
    sys.exit(f"coupled_tracer: no h/dx = {h_over_dx}, eps = {eps} row in {table}")


def exact(x, t, d=D):
    """c(x, t) / c0 of the periodic stripe [A, B] on [0, 1), shifted by g t^2 / 2."""
    s, w = G * t * t / 2, math.sqrt(4 * d * t)
    return 0.5 * sum(math.erf((x - s - A + k) / w) - math.erf((x - s - B + k) / w)
                     for k in range(-3, 4))


def sweep(sadr, d, params, realizations):
    """One sadr sweep; returns (sweep.json, per-run [(point values, dir, cpu_s)], CPU s)."""
    d.mkdir(parents=True, exist_ok=True)
    (d / "scene.yaml").write_text(SCENE)
    text = f"scene: scene.yaml\nrealizations: {realizations}\nkeep: all\nseed: 2020\nparameters:\n"
    text += params
    (d / "sweep.yaml").write_text(text)
    r = run_measured([sadr, "sweep", d / "sweep.yaml", "-o", d / "out", "-q"], log=d / "log")
    if r["rc"]:
        sys.exit(f"coupled_tracer: sadr sweep exited {r['rc']}:\n" + (d / "log").read_text())
    return json.loads((d / "out" / "sweep.json").read_text()), r["cpu_s"], text


def point_errors(root, m, point, subsets):
    """Errors of the mean of the first r realizations of `point`, noise levels, CPU s per run."""
    runs = sorted((x for x in m["runs"] if x["point"] == point), key=lambda x: x["realization"])
    finals, cpu, xs = [], [], None
    for x in runs:
        rd = root / x["dir"]
        cpu.append(json.loads((rd / "result.json").read_text())["cpu_s"])
        last = sorted((rd / "frames").glob("frame_*.csv"))[-1]
        rows = sorted(csv.DictReader(open(last)), key=lambda row: int(row["id"]))
        finals.append([float(row["A"]) for row in rows])
        if xs is None:
            xs, t = [float(row["x"]) for row in rows], float(rows[0]["time"])
    n = len(xs)
    ref = [exact(x, t, D * kappa_ratio()) for x in xs]  # the operator's limit
    ref_d = [exact(x, t) for x in xs]  # the scene's kappa
    total = len(finals)
    grand = [sum(f[i] for f in finals) / total for i in range(n)]
    var = [sum((f[i] - grand[i]) ** 2 for f in finals) / max(1, total - 1) for i in range(n)]
    out = {}
    for r in sorted({s for s in subsets if s <= total} | {total}):
        mean = [sum(f[i] for f in finals[:r]) / r for i in range(n)]
        err = math.sqrt(sum((mean[i] / N0 - ref[i]) ** 2 for i in range(n)) / n)
        err_d = math.sqrt(sum((mean[i] / N0 - ref_d[i]) ** 2 for i in range(n)) / n)
        noise = math.sqrt(sum(v / r for v in var) / n) / N0
        out[r] = {"error": err, "error_vs_kappa": err_d, "noise": noise, "cpu_s": sum(cpu[:r])}
    return out, len(xs), t


def run(bin_dir, dxs=FULL_DX, realizations=64,
        taus=(0.2, 0.1, 0.05, 0.025)):
    sadr = pathlib.Path(bin_dir) / "sadr"
    subsets = (1, 2, 4, 8, 16, 32, 64, 128, 256)
    res = {"D": D, "g": G, "n0": N0, "stripe": [A, B], "T": T_END, "rows": [], "tau_rows": [],
           "kappa_ratio": kappa_ratio(), "h_over_dx": 2.0}
    with tempfile.TemporaryDirectory(prefix="sadr-tracer-") as tmp:
        tmp = pathlib.Path(tmp)
        spacing = [float(Fraction(x)) for x in dxs]
        m, cpu, text = sweep(sadr, tmp / "dx",
                             f"  grid:\n    particles.spacing: [{', '.join(map(repr, spacing))}]\n",
                             realizations)
        res["sweep_dx"] = text
        res["sweep_dx_cpu_s"] = cpu
        for p in m["points"]:
            errs, n, t = point_errors(tmp / "dx" / "out", m, p["index"], subsets)
            res["rows"].append({"dx": spacing[p["index"]], "particles": n, "t": t,
                                "by_r": {str(k): v for k, v in errs.items()}})
        finest = min(spacing)
        m, cpu, text = sweep(sadr, tmp / "tau",
                             f"  grid:\n    time.coupling_step: [{', '.join(map(repr, taus))}]\n"
                             f"  zip:\n    particles.spacing: [{finest!r}]\n", realizations // 4)
        res["sweep_tau"] = text
        for p in m["points"]:
            errs, n, t = point_errors(tmp / "tau" / "out", m, p["index"], subsets)
            r = max(errs)
            res["tau_rows"].append({"tau": taus[p["index"]], "dx": finest, "R": r, **errs[r]})
    res["command"] = (f"bench/validation/coupled_tracer.py --dx {' '.join(dxs)} "
                      f"--realizations {realizations}")
    return res


def plot(d, path):
    from wp_plots import finish, plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, row in enumerate(d["rows"]):
        rs = sorted(int(r) for r in row["by_r"])
        a.loglog([row["by_r"][str(r)]["cpu_s"] for r in rs],
                 [row["by_r"][str(r)]["error"] for r in rs], "o-", color=f"C{k}",
                 label=f"dx = 1/{round(1 / row['dx'])}: mean of r = 1..{rs[-1]}")
        a.loglog([row["by_r"][str(r)]["cpu_s"] for r in rs],
                 [row["by_r"][str(r)]["noise"] for r in rs], ":", color=f"C{k}")
    a.set_xlabel("CPU time [s] of the r realizations (loaded machine)")
    a.set_ylabel("RMS(E_r[X]/n0 - c/c0)")
    a.set_title("tracer in a flow: error against R (dotted: noise level)")
    big = [max(row["by_r"], key=int) for row in d["rows"]]
    b.loglog([row["dx"] for row in d["rows"]],
             [row["by_r"][r]["error"] for row, r in zip(d["rows"], big)], "o-",
             label="error, largest R")
    b.loglog([row["dx"] for row in d["rows"]],
             [row["by_r"][r]["noise"] for row, r in zip(d["rows"], big)], "s:",
             label="noise level, largest R")
    b.set_xlabel("dx")
    b.set_ylabel("RMS(E_R[X]/n0 - c/c0)")
    b.set_title("error against resolution")
    finish(fig, (a, b), path)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--dx", nargs="+", default=["1/16", "1/32", "1/64", "1/128"])
    ap.add_argument("--realizations", type=int, default=64)
    ap.add_argument("--plot", default=None)
    ap.add_argument("--json", default=None)
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless, at the finest dx and largest R, the error against "
                         "kappa_eff is within 2 noise levels and the error against D is not "
                         "(ctest validation_coupled_tracer)")
    a = ap.parse_args()
    d = run(a.bin, a.dx, a.realizations)
    print("dx,particles,r,error_vs_kappa_eff,error_vs_kappa,noise,cpu_s")
    for row in d["rows"]:
        for r, v in sorted(row["by_r"].items(), key=lambda kv: int(kv[0])):
            print(f"{row['dx']:g},{row['particles']},{r},{v['error']:.3e},"
                  f"{v['error_vs_kappa']:.3e},{v['noise']:.3e},{v['cpu_s']:.2f}")
    print("tau,dx,R,error,noise")
    for row in d["tau_rows"]:
        print(f"{row['tau']:g},{row['dx']:g},{row['R']},{row['error']:.3e},{row['noise']:.3e}")
    if a.plot:
        plot(d, a.plot)
    if a.json:
        pathlib.Path(a.json).write_text(json.dumps(d, indent=1) + "\n")
    if a.check:
        # error^2 / noise^2 is about chi^2_n / n over n particles (fewer independent ones, as
        # the profile is smooth): a ratio above 2 from noise alone needs chi^2_n / n > 4,
        # probability < 1e-6 for n >= 16 independent terms; the bound is the false-failure rate.
        row = d["rows"][-1]
        v = row["by_r"][max(row["by_r"], key=int)]
        ok = v["error"] <= 2 * v["noise"] < v["error_vs_kappa"]
        print(f"check: dx = {row['dx']:g}: error vs kappa_eff {v['error']:.3e}, vs D "
              f"{v['error_vs_kappa']:.3e}, noise {v['noise']:.3e}: "
              f"{'ok' if ok else 'FAILED'} (needs error <= 2 noise < error vs D)")
        return 0 if ok else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
