#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Benchmark of `sadr sweep`'s local executor (issue #16); run it in a quiet window.

    /usr/bin/python3 bench/sweep/sweep_bench.py BUILD/bin [--out bench/results/sweep_bench.json]

1. Throughput: a CPU-bound sweep (8 runs of a birth-death scene, ~1e7 NSM events
   each, no output to speak of) with --workers 1 and --workers 2; prints the wall
   times and the speed-up (target >= 1.8 on 2 cores).
2. Per-run overhead: 40 runs of a scene with almost no work (one coupling step,
   8 particles) with --workers 1: (wall time - the runs' own coupling loops, from
   run.json) / runs = what a run costs beyond its simulation (worker and service
   start-up, handshake, output, manifest); target <= 50 ms.
Each measurement is repeated (--repeat, default 3) and the median is printed.
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENE = """name: bench_bd
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [true]}}
particles: {{spacing: 0.125, density: 1.0}}
fluid: {{backend: static, h_over_dx: 1.5}}
species: [{{name: A, diffusivity: 0.0}}]
reactions:
  - {{name: birth, equation: "0 -> A", rate: {rate}}}
  - {{name: death, equation: "A -> 0", rate: 1}}
time: {{coupling_step: {end}, end: {end}}}
output: {{times: [{end}], formats: [csv]}}
seed: 1
"""


def sweep(sadr, d, rate, end, runs, workers):
    d.mkdir(parents=True, exist_ok=True)
    (d / "scene.yaml").write_text(SCENE.format(rate=rate, end=end))
    (d / "sweep.yaml").write_text(f"scene: scene.yaml\nrealizations: {runs}\nkeep: all\n")
    out = d / f"out-w{workers}"
    t0 = time.perf_counter()
    subprocess.run([str(sadr), "sweep", str(d / "sweep.yaml"), "-o", str(out), "--force",
                    "--workers", str(workers), "-q"], check=True, capture_output=True)
    wall = time.perf_counter() - t0
    loops = 0.0
    for r in out.glob("runs/*/run.json"):
        loops += json.loads(r.read_text())["timings_s"].get("coupling_loop", 0.0)
    return wall, loops


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin", type=Path)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    sadr = a.bin / "sadr"
    res = {}
    with tempfile.TemporaryDirectory(prefix="sadr-sweep-bench-") as tmp:
        tmp = Path(tmp)
        w1 = [sweep(sadr, tmp / "cpu", 1.25e7, 1.0, 8, 1)[0] for _ in range(a.repeat)]
        w2 = [sweep(sadr, tmp / "cpu", 1.25e7, 1.0, 8, 2)[0] for _ in range(a.repeat)]
        res["cpu_bound_8_runs_wall_s"] = {"workers_1": statistics.median(w1),
                                          "workers_2": statistics.median(w2)}
        res["speedup_2_vs_1"] = statistics.median(w1) / statistics.median(w2)
        over = []
        for _ in range(a.repeat):
            wall, loops = sweep(sadr, tmp / "tiny", 8.0, 0.01, 40, 1)
            over.append((wall - loops) / 40)
        res["per_run_overhead_ms"] = 1e3 * statistics.median(over)
    print(f"CPU-bound sweep, 8 runs: 1 worker {res['cpu_bound_8_runs_wall_s']['workers_1']:.2f} s, "
          f"2 workers {res['cpu_bound_8_runs_wall_s']['workers_2']:.2f} s, "
          f"speed-up {res['speedup_2_vs_1']:.2f} (target >= 1.8)")
    print(f"per-run overhead (wall - coupling loop) / run: {res['per_run_overhead_ms']:.1f} ms "
          f"(target <= 50 ms)")
    if a.out:
        a.out.write_text(json.dumps(res, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
