#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a sweep's aggregates against numpy on the per-realization frames.

    sweep_stats_check.py SWEEP_DIR

For every point and frame: A_mean and A_var (ddof = 1) of every species equal
numpy's mean and var over runs/pPPPP_r*/frames/frame_NNNNNN.csv to 1e-12
(relative to max(1, |value|)), and so does sem = sqrt(var / R); the 95 %
interval mean -+ t(0.975, R - 1) sem is checked to 1e-9 only, because scipy's
t quantile is itself off by up to ~6e-11 (df = 9: 2.2621571627409915 against
mpmath's 2.2621571627982055, which Boost.Math gives). Prints the largest
deviation; exit 1 on a mismatch."""
import csv
import json
import math
import sys
from pathlib import Path

import numpy as np
from scipy import stats


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def main():
    d = Path(sys.argv[1])
    m = json.loads((d / "sweep.json").read_text())
    R = m["realizations"]
    worst, checked = 0.0, 0
    for p in m["points"]:
        runs = [r for r in m["runs"] if r["point"] == p["index"]]
        runs.sort(key=lambda r: r["realization"])
        agg_dir = d / p["aggregate_dir"]
        for agg in sorted(agg_dir.glob("frame_*.csv")):
            a = read(agg)
            frames = [read(d / r["dir"] / "frames" / agg.name) for r in runs]
            species = [k[:-5] for k in a if k.endswith("_mean")]
            t = stats.t.ppf(0.975, R - 1)
            for s in species:
                x = np.stack([f[s] for f in frames])  # R x N
                mean, var = x.mean(axis=0), x.var(axis=0, ddof=1)
                sem = np.sqrt(var / R)
                for name, ref, tol in ((s + "_mean", mean, 1e-12), (s + "_var", var, 1e-12),
                                       (s + "_sem", sem, 1e-12),
                                       (s + "_ci95_lo", mean - t * sem, 1e-9),
                                       (s + "_ci95_hi", mean + t * sem, 1e-9)):
                    err = np.max(np.abs(a[name] - ref) / np.maximum(1.0, np.abs(ref)))
                    if tol == 1e-12:
                        worst = max(worst, float(err))
                    checked += ref.size
                    if not err <= tol:
                        print(f"{agg}: {name} differs from numpy by {err:.3g}")
                        return 1
            if not np.all(a["realizations"] == R):
                print(f"{agg}: realizations column is not {R}")
                return 1
    if checked == 0:
        print("nothing checked")
        return 1
    print(f"{checked} values checked; mean, var, sem equal numpy's to {worst:.3g} "
          "(relative, tolerance 1e-12)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
