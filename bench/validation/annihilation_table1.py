#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""drawert2019 Table 1, SSA column: 1D A + B -> 0 between Dirichlet reservoirs.

Runs `sadr run` with R realizations per particle count, reads the ensemble
mean of the last frame (steady state), and computes the paper's metric
    eps = ||u_A - u_ref||_2 / (Np - 1),  u_A = E[X_A] / N_b  (interior particles),
against the 6th-order PDE reference at t = inf (tests/data/refs/annihilation_1d_subset.csv,
from refs/annihilation_1d.py). Also reported (refs/README.md section 8): the
statistical noise level sqrt(sum s_i^2 / R) / N_b / (Np - 1) of that metric, and
the noise-corrected bias sqrt(max(0, ||.||^2 - sum s_i^2/R)) / N_b / (Np - 1).

Usage: annihilation_table1.py --sadr build/release/bin/sadr [--np 17 33 65]
       [--nb 1000] [--realizations 100] [--end 4] [--out bench/results]
Writes <out>/annihilation_table1.json and .md, and prints a table.
"""
import argparse, csv, json, math, os, re, shutil, subprocess, sys, tempfile, time

PAPER = {17: 7.285e-4, 33: 5.334e-4, 65: 6.644e-4}          # Table 1, eps_SSA (N_b = 1e4)
PAPER_TIME = "0.7-6 s per realization (the paper's code, measured on this machine type)"

SCENE = """name: ann{np}
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [false]}}
regions:
  - {{name: left_wall, shape: box, lower: [0.0], upper: [0.0]}}
  - {{name: right_wall, shape: box, lower: [1.0], upper: [1.0]}}
particles:
  spacing: {dx!r}
  density: 1.0
  fill:
    - {{region: left_wall, kind: wall}}
    - {{region: right_wall, kind: wall}}
    - {{kind: fluid}}
fluid: {{backend: static, h_over_dx: 1.8}}
species:
  - name: A
    diffusivity: 0.1
    boundaries:
      - {{region: left_wall, condition: dirichlet, count: {nb}}}
      - {{region: right_wall, condition: dirichlet, count: 0}}
  - name: B
    diffusivity: 0.1
    boundaries:
      - {{region: left_wall, condition: dirichlet, count: 0}}
      - {{region: right_wall, condition: dirichlet, count: {nb}}}
reactions:
  - {{name: annihilation, equation: "A + B -> 0", rate: 0.1}}
time: {{coupling_step: 0.05, end: {end}}}
output: {{times: [{end}], formats: [csv]}}
ssa: {{convention: symmetric}}
seed: {seed}
"""


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def reference(refs, np_, nb, t="inf"):
    """u_A = a/C0 at the particles at time t ("inf": steady state)."""
    def at(r):
        return r["t"] == "inf" if t == "inf" else r["t"] != "inf" and abs(float(r["t"]) - t) < 1e-12
    rows = [r for r in refs if int(r["Np"]) == np_ and float(r["Nb"]) == nb and at(r)]
    rows.sort(key=lambda r: float(r["x"]))
    if len(rows) != np_:
        sys.exit(f"no t={t} reference for Np={np_}, Nb={nb} in the reference file")
    return [float(r["uA"]) for r in rows]


def with_tolerance(scene_text, tolerance):
    """The Table 1 scene with the adaptive SSA at `tolerance` (None: the exact NSM)."""
    if tolerance is None:
        return scene_text
    old = "ssa: {convention: symmetric}"
    assert old in scene_text
    return scene_text.replace(old, "ssa: {convention: symmetric, method: adaptive, "
                                   f"tolerance: {tolerance!r}}}")


def run_ensemble(sadr, work, np_, nb, realizations, end, seed, tolerance=None):
    """Writes the Table 1 scene into `work` (the adaptive SSA at `tolerance`, None: exact)
    and runs `sadr run -r R` of it (CPU time by os.wait4); returns the measurement and the
    folder of each realization."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from measure import run_measured
    scene = os.path.join(work, "scene.yaml")
    with open(scene, "w") as f:
        f.write(with_tolerance(SCENE.format(np=np_, dx=1.0 / (np_ - 1), nb=int(nb), end=end,
                                            seed=seed), tolerance))
    out = os.path.join(work, "out")
    r = run_measured([sadr, "run", scene, "-r", str(realizations), "-q", "-o", out])
    if r["rc"]:
        sys.exit(f"sadr run failed (exit {r['rc']}) for Np={np_}, N_b={nb}")
    # sadr run -r 1 writes its one run into out/ itself
    return r, [os.path.join(out, f"realization_{k:04d}" if realizations > 1 else "")
               for k in range(realizations)]


