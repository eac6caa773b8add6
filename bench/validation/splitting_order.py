#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Observed order of Lie and Strang splitting against the exact continuous answer.

The case of tests/e2e/splitting_test.cpp, with more molecules: 32 SDPD
particles at rest on a periodic line (k_B T = 0), each with n0 molecules of A
decaying at rate lambda; the fluid feels the Boussinesq acceleration
beta n_i / V_i, so its total momentum is P = beta rho0 S with
S = sum over fluid stages of (stage length) x (molecule count the stage saw).
The exact continuous answer is E[S] = N0 (1 - exp(-lambda T)) / lambda; Lie
gives the left Riemann sum of N(t) (error O(tau)), Strang the trapezoid rule
(O(tau^2)). The exact mean of each rule at each tau and the standard deviation
of one run (independent exponential lifetimes) are computed too, so each
measured point is also checked against its own rule (z score).

    bench/validation/splitting_order.py [--bin build/release/bin] [--n0 1000000]
        [--tau 0.4 0.2 0.1 0.05 0.025] [--plot docs/validation/splitting_order.png]
"""
import argparse
import csv
import math
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, run_measured  # noqa: E402

LAMBDA, T_END, PARTICLES = 2.0, 0.8, 32

SCENE = """name: buoyancy
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [true]}}
particles: {{spacing: 0.03125, density: 1.0, fill: [{{kind: fluid}}]}}
fluid:
  backend: sdpd
  h_over_dx: 2.0
  reference_density: 1.0
  sound_speed: 1.0
  shear_viscosity: 0.1
  temperature: 0.0
  boussinesq: {{species: A, coefficient: {beta!r}, direction: [1.0]}}
species:
  - {{name: A, stochastic: true, diffusivity: 0.0, initial: [{{count: {n0}}}]}}
reactions:
  - {{name: decay, equation: "A -> 0", rate: {lam}}}
time: {{coupling_step: {tau!r}, end: {end}, splitting: {splitting}}}
output: {{times: [{end}], formats: [csv]}}
seed: {seed}
"""


def rule_moments(strang, tau, n_total):
    """Exact mean and variance of S for the splitting rule (independent lifetimes)."""
    steps = round(T_END / tau)
    w = [0.0] * (steps + 1)
    for k in range(steps):
        if strang:
            w[k] += tau / 2
            w[k + 1] += tau / 2
        else:
            w[k] += tau
    q = math.exp(-LAMBDA * tau)
    m1 = sum(w[k] * q**k for k in range(steps + 1))
    m2 = sum(w[k] * w[l] * q ** max(k, l) for k in range(steps + 1) for l in range(steps + 1))
    return n_total * m1, n_total * (m2 - m1 * m1)


def fit_order(taus, errors):
    xs, ys = [math.log(t) for t in taus], [math.log(e) for e in errors]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def run(bin_dir, n0=1_000_000, taus=(0.4, 0.2, 0.1, 0.05, 0.025), seed=2024):
    beta = 1e-7 * 3125 / n0  # the e2e test's acceleration, whatever n0
    n_total = PARTICLES * n0
    exact = n_total * (1 - math.exp(-LAMBDA * T_END)) / LAMBDA
    rows = []
    with tempfile.TemporaryDirectory(prefix="sadr-split-") as d:
        for splitting in ("lie", "strang"):
            for tau in taus:
                scene = pathlib.Path(d) / f"{splitting}-{tau}.yaml"
                scene.write_text(SCENE.format(beta=beta, n0=n0, lam=LAMBDA, tau=tau, end=T_END,
                                              splitting=splitting, seed=seed))
                out = pathlib.Path(d) / f"out-{splitting}-{tau}"
                r = run_measured([pathlib.Path(bin_dir) / "sadr", "run", scene, "-q", "-o", out])
                if r["rc"]:
                    sys.exit(f"sadr failed for {splitting} tau={tau}: exit {r['rc']}")
                frame = sorted((out / "frames").glob("*.csv"))[-1]
                p = sum(float(x["mass"]) * float(x["vx"]) for x in csv.DictReader(open(frame)))
                s = p / beta
                mean, var = rule_moments(splitting == "strang", tau, n_total)
                rows.append({"splitting": splitting, "tau": tau, "S": s, "rule_mean": mean,
                             "rule_sd": math.sqrt(var), "z_rule": (s - mean) / math.sqrt(var),
                             "error": abs(s - exact) / exact,
                             "rule_error": abs(mean - exact) / exact,
                             "noise": math.sqrt(var) / exact, "cpu_s": r["cpu_s"]})
    orders = {}
    for splitting in ("lie", "strang"):
        pts = [(r["tau"], r["error"]) for r in rows
               if r["splitting"] == splitting and r["error"] > 3 * r["noise"]]
        orders[splitting] = fit_order(*zip(*pts)) if len(pts) >= 2 else None
        orders[splitting + "_points"] = len(pts)
    return {"n0": n0, "N0": n_total, "lambda": LAMBDA, "T": T_END, "exact": exact,
            "rows": rows, "orders": orders}


def plot(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    for k, name in enumerate(("lie", "strang")):
        rows = [r for r in res["rows"] if r["splitting"] == name]
        taus = [r["tau"] for r in rows]
        o = res["orders"][name]
        ax.loglog(taus, [r["error"] for r in rows], "o", color=f"C{k}",
                  label=f"{name} (measured; fitted order {o:.2f})" if o else f"{name} (measured)")
        ax.loglog(taus, [r["rule_error"] for r in rows], "-", color=f"C{k}", lw=0.8,
                  label=f"{name}: exact mean of the rule")
    rows = [r for r in res["rows"] if r["splitting"] == "strang"]
    ax.loglog([r["tau"] for r in rows], [r["noise"] for r in rows], ":", color="grey",
              label="one run's standard deviation")
    ax.set_xlabel("coupling step tau")
    ax.set_ylabel("|S - S_exact| / S_exact")
    ax.set_title(f"Splitting order, decay + Boussinesq, N0 = {res['N0']:.1e}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--n0", type=int, default=1_000_000)
    ap.add_argument("--tau", type=float, nargs="+", default=[0.4, 0.2, 0.1, 0.05, 0.025])
    ap.add_argument("--plot", default="")
    a = ap.parse_args()
    res = run(a.bin, a.n0, a.tau)
    for r in res["rows"]:
        print(f"{r['splitting']:6s} tau={r['tau']:<6g} error {r['error']:.3e} (rule {r['rule_error']:.3e},"
              f" noise {r['noise']:.1e}, z vs rule {r['z_rule']:+.2f}) CPU {r['cpu_s']:.2f} s")
    print("fitted orders:", {k: v for k, v in res["orders"].items()})
    if a.plot:
        plot(res, a.plot)


if __name__ == "__main__":
    main()
