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
of the fluid and SSA call times plus the state read (`transfer`). These are
wall times of stages that overlap (the SSA step k runs beside the fluid step
k + 1 unless --no-overlap): on 2 cores each includes the time it waited for a
core the other stage held, and "total" (their sum) can exceed the loop's wall
time per step, printed last as "wall" (run.json `coupling_loop` / steps).

Overlap (--compare-overlap P): P interleaved pairs per size and mode, the
sequential loop (--no-overlap) then the overlapped one (--overlap: SSA step k
on a worker thread while the fluid computes step k+1). Per loop: wall ms per
coupling step (run.json `coupling_loop` / steps, frames and checkpoints
included) and the exposed SSA + transfer share = `ssa_wait` / `coupling_loop`
(`ssa_wait`: time the main thread spent on SSA stages outside a fluid call,
i.e. the SSA time the overlap did not hide; sequential: the whole SSA stage).
The breakdown table then uses the sequential run with the smallest wall time.

Coupling step (--taus T ...): the per-step coupling cost (transfer, rebuild) is
paid once per coupling step, the fluid once per sub-step, so the share depends
on how many sub-steps the stability limits cut tau into (run.json
`fluid_substeps` / steps, printed). kappa stays 5 (about one jump per molecule
per 0.05) whatever tau. --fluid-only adds, interleaved with the other runs, the
same scene without the species (no ssa_service): its wall ms per step is what
the fluid alone costs, so coupled wall - fluid-only wall is the whole price of
the SSA (NSM included) on this machine.
Usage: coupled_step.py [--sadr build/release/bin/sadr] [--sizes 10000 100000] [--steps 20]
                       [--modes embedded processes] [--extra="--no-shared-memory"]
                       [--compare-overlap 3] [--extra="--fluid-threads 1 --ssa-threads 1"]
                       [--taus 0.05 0.1 0.2] [--fluid-only]
