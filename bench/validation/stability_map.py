#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Stability map: what sadr does when pushed past each stability rule.

Every cell is one `sadr run` of a variant of an example scene, classified by
what happened:
  runs     exit 0; the frames are checked for non-finite values, and the
           figure of merit of the cell (density band, centre-line speed, error
           against the smallest sub-step) is reported;
  refused  exit 1 (invalid scene/input) with the message;
  caught   exit 4 (numerical failure) with the diagnosis (step, particle, value);
  SILENT   exit 0 but non-finite or absurd values in the frames: a bug.
Axes: the fluid sub-step from 0.25x to 4x the acoustic, viscous, diffusion and
reaction limits (fluid.max_time_step with force_time_step; the limit is the
smallest one the same run meets with automatic sub-steps, from its run.json);
the sound speed from 3x to 100x the flow speed; diffusivity and rate over 6
decades, deterministic and stochastic; stochastic copy numbers from 0 to past
the largest accepted; jittered, clumped and sparse particles; one long run
(>= 1e6 sub-steps) with the drift of mass, momentum, kinetic temperature and
molecule count; the two tolerances (time.tolerance, ssa.tolerance) from 1e-1 to 1e-6, with
the error each run achieves and its cost.
The body-force limit 0.25 sqrt((h/2)/|a|) binds only when |a| > c0^2/(h/2),
i.e. when the hydrostatic density variation |a| H / c0^2 exceeds H/(h/2) (>> 1):
never in a weakly compressible scene, so it has no cell of its own.

    bench/validation/stability_map.py [--bin build/release/bin] [--out docs]
        [--long-steps 1000000]

