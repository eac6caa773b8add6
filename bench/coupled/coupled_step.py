#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Coupled-step benchmark (issue 5): time per coupling step split into fluid
compute, transfer (serialise + send + parse, both directions), SSA graph
rebuild and NSM, for 1e4 and 1e5 particles, embedded vs child processes.

Scene: 2D periodic box of SDPD fluid at rest with thermal noise (particles
move every step, so the SSA graph is rebuilt every step), h = 3 dx, one
stochastic tracer with one molecule per voxel and kappa chosen for about one
jump per molecule per coupling step; tau = 0.05, which the SDPD acoustic limit
0.25 (h/2) / c0 = 0.0375 splits into two fluid sub-steps.

Timings come from run.json: `fluid_compute` (backend advance inside the
service), `ssa_graph` and `ssa_nsm` (inside ssa_service); transfer = the rest
of the fluid and SSA call times plus the state read (`transfer`).
Usage: coupled_step.py [--sadr build/release/bin/sadr] [--sizes 10000 100000] [--steps 20]
                       [--modes embedded processes] [--extra="--no-shared-memory"]
Writes bench/results/coupled_step.json and .md.
"""
import argparse, json, math, os, subprocess, sys, tempfile

SCENE = """name: coupled_bench_{n}
dimension: 2
box: {{lower: [0.0, 0.0], upper: [{L}, {L}], periodic: [true, true]}}
particles: {{spacing: 1.0, density: 1.0}}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  reference_density: 1.0
  sound_speed: 10.0
  shear_viscosity: 1.0
  temperature: 0.001
species:
  - {{name: A, diffusivity: {kappa}, initial: [{{region: all, count: 1}}]}}
time: {{coupling_step: {tau}, end: {end}}}
output: {{times: [{end}], formats: [csv]}}
seed: 1
"""


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sadr", default=os.path.join(root, "build/release/bin/sadr"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[10000, 100000])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--out", default=os.path.join(root, "bench/results"))
    ap.add_argument("--modes", nargs="+", default=["embedded", "processes"],
                    choices=["embedded", "processes"])
    ap.add_argument("--extra", default="", help="more sadr run options, e.g. --no-shared-memory")
    a = ap.parse_args()
    tau = 0.05  # two SDPD sub-steps: acoustic limit 0.25 (h/2) / c0 = 0.0375
    kappa = 1.0 / (4 * tau)  # 2D: per-molecule jump rate ~ 4 kappa / dx^2 -> ~1 jump per step
    rows = []
    for n in a.sizes:
        L = int(round(math.sqrt(n)))
        for mode in a.modes:
            work = tempfile.mkdtemp(prefix="sadr-coupled-")
            scene = os.path.join(work, "scene.yaml")
            with open(scene, "w") as f:
                f.write(SCENE.format(n=L * L, L=float(L), kappa=kappa, tau=tau, end=tau * a.steps))
            cmd = [a.sadr, "run", scene, "-q", "-o", os.path.join(work, "out")]
            if mode == "embedded":
                cmd.append("--embedded")
            cmd += a.extra.split()
            subprocess.run(cmd, check=True)
            with open(os.path.join(work, "out", "run.json")) as f:
                t = json.load(f)["timings_s"]
            steps = a.steps
            fluid = t.get("fluid_compute", 0.0)
            graph = t.get("ssa_graph", 0.0)
            nsm = t.get("ssa_nsm", 0.0)
            transfer = t.get("transfer", 0.0) + (t.get("fluid", 0.0) - fluid) + (t.get("ssa", 0.0) - graph - nsm)
            total = fluid + graph + nsm + transfer
            row = {"particles": L * L, "mode": mode, "steps": steps,
                   "ms_per_step": {k: 1e3 * v / steps for k, v in
                                   {"fluid": fluid, "transfer": transfer, "graph_rebuild": graph, "nsm": nsm, "total": total}.items()},
                   "transfer_plus_rebuild_share": (transfer + graph) / total}
            rows.append(row)
            m = row["ms_per_step"]
            print(f"N={L*L:7d} {mode:9s}  fluid {m['fluid']:8.2f}  transfer {m['transfer']:7.2f}  rebuild {m['graph_rebuild']:7.2f}"
                  f"  nsm {m['nsm']:7.2f}  total {m['total']:8.2f} ms/step   transfer+rebuild = {100*row['transfer_plus_rebuild_share']:.1f}%"
                  f"  (target: embedded <= 5%, processes <= 15% at 1e4)", flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "coupled_step.json"), "w") as f:
        json.dump({"command": " ".join(sys.argv), "cores": os.cpu_count(), "rows": rows}, f, indent=2)
    with open(os.path.join(a.out, "coupled_step.md"), "w") as f:
        f.write(f"# Coupled step breakdown\n\nCommand: `{' '.join(sys.argv)}`\n\n")
        f.write("| particles | mode | fluid ms | transfer ms | rebuild ms | NSM ms | total ms | transfer+rebuild |\n|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            m = r["ms_per_step"]
            f.write(f"| {r['particles']} | {r['mode']} | {m['fluid']:.2f} | {m['transfer']:.2f} | {m['graph_rebuild']:.2f} | {m['nsm']:.2f} | {m['total']:.2f} | {100*r['transfer_plus_rebuild_share']:.1f}% |\n")
        f.write("\nTargets (issue 5): transfer + rebuild <= 5% of the step embedded, <= 15% with processes, at 1e4 particles.\n")


if __name__ == "__main__":
    main()
