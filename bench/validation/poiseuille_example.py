#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Where the no-slip planes of examples/poiseuille_tracer_2d.yaml are.

Runs the example (to t = 10 by default, steady to 5e-5), fits
u(y) = c0 + c1 y + c2 y^2 to the fluid particles' u_x of the last frame and
reports the fit's zeros (the effective no-slip planes), H_eff, the viscosity
implied by the curvature (nu = g / (-2 c2)), the centre-line speed, and the
u_max the comment's formula g H_eff^2 / (8 nu) gives.

    bench/validation/poiseuille_example.py [--bin build/release/bin] [--end 10]
"""
import argparse
import csv
import pathlib
import re
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, run_measured  # noqa: E402

SCENE = ROOT / "examples/poiseuille_tracer_2d.yaml"


def measure(bin_dir, end=10.0, scene=SCENE):
    text = scene.read_text()
    g = float(re.search(r"gravity: \[([0-9.eE+-]+),", text).group(1))
    nu = float(re.search(r"shear_viscosity: ([0-9.eE+-]+)", text).group(1))  # rho = 1
    text = text.replace("end: 10.0", f"end: {end}")
    with tempfile.TemporaryDirectory(prefix="sadr-pois-") as d:
        s = pathlib.Path(d) / "scene.yaml"
        s.write_text(text)
        r = run_measured([pathlib.Path(bin_dir) / "sadr", "run", s, "-q", "--force", "-o",
                          pathlib.Path(d) / "out"])
        if r["rc"]:
            sys.exit(f"sadr failed: exit {r['rc']}")
        last = sorted((pathlib.Path(d) / "out" / "frames").glob("*.csv"))[-1]
        rows = [row for row in csv.DictReader(open(last)) if row["kind"] == "0"]
    y = np.array([float(row["y"]) for row in rows])
    u = np.array([float(row["vx"]) for row in rows])
    c2, c1, c0 = np.polyfit(y, u, 2)
    lo, hi = sorted(np.roots([c2, c1, c0]).real)
    h_eff = hi - lo
    return {"g": g, "nu": nu, "no_slip_lower": lo, "no_slip_upper": hi, "H_eff": h_eff,
            "nu_from_curvature": g / (-2 * c2), "u_centre": float(np.polyval([c2, c1, c0], -c1 / (2 * c2))),
            "u_max_formula_H1": g / (8 * nu), "u_max_formula_Heff": g * h_eff**2 / (8 * nu),
            "fit_rms": float(np.sqrt(np.mean((np.polyval([c2, c1, c0], y) - u) ** 2))),
            "cpu_s": r["cpu_s"], "end": end}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--end", type=float, default=10.0)
    a = ap.parse_args()
    m = measure(a.bin, a.end)
    print(f"g = {m['g']}: no-slip planes y = {m['no_slip_lower']:.4f} / {m['no_slip_upper']:.4f}, "
          f"H_eff = {m['H_eff']:.4f}, nu(curvature) = {m['nu_from_curvature']:.4f}, "
          f"u_centre = {m['u_centre']:.4f} (g H^2/8nu = {m['u_max_formula_H1']:.4f}, "
          f"g H_eff^2/8nu = {m['u_max_formula_Heff']:.4f}), fit rms {m['fit_rms']:.1e}")


if __name__ == "__main__":
    main()
