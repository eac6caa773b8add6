#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Calibrates the plan's wall-time estimate and checks it against measured runs.

    bench/cost/cost_calibration.py BIN_DIR [--out FILE] [--only NAME ...]

Runs every example (long ones shortened with `--set time.end=T`, so that the
estimate covers the run that is measured) with `sadr run -q`, reads the plan's
estimate line ("about X of wall time") from stderr and the measured times from
run.json, and prints per example:

- the costs the estimate is built from, as measured: fluid wall time per
  particle and sub-step [ns] (timings_s.fluid_compute / (particles x
  fluid_substeps)), SSA time per event (ssa_nsm / ssa_events), graph rebuild
  per particle and coupling step (ssa_graph / (particles x steps)), frames per
  particle (output / (particles x frames));
- the estimated and the measured wall time of the coupling loop, and their
  ratio.

The medians per backend and dimension are the constants of
fluid_service/backends/*/NAME_schema.cpp (CostPerParticle) and
orchestrator/run/include/sadr/orchestrator/work_estimate.hpp.
"""
import argparse
import json
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
# Examples that take minutes or hours in full: the end time that keeps them to seconds.
SHORT_END = {
    "yeast_cell_channel": "0.05",
    "poiseuille_tracer_2d": "2.0",
    "open_channel_tracer": "1.0",
    "annihilation_1d_stochastic_n65": "4.0",  # its last output time
    "annihilation_1d_stochastic_n33": "4.0",
    "natural_convection_ra1e4": "2.0",
    "natural_convection_ra1e5": "1.0",
    "natural_convection_ra1e6": "0.5",
    "natural_convection_ra1e4_stochastic": "2.0",
    "natural_convection_ra1e5_stochastic": "1.0",
    "natural_convection_ra1e6_stochastic": "0.5",
    "coagulation_cascade": "0.006",
    "coagulation_cascade_prescribed": "0.05",
    "coagulation_cascade_sdpd": "0.0016",
}
UNITS = [(86400, "days"), (3600, "h"), (60, "min"), (1, "s")]


def seconds(text):
    value, unit = text.split()
    return float(value) * dict((u, f) for f, u in UNITS)[unit]


def run(bindir, scene, work):
    name = scene.stem
    out = work / name
    cmd = [str(bindir / "sadr"), "run", str(scene), "-o", str(out), "--force", "--no-progress"]
    if name in SHORT_END:
        cmd += ["--set", f"time.end={SHORT_END[name]}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return {"name": name, "error": p.stderr.strip().splitlines()[-1:]}
    m = re.search(r"\((\d+) particles,", p.stderr)
    est = re.search(r"about ([0-9.e+-]+ (?:s|min|h|days)) of wall time", p.stderr)
    rj = json.loads((out / "run.json").read_text())
    t = rj.get("timings_s", {})
    n = int(m.group(1)) if m else 0
    row = {"name": name, "particles": n, "backend": rj["plan"].get("fluid_backend", "?"),
           "dimension": int(re.search(r"^dimension:\s*(\d)", scene.read_text(), re.M).group(1)),
           "estimated_s": seconds(est.group(1)) if est else None,
           "measured_s": t.get("coupling_loop", 0.0)}
    subs, steps, events = rj.get("fluid_substeps", 0), rj.get("steps", 0), rj.get("ssa_events", 0)
    frames = len(rj.get("frames", [])) if isinstance(rj.get("frames"), list) else rj.get("frames", 0)
    if n and subs:
        row["fluid_ns"] = 1e9 * t.get("fluid_compute", 0.0) / (n * subs)
    if events:
        row["event_ns"] = 1e9 * t.get("ssa_nsm", 0.0) / events
    if n and steps and t.get("ssa_graph", 0.0) > 0:
        row["graph_ns"] = 1e9 * t["ssa_graph"] / (n * steps)
    if n and frames:
        row["frame_ns"] = 1e9 * t.get("output", 0.0) / (n * frames)
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bindir", type=pathlib.Path)
    ap.add_argument("--out", type=pathlib.Path)
    ap.add_argument("--only", nargs="*", default=[])
    a = ap.parse_args()
    scenes = sorted((ROOT / "examples").glob("*.yaml"))
    if a.only:
        scenes = [s for s in scenes if s.stem in a.only]
    rows = []
    with tempfile.TemporaryDirectory(prefix="sadr-cost-") as w:
        for s in scenes:
            r = run(a.bindir.resolve(), s, pathlib.Path(w))
            rows.append(r)
            print(json.dumps(r), flush=True)
    print("\n| example | backend | d | particles | fluid ns/particle-substep | SSA ns/event | "
          "graph ns/particle-step | estimated | measured | estimated/measured |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fmt = lambda v, f="%.0f": f % v if v is not None else "-"
    for r in rows:
        if "error" in r:
            print(f"| {r['name']} | failed: {r['error']} |")
            continue
        ratio = (r["estimated_s"] / r["measured_s"]
                 if r.get("estimated_s") and r["measured_s"] > 0 else None)
        print(f"| {r['name']} | {r['backend']} | {r['dimension']} | {r['particles']} | "
              f"{fmt(r.get('fluid_ns'))} | {fmt(r.get('event_ns'))} | {fmt(r.get('graph_ns'))} | "
              f"{fmt(r.get('estimated_s'), '%.3g s')} | {fmt(r['measured_s'], '%.3g s')} | "
              f"{fmt(ratio, '%.2f')} |")
    for key in ("fluid_ns", "event_ns", "graph_ns", "frame_ns"):
        groups = {}
        for r in rows:
            if key in r:
                groups.setdefault((r["backend"] if key == "fluid_ns" else "all",
                                   r["dimension"]), []).append(r[key])
        for g, v in sorted(groups.items()):
            print(f"median {key} {g}: {statistics.median(v):.0f} (n = {len(v)})")
    if a.out:
        a.out.write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main())
