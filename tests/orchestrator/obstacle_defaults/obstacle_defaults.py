#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A flow past an obstacle with the default fluid settings stays sound.

Runs obstacle_defaults.yaml (no sound_speed, reference_density or wall_model: the loader
chooses the sound speed and a background pressure) and asserts, at every frame after the first:
no fluid particle deeper than half a spacing inside the disk, the wake box behind it never
emptied (at least 3/4 of its particles at the start), and the density within 1 % of the first
frame's median. Then the same scene with the settings a new user picks from the Mach rule
alone (sound_speed 8, reference_density 1.0) must be warned at load and must put fluid inside
the disk within the same time: the check can fail.
"""
import argparse
import csv
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

CX, CY, R, DX = 0.6, 0.5, 0.25, 0.05
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "obstacle_defaults.yaml")


def frames(run):
    out = []
    for path in sorted(glob.glob(os.path.join(run, "frames", "frame_*.csv"))):
        with open(path) as fh:
            fluid = [r for r in csv.DictReader(fh) if r["kind"] == "0"]
        x = [float(r["x"]) for r in fluid]
        y = [float(r["y"]) for r in fluid]
        out.append({
            "t": float(fluid[0]["time"]),
            "inside": sum(math.hypot(a - CX, b - CY) < R - DX / 2 for a, b in zip(x, y)),
            "wake": sum(CX + R < a < CX + R + 0.2 and abs(b - CY) < 0.15 for a, b in zip(x, y)),
            "rho": sorted(float(r["density"]) for r in fluid),
        })
    return out


def run(sadr, out, extra):
    cmd = [sadr, "run", SCENE, "-q", "--force", "-o", out] + extra
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {res.returncode}\n{res.stderr}")
    return res.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sadr", required=True)
    a = ap.parse_args()
    fails = []
    with tempfile.TemporaryDirectory() as tmp:
        good = os.path.join(tmp, "defaults")
        run(a.sadr, good, [])
        with open(os.path.join(good, "run.json")) as fh:
            chosen = json.load(fh)["plan"].get("chosen", [])
        print("chosen:", *chosen, sep="\n  ")
        if len(chosen) != 2:
            fails.append(f"expected a chosen sound speed and background pressure, got {chosen}")
        fr = frames(good)
        rho0 = fr[0]["rho"][len(fr[0]["rho"]) // 2]
        for f in fr[1:]:
            drho = max(abs(f["rho"][0] / rho0 - 1), abs(f["rho"][-1] / rho0 - 1))
            print(f"defaults t = {f['t']:4.1f}: inside {f['inside']}, wake {f['wake']} "
                  f"(start {fr[0]['wake']}), max |rho/rho0 - 1| {drho:.4f}")
            if f["inside"] > 0:
                fails.append(f"t = {f['t']}: {f['inside']} fluid particles inside the disk")
            if f["wake"] < 0.75 * fr[0]["wake"]:
                fails.append(f"t = {f['t']}: the wake box holds {f['wake']} of {fr[0]['wake']}")
            if drho > 0.01:
                fails.append(f"t = {f['t']}: density deviation {drho:.4f} > 0.01")
        bad = os.path.join(tmp, "mach_rule_only")
        log = run(a.sadr, bad, ["--set", "fluid.sound_speed=8",
                                "--set", "fluid.reference_density=1.0"])
        for needle in ("is below sqrt(dp / (0.01 rho))", "the background pressure 0"):
            if needle not in log:
                fails.append(f"c0 = 8, rho0 = 1: no warning containing '{needle}'")
        worst = max(f["inside"] for f in frames(bad)[1:])
        print(f"c0 = 8, reference_density 1.0: up to {worst} fluid particles inside the disk")
        if worst == 0:
            fails.append("c0 = 8, reference_density 1.0: no fluid inside the disk; the check "
                         "would not see the failure it guards against")
    for f in fails:
        print("FAIL:", f)
    print("obstacle_defaults:", "FAIL" if fails else "ok")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
