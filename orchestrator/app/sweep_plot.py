#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Summary plot of a sadr sweep (docs/sweeps.md).

    /usr/bin/python3 orchestrator/app/sweep_plot.py SWEEP_DIR [--species A] [--frame last]
                     [--parameter PATH] [-o SWEEP_DIR/summary.png]

From SWEEP_DIR/observables.csv: for every point, the mean over realizations of
the species total at one frame, against the swept parameter (the first one,
or --parameter), with the 95 % confidence band mean -+ t(0.975, R - 1) sem.
Needs Debian's python3-matplotlib (deploy/install-deps.sh). Prints the table
it plotted."""
import argparse
import csv
import math
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from scipy import stats  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir", type=Path)
    ap.add_argument("--species", default=None, help="default: the first species")
    ap.add_argument("--frame", default="last", help="frame index, or 'last'")
    ap.add_argument("--parameter", default=None, help="default: the first swept path")
    ap.add_argument("-o", "--output", type=Path, default=None)
    a = ap.parse_args()
    with open(a.sweep_dir / "observables.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{a.sweep_dir}/observables.csv has no rows (no point aggregated yet)")
    fixed = {"point", "realization", "frame", "time", "species", "total"}
    params = [k for k in rows[0] if k not in fixed]
    if not params:
        sys.exit("the sweep has no parameters: nothing to plot against")
    param = a.parameter or params[0]
    if param not in params:
        sys.exit(f"--parameter {param}: not a swept path ({', '.join(params)})")
    species = a.species or rows[0]["species"]
    rows = [r for r in rows if r["species"] == species]
    if not rows:
        sys.exit(f"--species {species}: not in observables.csv")
    frame = max(int(r["frame"]) for r in rows) if a.frame == "last" else int(a.frame)
    by_point = defaultdict(list)
    x_of = {}
    for r in rows:
        if int(r["frame"]) == frame:
            by_point[int(r["point"])].append(float(r["total"]))
            x_of[int(r["point"])] = float(r[param])
    xs, means, lo, hi = [], [], [], []
    print(f"{param},{species}_total_mean,ci95_lo,ci95_hi,realizations")
    for p in sorted(by_point, key=lambda p: x_of[p]):
        v = by_point[p]
        n = len(v)
        m = sum(v) / n
        half = float("nan")
        if n > 1:
            var = sum((x - m) ** 2 for x in v) / (n - 1)
            half = stats.t.ppf(0.975, n - 1) * math.sqrt(var / n)
        xs.append(x_of[p])
        means.append(m)
        lo.append(m - half)
        hi.append(m + half)
        print(f"{x_of[p]},{m},{m - half},{m + half},{n}")
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.fill_between(xs, lo, hi, alpha=0.3, label="95 % confidence band")
    ax.plot(xs, means, "o-", label=f"mean total {species}")
    ax.set_xlabel(param)
    ax.set_ylabel(f"total {species} at frame {frame}")
    ax.legend()
    fig.tight_layout()
    out = a.output or a.sweep_dir / "summary.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
