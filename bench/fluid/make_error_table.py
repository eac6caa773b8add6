#!/usr/bin/env python3
"""Runs fluid_error_sweep and writes the run-time-vs-error table to docs/fluid-error-table.md.

Usage: bench/fluid/make_error_table.py [path/to/fluid_error_sweep]
(default: build/release/bench/fluid/fluid_error_sweep relative to the repository root)."""
import csv
import datetime
import io
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/release/bench/fluid/fluid_error_sweep")
env = dict(os.environ, SADR_REFS=os.path.join(ROOT, "tests/data/refs"), OMP_NUM_THREADS="1")
out = subprocess.run([exe], check=True, capture_output=True, text=True, env=env).stdout
rows = list(csv.DictReader(io.StringIO(out)))
lines = ["# Fluid core: run time versus error",
         "",
         "Written by `bench/fluid/make_error_table.py` on %s (one thread; CPU seconds of the"
         % datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"),
         "whole run; %s, load average %.2f at the end). Regenerate after any change to the fluid numerics."
         % (os.path.relpath(os.path.abspath(exe), ROOT), os.getloadavg()[0]),
         "",
         "* Poiseuille start-up (Morris, Fox & Zhu 1997 series, `poiseuille_exact` in tests/fluid/reference_solutions.hpp), SDPD backend, k_B T = 0, Morris walls, h = 3 dx, error =",
         "  scaled L2 / u_max at t = 0.225 s; resolution = H/dx; dt = sub-step (1, 1/2, 1/4 of the viscous limit).",
         "* A + B -> 0 (drawert2019 sec. 4.1, N_b = 1e3), deterministic species on frozen particles, h = 1.8 dx,",
         "  eps = 0; error = the paper's metric ||u_A - u_ref||_2/(Np - 1) at t = 1 s vs the 6th-order PDE",
         "  reference (tests/data/refs/annihilation_1d_subset.csv); resolution = Np.",
         "",
         "| case | resolution | dt [s] | error | CPU [s] | wall [s] |",
         "|---|---|---|---|---|---|"]
for r in rows:
    lines.append("| %s | %s | %s | %.3e | %s | %s |" % (r["case"], r["resolution"], r["dt"], float(r["error"]),
                                                       r["cpu_s"], r["wall_s"]))
path = os.path.join(ROOT, "docs", "fluid-error-table.md")
with open(path, "w") as f:
    f.write("\n".join(lines) + "\n")
print("wrote", path)
