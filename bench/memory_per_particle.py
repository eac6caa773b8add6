#!/usr/bin/python3
"""Peak resident memory (VmHWM) of sadr, fluid_service and ssa_service per
particle, by backend and dimension: two lattice sizes each, the slope is the
bytes per particle that orchestrator/scene/src/machine_limits.cpp uses.

    bench/memory_per_particle.py BUILD/bin [--sizes 50000 200000]

Correctness-style measurement (peak RSS, not timing): fine on a loaded machine.
"""
import argparse, os, subprocess, sys, tempfile, time

# The process helpers (children, comm) have one home, shared with the fault campaign.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "fault"))
from sadr_procs import children, comm  # noqa: E402

SCENE = """name: mem
dimension: {dim}
box: {{lower: [{lo}], upper: [{hi}], periodic: [{per}]}}
particles: {{spacing: 1.0}}
fluid: {{backend: {backend}, h_over_dx: {hdx}, sound_speed: 10.0, shear_viscosity: 1.0{extra}}}
species:
  - {{name: A, stochastic: {stochastic}, diffusivity: 0.01, initial: [{{count: 10}}]}}
time: {{coupling_step: 0.001, end: 0.002}}
output: {{include_initial: false, formats: [csv]}}
"""

def hwm(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        return None
    return None

def measure(bindir, dim, backend, n, tmp, stochastic):
    side = round(n ** (1.0 / dim))
    extra = ", temperature: 0.0" if backend != "static" else ""
    text = SCENE.format(dim=dim, lo=", ".join(["0.0"] * dim), hi=", ".join([str(float(side))] * dim),
                        per=", ".join(["true"] * dim), backend=backend,
                        hdx={1: 3.0, 2: 3.0, 3: 2.0}[dim], extra=extra,
                        stochastic="true" if stochastic else "false")
    path = os.path.join(tmp, f"mem_{backend}_{dim}d_{n}_{stochastic}.yaml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(tmp, f"out_{backend}_{dim}d_{n}_{stochastic}")
    p = subprocess.Popen([os.path.join(bindir, "sadr"), "run", path, "-o", out, "--force", "-q"],
                         stderr=subprocess.PIPE)
    peak = {}
    while p.poll() is None:
        for pid in [p.pid] + children(p.pid):
            v = hwm(pid)
            if v:
                name = comm(pid)
                name = "sadr" if pid == p.pid else name
                peak[name] = max(peak.get(name, 0), v)
        time.sleep(0.01)
    err = p.stderr.read().decode()
    if p.returncode != 0:
        sys.exit(f"{path}: exit {p.returncode}: {err}")
    return side ** dim, peak

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bindir")
    ap.add_argument("--sizes", type=int, nargs=2, default=[50000, 200000])
    # BACKEND:DIMENSION[:det] (det: a deterministic species instead of a stochastic one)
    ap.add_argument("--cases", nargs="*", default=["sdpd:1", "sdpd:2", "sdpd:3", "static:1",
                                                   "static:2", "static:3", "tdpd:2", "tdpd:3",
                                                   "static:2:det", "static:3:det", "sdpd:3:det"])
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print("| case | process | base MiB | bytes/particle |")
        print("|---|---|---|---|")
        for case in a.cases:
            backend, dim, *kind = case.split(":")
            stochastic = kind != ["det"]
            (n1, p1), (n2, p2) = (measure(a.bindir, int(dim), backend, s, tmp, stochastic)
                                  for s in a.sizes)
            for proc in sorted(set(p1) & set(p2)):
                slope = (p2[proc] - p1[proc]) / (n2 - n1)
                base = p1[proc] - slope * n1
                if proc == "exe":
                    continue  # a short-lived exec of a child before it renames itself
                print(f"| {case} | {proc} | {base / 2**20:.1f} | {slope:.0f} |", flush=True)

main()
