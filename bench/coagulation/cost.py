#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Cost of the 25-species coagulation chemistry against the same tDPD flow with no species.

li2015 sec. III C: a 30 x 33 x 10 periodic box of 39 600 particles (rho = 4, r_c = 2.9,
r_cc = 1.0), 0.398 s per step with the 23 transported species and 0.192 s without: 2.07x on one
core of a Xeon E5-2637. Here: the same box on a 0.625 lattice (48 x 53 x 16 = 40 704 particles,
box 30 x 33.125 x 10, number density 4.096), the li2015 parameters of examples/
coagulation_cascade.yaml, at rest (k_B T = 1, no body force), dt = 0.003; with species: the 23
transported species of the cascade at their plasma values C_i0, the two assigned ones, and the
22 Table III reactions (bench/coagulation/make_scenes.py); without: no species at all.

Each configuration runs `sadr run` twice, to t = T0 and to t = T0 + T (frames only at the end);
the cost per step is the difference of the two runs' CPU seconds (all processes: sadr and its
services, getrusage of the children) divided by the T/dt extra steps, so start-up and output
cancel. Pairs are interleaved (with, without, with, without, ...) and the ratio of medians is
reported. Target: <= 1.8x. Do not run on a loaded machine: the figures mean nothing there.

  OMP_NUM_THREADS=1 /usr/bin/python3 bench/coagulation/cost.py --sadr build/release/bin/sadr \
      --pairs 3 --out bench/results/coagulation_cost.json
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_scenes  # noqa: E402

ref = make_scenes.ref
DX = 0.625
DT = 0.003  # the tdpd dissipative limit at r_c = 2.9, gamma = 4.5, rho = 4.096 (0.00303)


def scene(with_species, end):
    p = ref.rate_parameters()
    lines = [
        f"name: coagulation_cost_{'species' if with_species else 'flow'}",
        "dimension: 3",
        "box: {lower: [0, 0, 0], upper: [30.0, 33.125, 10.0], periodic: [true, true, true]}",
        f"particles: {{spacing: {DX}}}",
        "fluid:",
        "  backend: tdpd",
        "  smoothing_length: 2.9",
        "  reference_density: 4.096",
        "  temperature: 1.0",
        "  shear_viscosity: 138.6   # not read by tdpd (its viscosity follows from a, gamma, r_c)",
        f"  max_time_step: {DT}",
        "  parameters: {a: 18.75, gamma: 4.5, s1: 0.4, r_cc: 1.0}",
    ]
    if with_species:
        lines.append("species:")
        for (name, _, c0, _), (_, _, kappa) in zip(ref.SPECIES, ref.diffusivities()):
            lines.append(f"  - {{name: {name}, stochastic: false, diffusivity: {kappa:.6g}, "
                         f"initial: [{{concentration: {make_scenes.num(c0)}}}]}}")
        for name, _, expr in ref.ASSIGNED:
            lines.append(f'  - {{name: {name}, assigned: "{expr}"}}')
        lines += make_scenes.reactions_yaml(p)
    lines += [
        f"time: {{coupling_step: 0.06, end: {end}}}",  # 20 sub-steps per fluid call
        f"output: {{times: [{end}], include_initial: false, formats: [csv]}}",
        "seed: 3",
    ]
    return "\n".join(lines) + "\n"


def cpu_of_run(sadr, path, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.perf_counter()
    subprocess.run([sadr, "run", str(path), "--output", str(out), "--force", "--quiet",
                    "--allow-large"], check=True)
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sadr", default="build/release/bin/sadr")
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--t0", type=float, default=0.06, help="short run (start-up, cancels)")
    ap.add_argument("--t", type=float, default=0.6, help="extra time of the long run (200 steps)")
    ap.add_argument("--out", default=None, help="JSON with every measurement")
    ap.add_argument("--write-scenes", default=None, help="only write the scenes to this folder")
    args = ap.parse_args()
    tmp = Path(args.write_scenes or tempfile.mkdtemp(prefix="coag-cost-"))
    tmp.mkdir(parents=True, exist_ok=True)
    paths = {}
    for ws in (True, False):
        for end in (args.t0, round(args.t0 + args.t, 9)):
            path = tmp / f"{'species' if ws else 'flow'}_{end:g}.yaml"
            path.write_text(scene(ws, end))
            paths[ws, end] = path
    if args.write_scenes:
        print(f"wrote {len(paths)} scenes to {tmp}")
        return 0
    steps = args.t / DT
    per_step = {True: [], False: []}
    rows = []
    for k in range(args.pairs):
        for ws in (True, False):
            short, _ = cpu_of_run(args.sadr, paths[ws, args.t0], tmp / "out_short")
            long_, wall = cpu_of_run(args.sadr, paths[ws, round(args.t0 + args.t, 9)],
                                     tmp / "out_long")
            s = (long_ - short) / steps
            per_step[ws].append(s)
            rows.append({"pair": k, "species": ws, "cpu_short_s": short, "cpu_long_s": long_,
                         "wall_long_s": wall, "cpu_per_step_s": s})
            print(f"pair {k} {'25 species' if ws else 'no species'}: {s * 1e3:.1f} ms CPU/step "
                  f"(runs {short:.1f} s and {long_:.1f} s CPU)", flush=True)
    med = {ws: statistics.median(v) for ws, v in per_step.items()}
    ratio = med[True] / med[False]
    print(f"median CPU per step: 25 species {med[True] * 1e3:.1f} ms, no species "
          f"{med[False] * 1e3:.1f} ms, ratio {ratio:.2f}x (li2015 2.07x; target <= 1.8x)")
    if args.out:
        with open(args.out, "w") as f:
            json.dump({"particles": 48 * 53 * 16, "dt": DT, "steps": steps, "rows": rows,
                       "median_cpu_per_step_s": {"species": med[True], "flow": med[False]},
                       "ratio": ratio, "omp_threads": os.environ.get("OMP_NUM_THREADS")}, f,
                      indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
