#!/usr/bin/python3
"""The cost of reproduce.sh's runs (docs/natural-convection.md, "Cost"): for each NAME, CPU time
(user + sys of sadr and the services it launched) and wall time from OUT/NAME.time
(/usr/bin/time -v), simulated time, fluid sub-steps and SSA events from OUT/NAME/run.json (summed
over realizations), and the CPU time relative to a reference run (the deterministic one).

    /usr/bin/python3 bench/natural_convection/cost_table.py OUT NAME[=LABEL] ... [--relative-to NAME]
"""
import argparse
import glob
import json
import os
import re


def time_v(path):
    """user + sys seconds and the wall-clock string of a /usr/bin/time -v output."""
    text = open(path).read()
    get = lambda key: re.search(re.escape(key) + r":\s*(\S+)", text).group(1)  # noqa: E731
    return float(get("User time (seconds)")) + float(get("System time (seconds)")), \
        get("Elapsed (wall clock) time (h:mm:ss or m:ss)")


def run_stats(run):
    files = sorted(glob.glob(os.path.join(run, "realization_*", "run.json"))) or [os.path.join(run, "run.json")]
    substeps = events = 0
    t = []
    for f in files:
        with open(f) as fh:
            r = json.load(fh)
        substeps += r.get("fluid_substeps", 0)
        events += r.get("ssa_events", 0)
        t.append(r.get("time", float("nan")))
    return len(files), max(t), substeps, events


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("names", nargs="+")
    ap.add_argument("--relative-to", help="NAME of the run whose CPU time is 1")
    args = ap.parse_args()
    ref = time_v(os.path.join(args.out, args.relative_to + ".time"))[0] if args.relative_to else None
    print("| run | realizations | simulated time | fluid sub-steps | SSA events | CPU [s] | wall | CPU / reference |")
    print("|---|---|---|---|---|---|---|---|")
    for arg in args.names:
        name, _, label = arg.partition("=")
        cpu, wall = time_v(os.path.join(args.out, name + ".time"))
        n, t, sub, ev = run_stats(os.path.join(args.out, name))
        print("| %s | %d | %g | %d | %s | %.0f | %s | %s |" % (
            label or name, n, t, sub, "%.2e" % ev if ev else "-", cpu, wall,
            "%.2f" % (cpu / ref) if ref else "-"))


if __name__ == "__main__":
    main()
