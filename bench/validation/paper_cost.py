#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""drawert2019 Table 1: the paper code's cost per realization, measured on this machine beside ours.

The paper's public code (github briandrawert/hybrid_SSA_SDPD, a LAMMPS fork; built on this
machine, never part of this repository) runs the authors' own Table 1 inputs,
examples/ssa_tsdpd/cylinder_annihilation/temporal_analysis/{17,33,65}x1/cylinder_annihilation.lmp
(1D A + B -> 0 between reservoirs, N_b = 1000, D = 0.1, k = 0.1, h = 1.8 dx, 10,000 steps of
1e-4 s: t = 1 s; both the tDPD and the SSA species, as the authors ran it). One change is made
to a deck: its `dump ... ssa_tsdpd/vtk` line is dropped (the VTK writer needs a VTK library the
build here leaves out; it writes 5 frames, not part of the cost compared).

Each pair runs the paper code's realization and ours of the same problem (`sadr run` of
annihilation_table1.SCENE at N_b = 1e3, t = 1 s, one realization), the order alternating from
pair to pair; CPU time (user + sys of the whole process tree, os.wait4). The medians replace the
constant report.py carried before (PAPER_COST_ONE).

    bench/validation/paper_cost.py --lmp /path/to/lmp_mpi --decks /path/to/temporal_analysis \\
        [--sadr build/release/bin/sadr] [--pairs 5] [--np 17 33 65] [--out bench/results/paper_cost]
"""
import argparse
import datetime
import json
import os
import pathlib
import re
import statistics
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, commit, run_measured  # noqa: E402
import annihilation_table1  # noqa: E402

DECK = "{n}x1/cylinder_annihilation.lmp"


def paper_deck(decks, n, work):
    """The authors' deck for N = n, copied into `work` without its VTK dump; returns its path."""
    src = pathlib.Path(decks) / DECK.format(n=n)
    text = src.read_text()
    kept = [line for line in text.splitlines() if not re.match(r"\s*dump(_modify)?\s", line)]
    if len(kept) == len(text.splitlines()):
        raise SystemExit(f"{src}: no dump line found (not the authors' deck?)")
    if not re.search(rf"variable\s+Np\s+equal\s+{n}\b", text):
        raise SystemExit(f"{src}: does not set Np = {n}")
    path = pathlib.Path(work) / f"paper_{n}.lmp"
    path.write_text("\n".join(kept) + "\n")
    return path


def our_scene(n, work):
    path = pathlib.Path(work) / f"ours_{n}.yaml"
    path.write_text(annihilation_table1.SCENE.format(np=n, dx=1.0 / (n - 1), nb=1000, end=1.0,
                                                     seed=7))
    return path


def measure(lmp, decks, sadr, ns=(17, 33, 65), pairs=5):
    """{N: {"paper_cpu_s": [...], "ours_cpu_s": [...], medians, ratio}} from interleaved pairs."""
    work = tempfile.mkdtemp(prefix="sadr-paper-cost-")
    out = {}
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for n in ns:
        deck, scene = paper_deck(decks, n, work), our_scene(n, work)
        paper_cmd = [lmp, "-in", deck.name, "-log", "none", "-screen", "none"]
        ours_cmd = [sadr, "run", scene, "-o", pathlib.Path(work) / f"out_{n}", "--force", "-q"]
        res = {"paper_cpu_s": [], "ours_cpu_s": [], "paper_cmd": " ".join(map(str, paper_cmd)),
               "ours_cmd": " ".join(map(str, ours_cmd))}
        for k in range(pairs):
            order = [("paper", paper_cmd), ("ours", ours_cmd)]
            for who, cmd in (order if k % 2 == 0 else order[::-1]):
                r = run_measured(cmd, cwd=work, env=env)
                if r["rc"] != 0:
                    raise SystemExit(f"{who} N={n} failed (exit {r['rc']}): {r['cmd']}")
                res[f"{who}_cpu_s"].append(r["cpu_s"])
        res["paper_median_s"] = statistics.median(res["paper_cpu_s"])
        res["ours_median_s"] = statistics.median(res["ours_cpu_s"])
        res["ratio_paper_over_ours"] = res["paper_median_s"] / res["ours_median_s"]
        out[n] = res
    return out


def load_average():
    return " ".join(pathlib.Path("/proc/loadavg").read_text().split()[:3])


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", required=True, help="the paper code's LAMMPS executable")
    ap.add_argument("--decks", required=True,
                    help="its examples/ssa_tsdpd/cylinder_annihilation/temporal_analysis folder")
    ap.add_argument("--sadr", default=str(ROOT / "build/release/bin/sadr"))
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--np", type=int, nargs="+", default=[17, 33, 65])
    ap.add_argument("--out", default=str(ROOT / "bench/results/paper_cost"))
    a = ap.parse_args()
    before = load_average()
    started = datetime.datetime.now(datetime.timezone.utc)
    res = measure(pathlib.Path(a.lmp).resolve(), a.decks, pathlib.Path(a.sadr).resolve(),
                  a.np, a.pairs)
    after = load_average()
    meta = {"commit": commit(), "utc": f"{started:%Y-%m-%d %H:%M}", "pairs": a.pairs,
            "load_before": before, "load_after": after,
            "command": "bench/validation/paper_cost.py " + " ".join(sys.argv[1:])}
    out = pathlib.Path(a.out)
    out.with_suffix(".json").write_text(json.dumps({"meta": meta, "cases": res}, indent=1) + "\n")
    L = ["# drawert2019 Table 1: the paper code's cost per realization, measured here", "",
         f"Generated by `{meta['command']}` at commit `{meta['commit']}` on {meta['utc']} UTC; "
         f"{a.pairs} interleaved pairs per N, CPU time of one realization (t = 1 s, N_b = 1e3), "
         f"load average {before} before, {after} after.", "",
         "| N | paper code, CPU s (min / median / max) | ours, CPU s (min / median / max) | "
         "paper / ours (medians) |", "|---|---|---|---|"]
    for n, r in res.items():
        p, o = r["paper_cpu_s"], r["ours_cpu_s"]
        L.append(f"| {n} | {min(p):.3g} / {r['paper_median_s']:.3g} / {max(p):.3g} | "
                 f"{min(o):.3g} / {r['ours_median_s']:.3g} / {max(o):.3g} | "
                 f"{r['ratio_paper_over_ours']:.3g} |")
    L += ["", "Commands (per pair, in the folder of the decks):", ""]
    L += [f"    {r['paper_cmd']}\n    {r['ours_cmd']}" for r in res.values()]
    out.with_suffix(".md").write_text("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
