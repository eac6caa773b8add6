#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Splitting error of a hybrid reaction against the coupling step tau (docs/method.md 4c).

Stochastic A birth-death (0 -> A at k1, A -> 0 at d1), deterministic B with
dB/dt = k A - d B: the fluid reads A = X / V, held at each coupling step's start.
E[B](T) has a closed form (the ODE driven by E[A](t)); the run's mean over N
independent particles (no diffusion) is compared at 5 values of tau.

The SSA of A does not depend on tau (no law of A reads B or t: the NSM's
trajectory is cut at the step ends without new draws), so every tau sees the
same A paths: the differences between taus are free of sampling noise, and the
observed order is fitted from them: p = log2(|B(2 tau) - B(tau)| / |B(tau) - B(tau/2)|).
Each error against the exact mean is also given with its standard error.

  /usr/bin/python3 bench/hybrid/tau_sweep.py --sadr build/release/bin/sadr \
      --out bench/results/hybrid_tau_sweep.txt
"""
import argparse
import csv
import glob
import math
import os
import subprocess
import sys
import tempfile

K1, D1, K, D, T = 20.0, 1.0, 1.0, 2.0, 2.0

SCENE = """name: hybrid_tau_sweep
dimension: 1
box: {{lower: [0.0], upper: [{n}.0], periodic: [true]}}
particles: {{spacing: 1.0}}
fluid: {{backend: static, h_over_dx: 2.0, max_time_step: 0.001}}
parameters: {{k: {k}}}
species:
  - {{name: A, diffusivity: 0}}
  - {{name: B, stochastic: false, diffusivity: 0}}
reactions:
  - {{name: a_birth, equation: "0 -> A", rate: {k1}}}
  - {{name: a_death, equation: "A -> 0", rate: {d1}}}
  - {{name: b_birth, equation: "0 -> B", law: {{type: expression, expression: "k*A"}}}}
  - {{name: b_death, equation: "B -> 0", rate: {d}}}
time: {{coupling_step: {tau}, end: {t}}}
output: {{every: {t}, formats: [csv]}}
seed: 23
"""


def exact_b(t):
    m = K1 / D1
    return K * m * ((1 - math.exp(-D * t)) / D - (math.exp(-D1 * t) - math.exp(-D * t)) / (D - D1))


def run(sadr, n, tau, work):
    d = os.path.join(work, "tau_%g" % tau)
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(d, "scene.yaml")
    with open(scene, "w") as f:
        f.write(SCENE.format(n=n, k=K, k1=K1, d1=D1, d=D, tau=tau, t=T))
    subprocess.run([sadr, "run", scene, "-q", "--embedded", "-o", os.path.join(d, "out")],
                   check=True)
    last = sorted(glob.glob(os.path.join(d, "out", "frames", "*.csv")))[-1]
    with open(last) as f:
        rows = list(csv.DictReader(f))
    b = [float(r["B"]) for r in rows]
    a = [float(r["A"]) for r in rows]
    mean = sum(b) / len(b)
    var = sum((x - mean) ** 2 for x in b) / (len(b) - 1)
    return mean, math.sqrt(var / len(b)), sum(a) / len(a)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sadr", required=True)
    ap.add_argument("--particles", type=int, default=4000)
    ap.add_argument("--taus", default="0.4,0.2,0.1,0.05,0.025")
    ap.add_argument("--out")
    args = ap.parse_args()
    taus = [float(x) for x in args.taus.split(",")]
    lines = ["# " + " ".join(["/usr/bin/python3"] + sys.argv),
             "# E[B](T=%g) exact %.6f; %d particles (V = 1), k1=%g d1=%g k=%g d=%g" %
             (T, exact_b(T), args.particles, K1, D1, K, D),
             "tau mean_B se error_vs_exact z mean_A"]
    results = []
    with tempfile.TemporaryDirectory(prefix="sadr-tau-sweep-") as work:
        for tau in taus:
            mean, se, mean_a = run(args.sadr, args.particles, tau, work)
            err = mean - exact_b(T)
            results.append((tau, mean))
            lines.append("%g %.6f %.6f %+.6f %+.2f %.4f" % (tau, mean, se, err, err / se, mean_a))
    lines.append("# successive differences (same A paths: no sampling noise) and observed order")
    diffs = [results[i][1] - results[i + 1][1] for i in range(len(results) - 1)]
    for i, dd in enumerate(diffs):
        order = "" if i == 0 else " order %.3f" % math.log2(abs(diffs[i - 1]) / abs(dd))
        lines.append("B(%g) - B(%g) = %+.6f%s" % (results[i][0], results[i + 1][0], dd, order))
    # The limit tau -> 0 by Richardson (first order), and the error constant.
    lim = 2 * results[-1][1] - results[-2][1]
    lines.append("# Richardson limit %.6f (exact %.6f); bias / tau at the smallest tau: %.4f "
                 "(leading-order prediction -k/2 int dE[A]/dt e^{-d(T-s)} ds = %.4f)" %
                 (lim, exact_b(T), (results[-1][1] - lim) / results[-1][0],
                  -K / 2 * K1 * math.exp(-D * T) * (math.exp((D - D1) * T) - 1) / (D - D1)))
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
