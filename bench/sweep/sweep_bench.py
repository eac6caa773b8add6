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
Each measurement is repeated (--repeat, default 3) and the median is printed,
with the targets, the machine's load average and core count before and after
(figures taken at a load above ~0.5 per core are not meaningful: the script
says so), and the CPU time (user + sys) of the sweep's processes.

    /usr/bin/python3 bench/sweep/sweep_bench.py BUILD/bin --check

is a correctness run of the same code paths in seconds (2 runs with 1e4 events
instead of 8 with 1e7, 4 tiny runs, --repeat 1): every run must finish ok with
its aggregate written; its timings mean nothing.
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


def children_cpu_s():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def load_line():
    l1, l5, _ = os.getloadavg()
    cores = os.cpu_count() or 1
    busy = " (busy: timings not meaningful, re-run in a quiet window)" if l1 > 0.5 * cores else ""
    return f"load average {l1:.2f} (1 min) {l5:.2f} (5 min) on {cores} cores{busy}", l1, cores


def sweep(sadr, d, rate, end, runs, workers):
    """One sweep; returns (wall s, the runs' coupling loops s, CPU s of its processes)."""
    d.mkdir(parents=True, exist_ok=True)
    (d / "scene.yaml").write_text(SCENE.format(rate=rate, end=end))
    (d / "sweep.yaml").write_text(f"scene: scene.yaml\nrealizations: {runs}\nkeep: all\n")
    out = d / f"out-w{workers}"
    cpu0 = children_cpu_s()
    t0 = time.perf_counter()
    proc = subprocess.run([str(sadr), "sweep", str(d / "sweep.yaml"), "-o", str(out), "--force",
                           "--workers", str(workers), "-q"], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    cpu = children_cpu_s() - cpu0
    if proc.returncode != 0:
        sys.exit(f"sweep_bench: sadr sweep {d} exited {proc.returncode}:\n{proc.stderr}")
    m = json.loads((out / "sweep.json").read_text())
    bad = [r for r in m["runs"] if r["state"] != "ok"]
    if len(m["runs"]) != runs or bad:
        sys.exit(f"sweep_bench: {out}: {len(m['runs'])} runs (expected {runs}), not ok: {bad}")
    if not (out / "points" / "p0000" / "aggregate.pvd").exists():
        sys.exit(f"sweep_bench: {out}/points/p0000/aggregate.pvd missing")
    loops = 0.0
    for r in out.glob("runs/*/run.json"):
        loops += json.loads(r.read_text())["timings_s"].get("coupling_loop", 0.0)
    return wall, loops, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin", type=Path)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--check", action="store_true",
                    help="tiny correctness run (seconds; timings meaningless)")
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    sadr = a.bin / "sadr"
    cpu_rate, cpu_runs, tiny_runs = (1.25e4, 2, 4) if a.check else (1.25e7, 8, 40)
    repeat = 1 if a.check else a.repeat
    before, l1_before, cores = load_line()
    print(f"sweep_bench: {'--check (correctness only) ' if a.check else ''}before: {before}")
    res = {"check_only": a.check, "cores": cores, "load_1min_before": l1_before}
    with tempfile.TemporaryDirectory(prefix="sadr-sweep-bench-") as tmp:
        tmp = Path(tmp)
        w1 = [sweep(sadr, tmp / "cpu", cpu_rate, 1.0, cpu_runs, 1) for _ in range(repeat)]
        w2 = [sweep(sadr, tmp / "cpu", cpu_rate, 1.0, cpu_runs, 2) for _ in range(repeat)]
        med = {k: statistics.median(x[0] for x in w) for k, w in (("workers_1", w1),
                                                                    ("workers_2", w2))}
        res[f"cpu_bound_{cpu_runs}_runs_wall_s"] = med
        res[f"cpu_bound_{cpu_runs}_runs_cpu_s"] = {
            "workers_1": statistics.median(x[2] for x in w1),
            "workers_2": statistics.median(x[2] for x in w2)}
        res["speedup_2_vs_1"] = med["workers_1"] / med["workers_2"]
        over = []
        for _ in range(repeat):
            wall, loops, _ = sweep(sadr, tmp / "tiny", 8.0, 0.01, tiny_runs, 1)
            over.append((wall - loops) / tiny_runs)
        res["per_run_overhead_ms"] = 1e3 * statistics.median(over)
    after, l1_after, _ = load_line()
    res["load_1min_after"] = l1_after
    cpu = res[f"cpu_bound_{cpu_runs}_runs_cpu_s"]
    print(f"CPU-bound sweep, {cpu_runs} runs: 1 worker {med['workers_1']:.2f} s wall "
          f"({cpu['workers_1']:.2f} s CPU), 2 workers {med['workers_2']:.2f} s wall "
          f"({cpu['workers_2']:.2f} s CPU), speed-up {res['speedup_2_vs_1']:.2f} "
          f"(target >= 1.8 on 2 cores)")
    print(f"per-run overhead (wall - coupling loop) / run, {tiny_runs} runs: "
          f"{res['per_run_overhead_ms']:.1f} ms (target <= 50 ms)")
    print(f"sweep_bench: after: {after}")
    if a.check:
        print("sweep_bench: --check: every run ok and aggregated; the timings above are not "
              "measurements")
    if a.out:
        a.out.write_text(json.dumps(res, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
