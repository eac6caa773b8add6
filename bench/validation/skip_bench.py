#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Run time of a scene with and without a skip of the plan, in interleaved pairs.

The skip measured here is "coupling step skipped: nothing moves; SSA advances
frame to frame" (orchestrator/run plan.cpp, splitting.hpp FrameToFrame). The
build without it is any build from before it (by default the session-start
release build, /work/baseline/build/release/bin); the build with it is this
tree's. Pairs alternate which build runs first. Cost is the CPU time (user +
sys) of sadr and its services (measure.py); wall time is reported too.
The frames of the two builds are compared byte by byte in every pair.

    bench/validation/skip_bench.py [--without BIN] [--with BIN] [--pairs 5]
        [--scene examples/annihilation_1d_stochastic.yaml ...] [--out bench/results]

Writes <out>/skip_frame_to_frame.json and .md.
"""
import argparse
import hashlib
import json
import pathlib
import shutil
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, commit, median, run_measured  # noqa: E402


def frames_digest(out: pathlib.Path) -> str:
    h = hashlib.sha256()
    for p in sorted((out / "frames").iterdir()):
        h.update(p.name.encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--without", default="/work/baseline/build/release/bin")
    ap.add_argument("--with", dest="with_", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--scene", nargs="+",
                    default=[str(ROOT / "examples/annihilation_1d_stochastic.yaml")])
    ap.add_argument("--out", default=str(ROOT / "bench/results"))
    a = ap.parse_args()
    builds = {"without": pathlib.Path(a.without), "with": pathlib.Path(a.with_)}
    work = pathlib.Path(tempfile.mkdtemp(prefix="sadr-skip-"))
    results = []
    for scene in a.scene:
        runs = {"without": [], "with": []}
        identical = True
        for k in range(a.pairs):
            order = ["without", "with"] if k % 2 == 0 else ["with", "without"]
            digests = {}
            for name in order:
                out = work / name
                shutil.rmtree(out, ignore_errors=True)
                r = run_measured([builds[name] / "sadr", "run", scene, "-q", "--force", "-o", out],
                                 log=work / f"{name}.log")
                if r["rc"] != 0:
                    sys.exit(f"{name}: exit {r['rc']}: {(work / f'{name}.log').read_text()}")
                manifest = json.loads((out / "run.json").read_text())
                r["steps"] = manifest.get("steps")
                r["frame_to_frame"] = manifest.get("plan", {}).get("frame_to_frame", False)
                runs[name].append(r)
                digests[name] = frames_digest(out)
            identical = identical and digests["with"] == digests["without"]
        row = {"scene": str(pathlib.Path(scene).resolve().relative_to(ROOT))
               if pathlib.Path(scene).resolve().is_relative_to(ROOT) else scene,
               "frames_identical": identical, "pairs": a.pairs}
        for name in runs:
            row[name] = {"cpu_s_median": median([r["cpu_s"] for r in runs[name]]),
                         "wall_s_median": median([r["wall_s"] for r in runs[name]]),
                         "cpu_s": [r["cpu_s"] for r in runs[name]],
                         "steps": runs[name][0]["steps"],
                         "frame_to_frame": runs[name][0]["frame_to_frame"]}
        row["cpu_ratio_per_pair"] = [w["cpu_s"] / x["cpu_s"]
                                     for w, x in zip(runs["without"], runs["with"])]
        results.append(row)
        print(f"{row['scene']}: CPU without {row['without']['cpu_s_median']:.3f} s "
              f"({row['without']['steps']} steps), with {row['with']['cpu_s_median']:.3f} s "
              f"({row['with']['steps']} steps), ratio per pair "
              + ", ".join(f"{x:.2f}" for x in row["cpu_ratio_per_pair"])
              + f"; frames identical: {identical}", flush=True)
    shutil.rmtree(work, ignore_errors=True)
    meta = {"command": " ".join(sys.argv), "commit": commit(), "builds": {k: str(v) for k, v in builds.items()},
            "cost": "CPU time user+sys of sadr and its services (os.wait4), median of the pairs",
            "results": results}
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "skip_frame_to_frame.json").write_text(json.dumps(meta, indent=2) + "\n")
    with open(out / "skip_frame_to_frame.md", "w") as f:
        f.write("# Skip: coupling step when nothing moves (SSA frame to frame)\n\n")
        f.write(f"Command: `{meta['command']}` at {meta['commit']}. {meta['cost']}; "
                f"{a.pairs} interleaved pairs (the order alternates).\n\n")
        f.write("| scene | steps without / with | CPU s without | CPU s with | ratio per pair "
                "| wall s without / with | frames identical |\n|---|---|---|---|---|---|---|\n")
        for r in results:
            f.write(f"| `{r['scene']}` | {r['without']['steps']} / {r['with']['steps']} "
                    f"| {r['without']['cpu_s_median']:.3f} | {r['with']['cpu_s_median']:.3f} | "
                    + ", ".join(f"{x:.2f}" for x in r["cpu_ratio_per_pair"])
                    + f" | {r['without']['wall_s_median']:.2f} / {r['with']['wall_s_median']:.2f} "
                    f"| {'yes' if r['frames_identical'] else 'NO'} |\n")


if __name__ == "__main__":
    main()