Writes bench/results/coupled_step.json and .md.
"""
import argparse, hashlib, json, math, os, shutil, statistics, subprocess, sys, tempfile

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
{species}time: {{coupling_step: {tau}, end: {end}}}
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
    ap.add_argument("--compare-overlap", type=int, default=0, metavar="P",
                    help="P interleaved pairs --no-overlap / --overlap per size and mode")
    ap.add_argument("--taus", type=float, nargs="+", default=[0.05],
                    help="coupling steps (0.05: two SDPD sub-steps, acoustic limit just under 0.0375)")
    ap.add_argument("--fluid-only", action="store_true",
                    help="also run the scene without species (fluid alone), interleaved")
    a = ap.parse_args()
    kappa = 5.0  # 2D: per-molecule jump rate ~ 4 kappa / dx^2 -> ~1 jump per molecule per 0.05
    species = f"species:\n  - {{name: A, diffusivity: {kappa}, initial: [{{region: all, count: 1}}]}}\n"
    rows = []
    for n, tau, mode in [(n, t, m) for n in a.sizes for t in a.taus for m in a.modes]:
        L = int(round(math.sqrt(n)))
        work = tempfile.mkdtemp(prefix="sadr-coupled-")
        scene = os.path.join(work, "scene.yaml")
        fluid_scene = os.path.join(work, "fluid_only.yaml")
        for path, sp in ((scene, species), (fluid_scene, "")):
            with open(path, "w") as f:
                f.write(SCENE.format(n=L * L, L=float(L), species=sp, tau=tau, end=tau * a.steps))
        fluid_walls = []

        def run_fluid_only():
            cmd = [a.sadr, "run", fluid_scene, "-q", "-o", os.path.join(work, "fluid"), "--force"]
            if mode == "embedded":
                cmd.append("--embedded")
            subprocess.run(cmd + a.extra.split(), check=True, stderr=subprocess.DEVNULL)
            with open(os.path.join(work, "fluid", "run.json")) as f:
                fluid_walls.append(1e3 * json.load(f)["timings_s"]["coupling_loop"] / a.steps)

        def run(loop_flags):
            cmd = [a.sadr, "run", scene, "-q", "-o", os.path.join(work, "out"), "--force"]
            if mode == "embedded":
                cmd.append("--embedded")
            cmd += a.extra.split() + loop_flags
            subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
            with open(os.path.join(work, "out", "run.json")) as f:
                j = json.load(f)
            frames = sorted(os.listdir(os.path.join(work, "out", "frames")))
            with open(os.path.join(work, "out", "frames", frames[-1]), "rb") as f:
                digests.add(hashlib.sha256(f.read()).hexdigest())
            substeps.append(j.get("fluid_substeps", 0) / a.steps)
            return j["timings_s"], j.get("overlapped_steps", 0)

        digests = set()  # of the last frame: every run must give the same bytes
        substeps = []  # fluid sub-steps per coupling step, per run

        overlap = None
        if a.compare_overlap > 0:
            runs = {"sequential": [], "overlapped": []}
            for _ in range(a.compare_overlap):  # interleaved: seq, ovl, (fluid), seq, ...
                runs["sequential"].append(run(["--no-overlap"]))
                runs["overlapped"].append(run(["--overlap"]))
                if a.fluid_only:
                    run_fluid_only()
            overlap = {}
            for loop, rs in runs.items():
                walls = [1e3 * t.get("coupling_loop", 0.0) / a.steps for t, _ in rs]
                shares = [t.get("ssa_wait", 0.0) / t["coupling_loop"] for t, _ in rs]
                overlap[loop] = {"wall_ms_per_step": walls, "wall_min": min(walls),
                                 "wall_median": statistics.median(walls),
                                 "exposed_ssa_transfer_share": shares,
                                 "exposed_share_median": statistics.median(shares),
                                 "overlapped_steps": rs[0][1]}
            overlap["identical_frames"] = len(digests) == 1
            if len(digests) != 1:
                print(f"WARNING: N={L*L} {mode}: the runs' last frames differ ({len(digests)} versions)",
                      file=sys.stderr, flush=True)
            best = min(runs["sequential"], key=lambda r: r[0].get("coupling_loop", 0.0))
            t = best[0]
        else:
            t, _ = run([])
            if a.fluid_only:
                run_fluid_only()
        steps = a.steps
        fluid = t.get("fluid_compute", 0.0)
        graph = t.get("ssa_graph", 0.0)
        nsm = t.get("ssa_nsm", 0.0)
        transfer = t.get("transfer", 0.0) + (t.get("fluid", 0.0) - fluid) + (t.get("ssa", 0.0) - graph - nsm)
        total = fluid + graph + nsm + transfer
        row = {"particles": L * L, "tau": tau, "substeps_per_step": max(substeps), "mode": mode,
               "steps": steps,
               "ms_per_step": {k: 1e3 * v / steps for k, v in
                               {"fluid": fluid, "transfer": transfer, "graph_rebuild": graph, "nsm": nsm, "total": total}.items()},
               "transfer_plus_rebuild_share": (transfer + graph) / total,
               # the loop's wall time: not the column sum when the SSA overlaps the fluid
               "wall_ms_per_step": 1e3 * t.get("coupling_loop", 0.0) / steps}
        if overlap:
            row["overlap"] = overlap
        if fluid_walls:
            row["fluid_only_wall_ms_per_step"] = fluid_walls
            row["fluid_only_wall_median"] = statistics.median(fluid_walls)
        rows.append(row)
        shutil.rmtree(work, ignore_errors=True)  # the runs' scenes and outputs: read above
        m = row["ms_per_step"]
        print(f"N={L*L:7d} tau {tau:g} ({row['substeps_per_step']:g} sub-steps) {mode:9s}  fluid {m['fluid']:8.2f}  transfer {m['transfer']:7.2f}  rebuild {m['graph_rebuild']:7.2f}"
              f"  nsm {m['nsm']:7.2f}  total {m['total']:8.2f} ms/step   transfer+rebuild = {100*row['transfer_plus_rebuild_share']:.1f}%"
              f"  (target: embedded <= 5%, processes <= 15% at 1e4)  wall {row['wall_ms_per_step']:.2f} ms/step", flush=True)
        if overlap:
            for loop, o in overlap.items():
                if loop == "identical_frames":
                    continue
                print(f"    {loop:10s} wall ms/step min {o['wall_min']:8.2f} median {o['wall_median']:8.2f}"
                      f"  exposed ssa+transfer {100*o['exposed_share_median']:.1f}%"
                      f"  (overlapped steps {o['overlapped_steps']})", flush=True)
        if fluid_walls:
            print(f"    fluid only wall ms/step min {min(fluid_walls):8.2f} median {row['fluid_only_wall_median']:8.2f}",
                  flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "coupled_step.json"), "w") as f:
        json.dump({"command": " ".join(sys.argv), "cores": os.cpu_count(), "rows": rows}, f, indent=2)
    with open(os.path.join(a.out, "coupled_step.md"), "w") as f:
        f.write(f"# Coupled step breakdown\n\nCommand: `{' '.join(sys.argv)}`\n\n")
        f.write("| particles | tau (sub-steps) | mode | fluid ms | transfer ms | rebuild ms | NSM ms | total ms | transfer+rebuild | wall ms |\n|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            m = r["ms_per_step"]
            f.write(f"| {r['particles']} | {r['tau']:g} ({r['substeps_per_step']:g}) | {r['mode']} | {m['fluid']:.2f} | {m['transfer']:.2f} | {m['graph_rebuild']:.2f} | {m['nsm']:.2f} | {m['total']:.2f} | {100*r['transfer_plus_rebuild_share']:.1f}% | {r['wall_ms_per_step']:.2f} |\n")
        f.write("\nTargets (issue 5): transfer + rebuild <= 5% of the step embedded, <= 15% with processes, at 1e4 particles.\n"
                "Columns are stage times (overlapping when the SSA runs beside the fluid); wall = the loop's wall time per step.\n")
        if any("overlap" in r for r in rows):
            f.write("\n## Sequential vs overlapped loop (interleaved pairs)\n\n"
                    "Wall ms per coupling step = run.json coupling_loop / steps; exposed = ssa_wait / coupling_loop "
                    "(SSA + transfer time not hidden behind the fluid).\n\n"
                    "| particles | tau (sub-steps) | mode | loop | wall ms/step min | median | runs | exposed SSA+transfer (median) |\n"
                    "|---|---|---|---|---|---|---|---|\n")
            for r in rows:
                for loop, o in r.get("overlap", {}).items():
                    if loop == "identical_frames":
                        continue
                    f.write(f"| {r['particles']} | {r['tau']:g} ({r['substeps_per_step']:g}) | {r['mode']} | {loop} | {o['wall_min']:.2f} | {o['wall_median']:.2f} | "
                            f"{', '.join(f'{w:.2f}' for w in o['wall_ms_per_step'])} | {100*o['exposed_share_median']:.1f}% |\n")
                if "fluid_only_wall_ms_per_step" in r:
                    w = r["fluid_only_wall_ms_per_step"]
                    f.write(f"| {r['particles']} | {r['tau']:g} ({r['substeps_per_step']:g}) | {r['mode']} | fluid only | "
                            f"{min(w):.2f} | {statistics.median(w):.2f} | {', '.join(f'{x:.2f}' for x in w)} | - |\n")


if __name__ == "__main__":
    main()