Writes <out>/validation/stability_map.md, .json and .png.
"""
import argparse
import csv
import json
import math
import pathlib
import random
import re
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, commit, run_measured  # noqa: E402

EX = ROOT / "examples"


def sub(text, old, new):
    if old not in text:
        raise SystemExit(f"stability_map: '{old}' not in the scene")
    return text.replace(old, new, 1)


def read_frames(out):
    """Last CSV frame as a list of dicts (empty when none)."""
    frames = sorted((out / "frames").glob("*.csv")) if (out / "frames").exists() else []
    return list(csv.DictReader(open(frames[-1]))) if frames else [], len(frames)


def finite_and_max(rows, cols):
    bad, big = 0, {c: 0.0 for c in cols}
    for r in rows:
        for c in cols:
            if c not in r:
                continue
            x = float(r[c])
            if not math.isfinite(x):
                bad += 1
            else:
                big[c] = max(big[c], abs(x))
    return bad, big


def run_cell(bin_dir, work, name, text, extra=()):
    d = work / re.sub(r"\W", "_", name)
    d.mkdir(parents=True, exist_ok=True)
    (d / "scene.yaml").write_text(text)
    log = d / "log.txt"
    r = run_measured([bin_dir / "sadr", "run", d / "scene.yaml", "-q", "--force", "-o", d / "out",
                      *extra], log=log)
    msg = ""
    lines = log.read_text(errors="replace").splitlines()
    for i, line in enumerate(lines):
        if "error" in line.lower() or "failure" in line.lower() or "refus" in line.lower():
            msg = line.strip()
            # a heading ("...: 1 problem", "...work estimate:"): the reason is the next line
            if (msg.endswith(":") or re.search(r"\d+ problems?$", msg)) and i + 1 < len(lines):
                msg += " " + lines[i + 1].strip()
            break
    rows, nframes = read_frames(d / "out")
    manifest = {}
    if (d / "out" / "run.json").exists():
        manifest = json.loads((d / "out" / "run.json").read_text())
    outcome = {0: "runs", 1: "refused", 4: "caught"}.get(r["rc"], f"exit {r['rc']}")
    return {"cell": name, "outcome": outcome, "rc": r["rc"], "message": msg[:400],
            "cpu_s": r["cpu_s"], "rows": rows, "frames": nframes,
            "substeps": manifest.get("fluid_substeps"), "dir": str(d)}


def limit_of(bin_dir, work, name, text):
    """(name, value) of the smallest stability limit the run meets: one run with
    the automatic sub-steps, whose run.json names the smallest binding limit the
    fluid's sub-steps met (`fluid_smallest_limit`; the limits follow the state,
    so this is below the limit at t = 0 when e.g. the species fill in)."""
    c = run_cell(bin_dir, work, f"{name}_limit", text)
    manifest = pathlib.Path(c["dir"]) / "out" / "run.json"
    got = json.loads(manifest.read_text()).get("fluid_smallest_limit", {}) \
        if manifest.exists() else {}
    if "stable_time_step" not in got:
        raise SystemExit(f"no smallest limit in {manifest} for {name}: {c['message']!r}")
    return got["limiting_criterion"], float(got["stable_time_step"])


def figure(cell, kind):
    """A number that says whether a run that finished is sound."""
    rows = cell["rows"]
    if not rows:
        return "no frames"
    bad, big = finite_and_max(rows, ["vx", "vy", "vz", "density", "A", "B", "T"])
    if bad:
        cell["outcome"] = "SILENT"
        return f"{bad} non-finite values in the last frame"
    if kind == "fluid":
        rho = [float(r["density"]) for r in rows]
        return (f"density {min(rho):.4f}..{max(rho):.4f}, max |u| {max(big['vx'], big['vy']):.4g}")
    if kind == "species":
        return f"max A {big['A']:.6g}, max B {big['B']:.6g}"
    return ""


def substep_cells(bin_dir, work):
    cells = []
    pois = (EX / "poiseuille_tracer_2d.yaml").read_text()
    pois = sub(pois, "end: 10.0", "end: 1.0")
    viscous = pois
    acoustic = sub(pois, "shear_viscosity: 0.1", "shear_viscosity: 0.005")
    det = (EX / "annihilation_1d_deterministic.yaml").read_text()
    det = sub(det, "end: 4.0", "end: 1.0")
    det = sub(det, "times: [0.2, 0.4, 0.6, 0.8, 1.0, 2.0, 4.0]", "times: [1.0]")
    reaction = det
    diffusion = sub(det, "rate: 0.1}", "rate: 0.0001}")
    for case, text, kind in (("acoustic", acoustic, "fluid"), ("viscous", viscous, "fluid"),
                             ("diffusion", diffusion, "species"), ("reaction", reaction, "species")):
        name, lim = limit_of(bin_dir, work, case, text)
        ref = None
        for f in (0.25, 0.5, 1.0, 2.0, 4.0):
            t = sub(text, "fluid:\n", f"fluid:\n  max_time_step: {f * lim!r}\n  force_time_step: true\n")
            c = run_cell(bin_dir, work, f"substep {case} {f}x", t)
            c["axis"] = f"sub-step / {name} limit ({lim:.3g})"
            c["value"] = f"{f}x"
            c["figure"] = figure(c, kind)
            if c["outcome"] == "runs" and c["rows"]:
                key = "vx" if kind == "fluid" else "A"
                vals = [float(r[key]) for r in c["rows"]]
                if ref is None:
                    ref = vals
                else:
                    scale = max(abs(v) for v in ref) or 1.0
                    dev = max(abs(a - b) for a, b in zip(vals, ref)) / scale
                    c["figure"] += f"; max |{key} - {key}(0.25x)| / max = {dev:.2e}"
                    if dev > 0.05:  # wrong by more than 5 %: said, or silent?
                        log = (pathlib.Path(c["dir"]) / "log.txt").read_text(errors="replace")
                        warned = "force_time_step: sub-step" in log
                        c["outcome"] = "runs, wrong (warned)" if warned else "SILENT"
            cells.append(c)
    return cells


def sound_speed_cells(bin_dir, work):
    cells = []
    pois = (EX / "poiseuille_tracer_2d.yaml").read_text()
    for mult in (3, 10, 30, 100):
        t = sub(pois, "sound_speed: 1.0", f"sound_speed: {0.1 * mult!r}")
        c = run_cell(bin_dir, work, f"c0 {mult}x", t)
        c["axis"] = "c0 / u_max (u_max = 0.1, Poiseuille example to t = 10)"
        c["value"] = f"{mult}x"
        c["figure"] = figure(c, "fluid")
        if c["outcome"] == "runs" and c["rows"]:
            u = max(float(r["vx"]) for r in c["rows"] if r["kind"] == "0")
            c["figure"] += f"; centre-line u {u:.4f} ({(u - 0.1) / 0.1:+.2%} from 0.1)"
        cells.append(c)
    return cells


def decade_cells(bin_dir, work):
    cells = []
    det = (EX / "annihilation_1d_deterministic.yaml").read_text()
    det = sub(det, "end: 4.0", "end: 0.5")
    det = sub(det, "times: [0.2, 0.4, 0.6, 0.8, 1.0, 2.0, 4.0]", "times: [0.5]")
    sto = (EX / "annihilation_1d_stochastic.yaml").read_text()
    sto = sub(sto, "end: 4.0", "end: 0.2")
    sto = sub(sto, "times: [0.2, 0.4, 0.6, 0.8, 1.0, 2.0, 4.0]", "times: [0.2]")
    sto = sto.replace("count: 1000}", "count: 100}")
    for label, text, decades in (("deterministic", det, range(-3, 4)),
                                 ("stochastic (N_b = 100, t = 0.2)", sto, range(-3, 3))):
        for what, old, base in (("diffusivity", "diffusivity: 0.1", 0.1),
                                ("rate", "rate: 0.1}", 0.1)):
            for k in decades:
                v = base * 10.0**k
                new = f"{what}: {v!r}" + ("}" if what == "rate" else "")
                t = text.replace(old, new)
                c = run_cell(bin_dir, work, f"{label} {what} {v:g}", t)
                c["axis"] = f"{label}: {what} (example {base:g})"
                c["value"] = f"{v:g}"
                c["figure"] = figure(c, "species")
                if c.get("substeps"):
                    c["figure"] += f"; {c['substeps']} fluid sub-steps"
                cells.append(c)
    return cells


STATIC_SSA = """name: counts
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [true]}}
particles: {{spacing: 0.25, density: 1.0}}
fluid: {{backend: static, h_over_dx: 1.8}}
species:
  - {{name: A, diffusivity: 0.0, initial: [{{count: {count}}}]}}
