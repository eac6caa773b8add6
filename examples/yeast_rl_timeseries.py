#!/usr/bin/env python3
"""Receptor occupancy over time from a yeast_cell_channel run (drawert2019 Fig. 7).

Reads the CSV frames of `sadr run examples/yeast_cell_channel.yaml -o OUT` and
prints, per frame: t, t* (= t: the example's time unit is x0/v0), the molecules
of L in the channel, R and RL on the membrane, and C_RL* = RL / (R + RL), the
dimensionless bound-receptor concentration (C_R = 1 at t = 0 in units of c0,
so C_RL* is also RL per membrane voxel in units of c0 V). Standard library only.

Usage: python3 examples/yeast_rl_timeseries.py OUT
"""
import csv
import glob
import os
import sys


def main(out):
    frames = sorted(glob.glob(os.path.join(out, "frames", "frame_*.csv")))
    if not frames:
        sys.exit(f"no CSV frames in {out}/frames (run with output formats including csv)")
    print("t,L_channel,R,RL,C_RL_star")
    for f in frames:
        with open(f, newline="") as fh:
            rows = list(csv.DictReader(fh))
        t = float(rows[0]["time"])
        lsum = sum(float(r["L"]) for r in rows)
        rsum = sum(float(r["R"]) for r in rows)
        rlsum = sum(float(r["RL"]) for r in rows)
        occ = rlsum / (rsum + rlsum) if rsum + rlsum > 0 else 0.0
        print(f"{t:.4g},{lsum:.0f},{rsum:.0f},{rlsum:.0f},{occ:.5f}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
