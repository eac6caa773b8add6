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
services, getrusage of the children) divided by the extra sub-steps, so start-up and output
cancel. Pairs are interleaved (with, without, with, without, ...) and the ratio of medians is
reported. Target: <= 1.8x. Do not run on a loaded machine: the figures mean nothing there.

  OMP_NUM_THREADS=1 /usr/bin/python3 bench/coagulation/cost.py --sadr build/release/bin/sadr \
      --pairs 3 --out bench/results/coagulation_cost.json

--backend sdpd runs the same box with the SDPD fluid of examples/coagulation_cascade_sdpd.yaml
(h = 3 dx, rho_0 = 1, eta = 138.6, c_0 = 2, k_B T = 0) at its own sub-step (the viscous limit,
7.9e-4); the sub-steps are counted from each run's run.json (`fluid_substeps`). Default
--t0 / --t are then 0.008 / 0.04 (about 50 sub-steps).
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


FLUIDS = {
    "tdpd": ["  backend: tdpd",
             "  smoothing_length: 2.9",
             "  reference_density: 4.096",
             "  temperature: 1.0",
             "  shear_viscosity: 138.6   # not read by tdpd (its viscosity follows from a, gamma, r_c)",
             f"  max_time_step: {DT}",
             "  parameters: {a: 18.75, gamma: 4.5, s1: 0.4, r_cc: 1.0}"],
    "sdpd": ["  backend: sdpd",
             f"  smoothing_length: {3 * DX}",
             "  reference_density: 1.0",
             "  shear_viscosity: 138.6",
             "  sound_speed: 2.0",
             "  temperature: 0.0"],
}


def scene(with_species, end, backend="tdpd"):
    p = ref.rate_parameters()
    lines = [
        f"name: coagulation_cost_{'species' if with_species else 'flow'}",
        "dimension: 3",
        "box: {lower: [0, 0, 0], upper: [30.0, 33.125, 10.0], periodic: [true, true, true]}",
        f"particles: {{spacing: {DX}}}",
        "fluid:",
    ] + FLUIDS[backend]
    if with_species:
        lines.append("species:")
        for (name, _, c0, _), (_, d, kappa) in zip(ref.SPECIES, ref.diffusivities()):
            diff = kappa if backend == "tdpd" else d
            lines.append(f"  - {{name: {name}, stochastic: false, diffusivity: {diff:.6g}, "
                         f"initial: [{{concentration: {make_scenes.num(c0)}}}]}}")
        for name, _, expr in ref.ASSIGNED:
            lines.append(f'  - {{name: {name}, assigned: "{expr}"}}')
        lines += make_scenes.reactions_yaml(p)
    tau = 0.06 if backend == "tdpd" else 0.008  # 20 (tdpd) / ~10 (sdpd) sub-steps per call
    lines += [
        f"time: {{coupling_step: {tau}, end: {end}}}",
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
    substeps = json.loads((Path(out) / "run.json").read_text())["fluid_substeps"]
    return cpu, wall, substeps


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sadr", default="build/release/bin/sadr")
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--backend", choices=sorted(FLUIDS), default="tdpd")
    ap.add_argument("--t0", type=float, default=None,
                    help="short run (start-up, cancels); default 0.06 (tdpd), 0.008 (sdpd)")
    ap.add_argument("--t", type=float, default=None,
                    help="extra time of the long run; default 0.6 (tdpd: 200 steps), 0.04 (sdpd)")
    ap.add_argument("--out", default=None, help="JSON with every measurement")
    ap.add_argument("--write-scenes", default=None, help="only write the scenes to this folder")
    args = ap.parse_args()
    tdpd = args.backend == "tdpd"
    if args.t0 is None:
        args.t0 = 0.06 if tdpd else 0.008
    if args.t is None:
        args.t = 0.6 if tdpd else 0.04
    tmp = Path(args.write_scenes or tempfile.mkdtemp(prefix="coag-cost-"))
    tmp.mkdir(parents=True, exist_ok=True)
    paths = {}
    for ws in (True, False):
        for end in (args.t0, round(args.t0 + args.t, 9)):
            path = tmp / f"{'species' if ws else 'flow'}_{end:g}.yaml"
            path.write_text(scene(ws, end, args.backend))
            paths[ws, end] = path
    if args.write_scenes:
        print(f"wrote {len(paths)} scenes to {tmp}")
        return 0
    per_step = {True: [], False: []}
    rows = []
    for k in range(args.pairs):
        for ws in (True, False):
            short, _, n_short = cpu_of_run(args.sadr, paths[ws, args.t0], tmp / "out_short")
            long_, wall, n_long = cpu_of_run(args.sadr, paths[ws, round(args.t0 + args.t, 9)],
                                             tmp / "out_long")
            steps = n_long - n_short
            s = (long_ - short) / steps
            per_step[ws].append(s)
            rows.append({"pair": k, "species": ws, "cpu_short_s": short, "cpu_long_s": long_,
                         "wall_long_s": wall, "extra_substeps": steps, "cpu_per_step_s": s})
            print(f"pair {k} {'25 species' if ws else 'no species'}: {s * 1e3:.1f} ms CPU/step "
                  f"(runs {short:.1f} s and {long_:.1f} s CPU)", flush=True)
    med = {ws: statistics.median(v) for ws, v in per_step.items()}
    ratio = med[True] / med[False]
    print(f"median CPU per step: 25 species {med[True] * 1e3:.1f} ms, no species "
          f"{med[False] * 1e3:.1f} ms, ratio {ratio:.2f}x (li2015 2.07x; target <= 1.8x)")
    if args.out:
        with open(args.out, "w") as f:
            json.dump({"backend": args.backend, "particles": 48 * 53 * 16, "rows": rows,
                       "median_cpu_per_step_s": {"species": med[True], "flow": med[False]},
                       "ratio": ratio, "omp_threads": os.environ.get("OMP_NUM_THREADS")}, f,
                      indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