reactions:
  - {{name: decay, equation: "A -> 0", rate: 1.0e-9}}
time: {{coupling_step: 0.01, end: 1.0e-7}}
output: {{times: [1.0e-7], formats: [csv]}}
seed: 1
"""


def copy_number_cells(bin_dir, work):
    cells = []
    for count in ("0", "1", "1000000", "1000000000000", "2251799813685248", "9007199254740992",
                  "9007199254740993", "1e18", "1e19", "1e300"):
        c = run_cell(bin_dir, work, f"count {count}", STATIC_SSA.format(count=count))
        c["axis"] = "stochastic copy number per particle (4 particles; 2^51 each = 2^53 in all)"
        c["value"] = count
        if c["outcome"] == "runs" and c["rows"]:
            got = [r["A"] for r in c["rows"]]
            c["figure"] = f"frame A = {got[0]} (asked {count})"
            try:
                if float(count) <= 2**53 and abs(float(got[0]) - float(count)) > 0.5 + 1e-9 * float(count):
                    c["outcome"] = "SILENT"
            except ValueError:
                pass
        else:
            c["figure"] = ""
        cells.append(c)
    return cells


ARRANGED = """name: arranged
dimension: 2
box: {lower: [0.0, 0.0], upper: [1.0, 1.0], periodic: [true, true]}
particles: {file: particles.csv}
fluid:
  backend: sdpd
  smoothing_length: 0.15
  reference_density: 1.0
  sound_speed: 1.0
  shear_viscosity: 0.1
  temperature: 1.0e-4
time: {coupling_step: 0.02, end: 0.5}
output: {times: [0.5], formats: [csv]}
seed: 5
"""


def arrangement_cells(bin_dir, work):
    cells = []
    n, dx = 20, 0.05
    rng = random.Random(7)
    lattice = [((i + 0.5) * dx, (j + 0.5) * dx) for i in range(n) for j in range(n)]
    arrangements = {
        "lattice": lattice,
        "jittered 0.3 dx": [((x + rng.uniform(-0.3, 0.3) * dx) % 1.0,
                             (y + rng.uniform(-0.3, 0.3) * dx) % 1.0) for x, y in lattice],
        "clumped (half in 1/4 of the box)": [(x * 0.5, y * 0.5) if k % 2 else (x, y)
                                              for k, (x, y) in enumerate(lattice)],
        "sparse (4 particles 0.5 apart, h = 0.15)": [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75),
                                                      (0.75, 0.75)],
    }
    for name, pts in arrangements.items():
        d = work / re.sub(r"\W", "_", "arr " + name)
        d.mkdir(parents=True, exist_ok=True)
        mass = 1.0 * dx * dx
        with open(d / "particles.csv", "w") as f:
            f.write("x,y,z,mass,density,kind\n")
            for x, y in pts:
                f.write(f"{x!r},{y!r},0,{mass!r},1.0,fluid\n")
        (d / "scene.yaml").write_text(ARRANGED)
        log = d / "log.txt"
        r = run_measured([bin_dir / "sadr", "run", d / "scene.yaml", "-q", "--force", "-o",
                          d / "out"], log=log)
        msg = next((l.strip() for l in log.read_text(errors="replace").splitlines()
                    if "error" in l.lower() or "failure" in l.lower()), "")
        rows, _ = read_frames(d / "out")
        c = {"cell": name, "axis": "particle arrangement (2D periodic SDPD, k_B T = 1e-4)",
             "value": name, "outcome": {0: "runs", 1: "refused", 4: "caught"}.get(r["rc"], f"exit {r['rc']}"),
             "rc": r["rc"], "message": msg[:400], "cpu_s": r["cpu_s"], "rows": rows}
        c["figure"] = figure(c, "fluid") if c["outcome"] == "runs" else ""
        cells.append(c)
    return cells


LONG = """name: long
dimension: 1
box: {{lower: [0.0], upper: [1.0], periodic: [true]}}
particles: {{spacing: 0.0625, density: 1.0}}
fluid:
  backend: sdpd
  h_over_dx: 2.0
  reference_density: 1.0
  sound_speed: 1.0
  shear_viscosity: 0.01
  temperature: 1.0e-4
  max_time_step: {dt!r}
