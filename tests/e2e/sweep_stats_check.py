#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks a sweep's aggregates against numpy on the per-realization frames.

    sweep_stats_check.py SWEEP_DIR

For every point and frame: A_mean and A_var (ddof = 1) of every species equal
numpy's mean and var over runs/pPPPP_r*/frames/frame_NNNNNN.csv to 1e-12
(relative to max(1, |value|)); sem = sqrt(var / R); the 95 % interval is
mean -+ t(0.975, R - 1) sem (scipy). Prints the largest deviation; exit 1 on a
mismatch."""
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
                for name, ref in ((s + "_mean", mean), (s + "_var", var), (s + "_sem", sem),
                                  (s + "_ci95_lo", mean - t * sem),
                                  (s + "_ci95_hi", mean + t * sem)):
                    err = np.max(np.abs(a[name] - ref) / np.maximum(1.0, np.abs(ref)))
                    worst = max(worst, float(err))
                    checked += ref.size
                    if not err <= 1e-12:
                        print(f"{agg}: {name} differs from numpy by {err:.3g}")
                        return 1
            if not np.all(a["realizations"] == R):
                print(f"{agg}: realizations column is not {R}")
                return 1
    if checked == 0:
        print("nothing checked")
        return 1
    print(f"{checked} values equal numpy's to {worst:.3g} (relative, tolerance 1e-12)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