def realization_errors(sadr, np_, nb, realizations, end=4.0, seed=2019, refs_path=None,
                       subsets=(2, 3, 5, 10, 20, 30, 50, 100), tolerance=None):
    """One `sadr run -r R` of the Table 1 scene; returns the paper metric of the
    ensemble mean over the first r realizations for each r in `subsets` (<= R),
    of one realization (r = 1), the CPU time of the whole run (sadr + services,
    os.wait4) and the number of realizations."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    refs = [] if refs_path is None else read_rows(refs_path)
    for name in ("annihilation_1d_subset.csv", "annihilation_1d_nb100_subset.csv"):
        if refs_path is None:
            refs += read_rows(os.path.join(root, "tests/data/refs", name))
    # t >= 4 s is steady to 1e-7 (refs/README.md section 4): compare with t = inf.
    ref = reference(refs, np_, nb, "inf" if end >= 4.0 else end)
    work = tempfile.mkdtemp(prefix=f"sadr-table1-{np_}-")
    try:
        r, run_dirs = run_ensemble(sadr, work, np_, nb, realizations, end, seed, tolerance)
        finals, events, leaped = [], [], []
        for run_dir in run_dirs:
            frames = os.path.join(run_dir, "frames")
            rows = read_rows(os.path.join(frames, sorted(os.listdir(frames))[-1]))
            rows.sort(key=lambda row: int(row["id"]))
            finals.append([float(row["A"]) for row in rows])
            with open(os.path.join(run_dir, "run.json")) as f:
                manifest = json.load(f)
            events.append(manifest["ssa_events"])  # reactions + diffusion jumps
            leaped.append(manifest.get("ssa_leaped_molecules", 0))  # adaptive SSA only
    finally:
        shutil.rmtree(work, ignore_errors=True)
    errors, noise = {}, {}
    grand = [sum(f[i] for f in finals) / realizations for i in range(np_)]
    var = [sum((f[i] - grand[i]) ** 2 for f in finals) / max(1, realizations - 1)
           for i in range(np_)]
    for n in sorted({1, *[s for s in subsets if s <= realizations], realizations}):
        mean = [sum(f[i] for f in finals[:n]) / n for i in range(np_)]
        err2 = sum((mean[i] / nb - ref[i]) ** 2 for i in range(1, np_ - 1))
        errors[n] = math.sqrt(err2) / (np_ - 1)
        # The metric's expected value from noise alone (refs/README.md section 8).
        noise[n] = math.sqrt(sum(var[i] / n for i in range(1, np_ - 1))) / nb / (np_ - 1)
    return {"Np": np_, "N_b": nb, "realizations": realizations, "end": end, "errors": errors,
            "noise": noise, "cpu_s": r["cpu_s"], "wall_s": r["wall_s"],
            "events_per_realization": sum(events) / len(events),
            "leaped_per_realization": sum(leaped) / len(leaped), "tolerance": tolerance}


# perf's shared objects and symbols, grouped into what a realization spends its CPU on.
PROFILE_GROUPS = [
    ("NSM events", lambda comm, dso, sym: dso == "ssa_service" and any(
        k in sym for k in ("NsmSolver", "EventTree", "RdmeState", "exponential", "ziggurat"))),
    ("SSA graph and model set-up", lambda comm, dso, sym: dso == "ssa_service" and any(
        k in sym for k in ("Graph", "graph", "Neighbor", "Model", "lucy"))),
    ("process start and exit (kernel: fork, exec, mmap, page faults, exit)",
     lambda comm, dso, sym: dso == "[kernel.kallsyms]"),
    ("dynamic linking (ld.so)", lambda comm, dso, sym: dso.startswith("ld-linux")),
    ("wire: protobuf, ZeroMQ, libsodium", lambda comm, dso, sym: any(
        dso.startswith(k) for k in ("libprotobuf", "libzmq", "libsodium", "libpgm"))),
    ("sadr: orchestration and frame output", lambda comm, dso, sym: dso in ("sadr", "exe") or
     dso.startswith("libyaml")),
    ("libc, libstdc++ and the rest", lambda comm, dso, sym: True),
]


def profile_split(cmd):
    """Runs cmd under `perf record` (user and kernel samples of the whole process tree) and
    returns {group: fraction of the samples} over PROFILE_GROUPS, or None without perf."""
    perf = shutil.which("perf")
    if not perf:
        return None
    work = tempfile.mkdtemp(prefix="sadr-table1-perf-")
    try:
        data = os.path.join(work, "perf.data")
        rec = subprocess.run([perf, "record", "-q", "-F", "5000", "-o", data, "--"] + cmd,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if rec.returncode:
            return None
        rep = subprocess.run([perf, "report", "-i", data, "--sort", "comm,dso,sym", "--stdio",
                              "-g", "none"], capture_output=True, text=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    split = {g: 0.0 for g, _ in PROFILE_GROUPS}
    for line in rep.stdout.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+(\S+)\s+(\S+)\s+\[.\]\s+(.*)$", line)
        if not m:
            continue
        pct, comm, dso, sym = float(m[1]), m[2], m[3], m[4]
        for g, match in PROFILE_GROUPS:
            if match(comm, dso, sym):
                split[g] += pct / 100.0
                break
    return split


def cost_split(sadr, np_, nb, realizations, end=1.0, seed=2019):
    """Where the CPU time of a realization goes: one `sadr run -r R` of the Table 1 scene
    (N_b = 0: no molecules, the fixed cost of a realization), CPU per realization and events
    per realization from each run.json, and, where perf exists, the split of a second,
    profiled run over PROFILE_GROUPS."""
    work = tempfile.mkdtemp(prefix=f"sadr-table1-split-{np_}-")
    try:
        r, run_dirs = run_ensemble(sadr, work, np_, nb, realizations, end, seed)
        events = []
        for run_dir in run_dirs:
            with open(os.path.join(run_dir, "run.json")) as f:
                events.append(json.load(f)["ssa_events"])
        split = profile_split([sadr, "run", os.path.join(work, "scene.yaml"), "-r",
                               str(realizations), "-q", "-o", os.path.join(work, "out_perf")])
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return {"Np": np_, "N_b": nb, "realizations": realizations, "end": end,
            "cpu_s_per_realization": r["cpu_s"] / realizations,
            "events_per_realization": sum(events) / len(events), "profile": split}


def tau_independence(sadr, np_=17, nb=1e3, taus=(0.0125, 0.05, 0.2), end=1.0, seed=2019):
    """Where tau matters in Table 1's SSA column: one realization of the scene at
    each coupling step tau; returns the sha256 of every frame per tau and whether
    they are identical (the plan advances a static SSA-only scene frame to frame,
    so tau should not enter), with the CPU time of each run."""
    import hashlib
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from measure import run_measured
    work = tempfile.mkdtemp(prefix="sadr-table1-tau-")
    try:
        scene = os.path.join(work, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE.format(np=np_, dx=1.0 / (np_ - 1), nb=int(nb), end=end, seed=seed))
        rows = []
        for tau in taus:
            out = os.path.join(work, f"tau{tau!r}")
            r = run_measured([sadr, "run", scene, "-q", "-o", out, "--set",
                              f"time.coupling_step={tau!r}"])
            if r["rc"]:
                sys.exit(f"sadr run failed (exit {r['rc']}) at tau = {tau}")
            frames = os.path.join(out, "frames")
            digest = [hashlib.sha256(open(os.path.join(frames, n), "rb").read()).hexdigest()
                      for n in sorted(os.listdir(frames)) if n.endswith(".csv")]
            rows.append({"tau": tau, "frames_sha256": digest, "cpu_s": r["cpu_s"]})
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return {"Np": np_, "N_b": nb, "end": end, "rows": rows,
            "identical": all(x["frames_sha256"] == rows[0]["frames_sha256"] for x in rows)}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sadr", default=os.path.join(root, "build/release/bin/sadr"))
    ap.add_argument("--np", type=int, nargs="+", default=[17, 33, 65])
    ap.add_argument("--nb", type=float, default=1000)
    ap.add_argument("--realizations", type=int, default=100)
    ap.add_argument("--end", type=float, default=4.0)
    ap.add_argument("--seed", type=int, default=2019)
    ap.add_argument("--refs", default=os.path.join(root, "tests/data/refs/annihilation_1d_subset.csv"))
    ap.add_argument("--out", default=os.path.join(root, "bench/results"))
    a = ap.parse_args()
    refs = read_rows(a.refs)
    results = []
    for np_ in a.np:
        work = tempfile.mkdtemp(prefix=f"sadr-table1-{np_}-")
        scene = os.path.join(work, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE.format(np=np_, dx=1.0 / (np_ - 1), nb=int(a.nb), end=a.end, seed=a.seed))
        out = os.path.join(work, "out")
        t0 = time.time()
        subprocess.run([a.sadr, "run", scene, "-r", str(a.realizations), "-q", "-o", out], check=True)
        cleanup = work
        wall = time.time() - t0
        frames = sorted(os.listdir(os.path.join(out, "ensemble")))
        rows = read_rows(os.path.join(out, "ensemble", frames[-1]))
        rows.sort(key=lambda r: int(r["id"]))
        ref = reference(refs, np_, a.nb)
        interior = range(1, np_ - 1)
        R = int(rows[1]["realizations"])
        err2 = sum((float(rows[i]["A_mean"]) / a.nb - ref[i]) ** 2 for i in interior)
        noise2 = sum(float(rows[i]["A_var"]) / R for i in interior) / a.nb ** 2
        n = np_ - 1
        res = {"Np": np_, "N_b": a.nb, "C0": a.nb * (np_ - 1), "realizations": R, "t": a.end,
               "eps": math.sqrt(err2) / n, "noise": math.sqrt(noise2) / n,
               "bias": math.sqrt(max(0.0, err2 - noise2)) / n,
               "paper_eps": PAPER.get(np_), "wall_s": wall, "wall_s_per_realization": wall / R}
        results.append(res)
        shutil.rmtree(cleanup, ignore_errors=True)
        print(f"Np={np_:3d}  eps={res['eps']:.3e} (noise {res['noise']:.2e}, bias {res['bias']:.2e})"
              f"  paper {res['paper_eps']:.3e}   wall {wall:.1f} s for {R} realizations", flush=True)
    os.makedirs(a.out, exist_ok=True)
    meta = {"command": " ".join(sys.argv), "metric": "||E[X_A]/N_b - u_ref||_2/(Np-1), interior, t=end vs PDE t=inf",
            "cores": os.cpu_count(), "paper_time": PAPER_TIME, "results": results}
    with open(os.path.join(a.out, "annihilation_table1.json"), "w") as f:
        json.dump(meta, f, indent=2)
    with open(os.path.join(a.out, "annihilation_table1.md"), "w") as f:
        f.write(f"# drawert2019 Table 1, SSA column\n\nCommand: `{meta['command']}`\n\n")
        f.write(f"Metric: {meta['metric']}. N_b = {a.nb:g} molecules per boundary particle.\n\n")
        f.write("| Np | eps (ours) | noise level | bias (noise-corrected) | paper eps_SSA (N_b = 1e4) | wall s / realization |\n|---|---|---|---|---|---|\n")
        for r in results:
            f.write(f"| {r['Np']} | {r['eps']:.2e} | {r['noise']:.2e} | {r['bias']:.2e} | {r['paper_eps']:.2e} | {r['wall_s_per_realization']:.3f} |\n")
        f.write(f"\nPeer: {PAPER_TIME}. Ours: {os.cpu_count()} cores, realizations in parallel.\n")


if __name__ == "__main__":
    main()