species:
  - {{name: A, diffusivity: 0.01, initial: [{{count: 1000}}]}}
time: {{coupling_step: {tau!r}, end: {end!r}}}
output: {{times: [0.0, {end!r}], formats: [csv]}}
seed: 11
"""


def long_run_cell(bin_dir, work, steps):
    dt = 1e-3
    end = steps * dt
    text = LONG.format(dt=dt, tau=1000 * dt, end=end)
    c = run_cell(bin_dir, work, "long run", text)
    c["axis"] = f"long run: 16 SDPD particles + 16000 molecules, {steps:.0e} sub-steps"
    c["value"] = f"{c.get('substeps')} sub-steps"
    d = pathlib.Path(c["dir"]) / "out" / "frames"
    frames = sorted(d.glob("*.csv")) if d.exists() else []
    if c["outcome"] == "runs" and len(frames) >= 2:
        first, last = (list(csv.DictReader(open(f))) for f in (frames[0], frames[-1]))

        def totals(rows):
            m = sum(float(r["mass"]) for r in rows)
            p = sum(float(r["mass"]) * float(r["vx"]) for r in rows)
            ke = sum(0.5 * float(r["mass"]) * float(r["vx"]) ** 2 for r in rows)
            n = sum(float(r["A"]) for r in rows)
            return m, p, ke, n

        m0, p0, k0, n0 = totals(first)
        m1, p1, k1, n1 = totals(last)
        tkin = 2 * k1 / len(last) / 1e-4
        c["figure"] = (f"mass {m0:.17g} -> {m1:.17g} (drift {abs(m1 - m0) / m0:.1e}); momentum "
                       f"{p0:.3e} -> {p1:.3e}; kinetic temperature T_kin/kT = {tkin:.3f} at the end "
                       f"(16 particles: one sample, sd ~ {math.sqrt(2 / 16):.2f}); molecules "
                       f"{n0:.0f} -> {n1:.0f}")
        if abs(m1 - m0) > 1e-12 * m0 or n1 != n0 or abs(p1 - p0) > 1e-9:
            c["outcome"] = "SILENT"
    return [c]


def tolerance_cells(bin_dir, work):
    """The two tolerances from 1e-1 to 1e-6: the error-controlled coupling step
    (time.tolerance, relative) on the splitting-order scene, whose exact answer is known,
    and the adaptive SSA (ssa.tolerance) on drawert2019 Table 1 at N = 33 (10 realizations
    against the PDE reference). Cost: CPU s, and steps or events, which load does not move."""
    import annihilation_table1
    import splitting_order
    cells = []
    n0, lam, end = 1_000_000, splitting_order.LAMBDA, splitting_order.T_END
    beta = 1e-7 * 3125 / n0
    exact = splitting_order.PARTICLES * n0 * (1 - math.exp(-lam * end)) / lam
    base = splitting_order.SCENE.format(beta=beta, n0=n0, lam=lam, tau=0.1, end=end,
                                        splitting="lie", seed=2024)
    for tol in (1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6):
        text = sub(base, "splitting: lie}", f"splitting: lie, tolerance: {tol!r}}}")
        c = run_cell(bin_dir, work, f"time tolerance {tol:g}", text)
        c["axis"] = ("time.tolerance (relative; splitting-order scene, Lie, first step 0.1, "
                     "noise of one run 1.8e-4)")
        c["value"] = f"{tol:g}"
        c["figure"] = figure(c, "fluid")
        manifest = pathlib.Path(c["dir"]) / "out" / "run.json"
        if c["outcome"] == "runs" and c["rows"] and manifest.exists():
            p = sum(float(r["mass"]) * float(r["vx"]) for r in c["rows"])
            sc = json.loads(manifest.read_text()).get("step_control", {})
            c["figure"] = (f"error {abs(p / beta - exact) / exact:.2e}; steps "
                           f"{sc.get('accepted')} accepted, {sc.get('rejected')} rejected")
        cells.append(c)
    for tol in (None, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6):
        name = "ssa exact" if tol is None else f"ssa tolerance {tol:g}"
        c = {"cell": name, "axis": "ssa.tolerance (adaptive SSA; Table 1, N = 33, N_b = 1e3, "
             "t = 1, 10 realizations)", "value": "exact" if tol is None else f"{tol:g}",
             "message": "", "dir": str(work)}
        try:
            res = annihilation_table1.realization_errors(str(bin_dir / "sadr"), 33, 1000, 10,
                                                         end=1.0, subsets=(), tolerance=tol)
        except SystemExit as e:
            c.update(outcome="caught", rc=1, cpu_s=0.0, message=str(e))
            cells.append(c)
            continue
        c.update(outcome="runs", rc=0, cpu_s=res["cpu_s"] / 10,
                 figure=(f"error of the mean {res['errors'][10]:.2e} (noise {res['noise'][10]:.2e}); "
                         f"{res['events_per_realization']:.3g} events and "
                         f"{res['leaped_per_realization']:.3g} leaped molecules per realization"))
        if not all(math.isfinite(v) for v in res["errors"].values()):
            c["outcome"] = "SILENT"
        cells.append(c)
    return cells


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/release/bin"))
    ap.add_argument("--out", default=str(ROOT / "docs"))
    ap.add_argument("--long-steps", type=int, default=1_000_000)
    ap.add_argument("--only", default="",
                    help="comma list of: substep,c0,decades,counts,arrangement,tolerance,long")
    a = ap.parse_args()
    bin_dir = pathlib.Path(a.bin).resolve()
    work = pathlib.Path(tempfile.mkdtemp(prefix="sadr-stability-"))
    only = set(filter(None, a.only.split(",")))
    groups = [("substep", substep_cells), ("c0", sound_speed_cells), ("decades", decade_cells),
              ("counts", copy_number_cells), ("arrangement", arrangement_cells),
              ("tolerance", tolerance_cells),
              ("long", lambda b, w: long_run_cell(b, w, a.long_steps))]
    cells = []
    for gname, fn in groups:
        if only and gname not in only:
            continue
        print(f"stability map: {gname}", flush=True)
        cells += fn(bin_dir, work)
    for c in cells:
        c.pop("rows", None)
        c["commit"] = commit()
    out = pathlib.Path(a.out) / "validation"
    out.mkdir(parents=True, exist_ok=True)
    command = "bench/validation/stability_map.py " + " ".join(sys.argv[1:])
    if only and (out / "stability_map.json").exists():
        # --only: the other groups' cells stay as the last run wrote them (each names its commit)
        old = json.loads((out / "stability_map.json").read_text())
        fresh = {c["cell"] for c in cells}
        kept = [dict(c, commit=c.get("commit", old["commit"])) for c in old["cells"]
                if c["cell"] not in fresh]
        cells = kept + cells
        command = f"{old['command']}, then {command}"
    meta = {"command": command, "commit": commit(), "cells": cells, "work": str(work)}
    (out / "stability_map.json").write_text(json.dumps(meta, indent=1) + "\n")
    with open(out / "stability_map.md", "w") as f:
        f.write(f"# Stability map\n\nGenerated by `{meta['command']}` at `{meta['commit']}` "
                "(cells and their meaning: the script's docstring; a run with --only keeps the "
                "other cells, and the JSON names each cell's commit). CPU = user + sys of the "
                "run.\n\n")
        f.write("| axis | value | outcome | figure / message | CPU s |\n|---|---|---|---|---|\n")
        for c in cells:
            text = c["figure"] if c["outcome"].startswith("runs") or c["outcome"] == "SILENT" \
                else c["message"]
            text = text.replace("|", "/")
            f.write(f"| {c['axis']} | {c['value']} | {c['outcome']} | {text} | {c['cpu_s']:.2f} |\n")
    silent = [c for c in cells if c["outcome"] == "SILENT"]
    print(f"{len(cells)} cells; silent failures: {len(silent)}")
    for c in silent:
        print("  SILENT:", c["cell"], c.get("figure"), c["dir"])


if __name__ == "__main__":
    main()
