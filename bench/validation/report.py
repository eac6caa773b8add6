#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Regenerates docs/validation-report.md and its plots (docs/validation/*.png) in one go.

    bench/validation/report.py --quick   # about 20 min on 2 cores
    bench/validation/report.py --full    # 1-2 hours (see below)
        [--build build/release] [--without BIN] [--out docs]

--full runs Table 1's SSA at R = 100 for N = 17/33/65 and N_b = 1e2/1e3/1e4
(plus t = 4 at N_b = 1e3): 0.83 h of CPU projected from the per-realization
CPU costs measured on 2026-12-01 (SSA_COST_PER_REALIZATION below, loaded
machine; the ensembles use both cores, so about half that in wall time on a
quiet machine), of which N = 65, N_b = 1e4 alone is 100 x 16.9 s; then every
validation binary (the tDPD and open-channel ones are not timed here) and the
sweeps at their full sizes. It prints its SSA projection when it starts.
--full has not been run yet.

Needs a build with the tests and benchmarks (cmake --preset release; the
default), /usr/bin/python3 with numpy and matplotlib (deploy/install-deps.sh).
Every row names the command that produced it and the commit; cost is CPU
time (user + sys of the process tree, bench/validation/measure.py), because
wall time on a shared machine measures the other users. Run it in a quiet
window for figures to quote. The pieces:

  * gtest validations (ctest -L validation) and the exact statistical checks of
    the default suite, run binary by binary; their RESULT/printf lines are the
    measured errors;
  * drawert2019 Table 1: deterministic (AnnihilationValidation + the
    fluid_error_sweep benchmark) and SSA (annihilation_table1.py) with a
    work-precision diagram against the paper's points and the paper code's cost;
  * Poiseuille start-up error against resolution (fluid_error_sweep), against
    resolution and sound speed through `sadr sweep` (poiseuille_sweep.py), and
    the example's centre-line speed (poiseuille_example.py);
  * the coupled stochastic case (a tracer in a flow) against R, resolution and
    tau through `sadr sweep` (coupled_tracer.py);
  * where tau matters in Table 1's SSA column (annihilation_table1.tau_independence);
    reduced versions of the two sweeps: ctest -L validation -R 'validation_(poiseuille_sweep|coupled_tracer)';
  * Lie vs Strang against the exact continuous answer, observed orders
    (splitting_order.py);
  * the plan's skips with and without (skip_bench.py; needs a build from before
    the skip, --without; otherwise the stored bench/results/skip_frame_to_frame.md).
"""
import argparse
import datetime
import json
import os
import pathlib
import re
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure import ROOT, commit, run_measured  # noqa: E402
import annihilation_table1  # noqa: E402
import coupled_tracer  # noqa: E402
import poiseuille_example  # noqa: E402
import poiseuille_sweep  # noqa: E402
import splitting_order  # noqa: E402
import paper_cost  # noqa: E402
import table1_floor  # noqa: E402
import wp_plots  # noqa: E402

# drawert2019 Table 1 and the paper code's cost on this machine type (issue #20).
PAPER_SDPD = {17: 1.856e-4, 33: 1.698e-4, 65: 2.325e-4}
PAPER_SSA = {17: 7.285e-4, 33: 5.334e-4, 65: 6.644e-4}  # 100 realizations
PAPER_SSA_ONE = {17: 3.5e-3, 33: 2.6e-3, 65: 1.4e-3}  # one realization
# s, one realization of 10,000 steps, measured on another machine of this type months ago: used
# only when the run is not given the paper code (--paper-lmp, --paper-decks), and then says so.
PAPER_COST_ONE = {17: 0.72, 33: 1.22, 65: 6.08}


def cost_one(d):
    """The paper code's cost per realization: measured in this run (paper_cost.py) or the constant."""
    measured = d.get("paper_cost")
    if measured:
        return {int(n): r["paper_median_s"] for n, r in measured.items()}
    return PAPER_COST_ONE

# Table 1 SSA: CPU seconds per realization to t = 1 (sadr + services, os.wait4). N = 17:
# the --quick run at 1c5522f; N = 33 / 65: R = 1-2 runs on 2026-12-01 at load ~13 on 2 cores
# (upper bounds). The --full projection uses them.
SSA_COST_PER_REALIZATION = {(17, 1e2): 0.0087, (17, 1e3): 0.038, (17, 1e4): 0.28,
                            (33, 1e2): 0.033, (33, 1e3): 0.24, (33, 1e4): 2.17,
                            (65, 1e2): 0.19, (65, 1e3): 1.76, (65, 1e4): 16.9}

# N = 33 / 65 at the paper's R = 100 with N_b = 1e3, and N = 33 at N_b = 1e4 (about 6 min of
# CPU together); N = 65 at N_b = 1e4 and R = 100 is --full only.
QUICK_SSA_CASES = [(17, 1e3, 30, 1.0), (33, 1e3, 100, 1.0), (65, 1e3, 100, 1.0),
                   (17, 1e4, 10, 1.0), (33, 1e4, 100, 1.0), (17, 1e2, 30, 1.0), (17, 1e3, 30, 4.0)]
FULL_SSA_CASES = ([(n, nb, 100, 1.0) for n in (17, 33, 65) for nb in (1e2, 1e3, 1e4)] +
                  [(n, 1e3, 100, 4.0) for n in (17, 33, 65)])


def projected_cpu_s(cases):
    """CPU seconds the SSA cases (N, N_b, R, t_end) will take, from SSA_COST_PER_REALIZATION."""
    return sum(SSA_COST_PER_REALIZATION.get((n, nb), 30.0) * r * end for n, nb, r, end in cases)


# (id, binary under build/tests, gtest filter, in --quick, reference, paper figure, docs)
GTESTS = [
    ("diffusion", "fluid/fluid_validation_tests", "DiffusionValidation.*", True,
     "erf step with no-flux images, Dirichlet and Neumann series (tests/fluid/reference_solutions.hpp)",
     "li2015 Fig. 3 (step), Fig. 4 (Dirichlet), Fig. 5 (Neumann)", "docs/fluid-core.md"),
    ("annihilation_det", "fluid/fluid_validation_tests", "AnnihilationValidation.*", True,
     "6th-order PDE reference and the semi-discrete ODE (tests/data/refs/annihilation_1d*_subset.csv)",
     "drawert2019 Table 1 (SDPD), Fig. 3b", "docs/fluid-core.md"),
    ("poiseuille", "fluid/fluid_validation_tests", "Walls/PoiseuilleValidation.*", True,
     "Morris, Fox & Zhu 1997 series (tests/fluid/reference_solutions.hpp)", "- (not in either paper)",
     "docs/fluid-core.md"),
    ("equipartition", "fluid/fluid_validation_tests", "Dims/Equipartition.*", True,
     "k_B T_kin = k_B T (fluctuation-dissipation)", "-", "docs/fluid-core.md"),
    ("open_channel", "fluid/fluid_validation_tests", "OpenChannelValidation.*", False,
     "plane Poiseuille profile", "-", "docs/fluid-core.md"),
    ("ssa_validation", "ssa/ssa_validation_tests", "*", True,
     "exact mean/variance (Eigen expm, FSP; scipy cross-check tests/ssa/linear_rdme_reference.py)", "-", "docs/ssa-core.md"),
    ("tdpd_diffusion", "fluid_tdpd/fluid_tdpd_validation_tests", "*", False,
     "erf step; li2015 D(kappa) fit D = 0.0187 + 0.771 kappa", "li2015 Fig. 1(b), Fig. 3",
     "docs/tdpd.md"),
    ("tdpd_walls", "fluid_tdpd/fluid_tdpd_walls_validation_tests", "*", False,
     "Dirichlet/Neumann series (tests/fluid/reference_solutions.hpp), Poiseuille", "li2015 Fig. 4, Fig. 5", "docs/tdpd.md"),
    ("tdpd_adr", "fluid_tdpd/fluid_tdpd_adr_validation_tests", "*", False,
     "converged finite-volume advection-diffusion", "li2015 Fig. 6-7 (Pe sweep)", "docs/tdpd.md"),
    # Exact statistical checks of the default suite (Bonferroni z tests, stated false-failure rates).
    ("ssa_exact_stats", "ssa/ssa_property_tests", "*", True,
     "exact moments: birth-death, dimerisation (FSP), linear networks, MSD, reservoirs, "
     "NSM vs direct", "-", "docs/ssa-core.md"),
    ("splitting_e2e", "e2e/e2e_splitting_tests", "*", True,
     "exact quadrature of N(t) implied by Lie / Strang", "-", "ARCHITECTURE.md"),
]


def run_gtest(build, binary, flt, work):
    exe = build / "tests" / binary
    log = work / (binary.replace("/", "_") + re.sub(r"\W", "_", flt) + ".log")
    r = run_measured([exe, f"--gtest_filter={flt}"], cwd=exe.parent, log=log)
    text = log.read_text(errors="replace")
    lines = []
    for line in text.splitlines():
        s = line.strip()
        if not s or s.startswith("[") or s.startswith("Note:") or s.startswith("Running main"):
            continue
        lines.append(s[len("RESULT "):] if s.startswith("RESULT ") else s)
    passed = re.findall(r"^\[\s+OK \] (\S+)", text, re.M)
    failed = re.findall(r"^\[  FAILED  \] (\S+) \(", text, re.M)
    skipped = re.findall(r"^\[  SKIPPED \] (\S+)", text, re.M)
    return {"rc": r["rc"], "cpu_s": r["cpu_s"], "lines": lines, "passed": passed,
            "failed": failed, "skipped": skipped,
            "command": f"{exe.relative_to(ROOT) if exe.is_relative_to(ROOT) else exe} "
                       f"--gtest_filter='{flt}'"}


def kv(line):
    return dict(re.findall(r"(\S+?)=(\S+)", line))


def fluid_error_sweep(build, work):
    exe = build / "bench/fluid/fluid_error_sweep"
    log = work / "fluid_error_sweep.csv"
    r = run_measured([exe], log=log)
    rows = [l.split(",") for l in log.read_text().splitlines()
            if l.count(",") == 5 and l.split(",")[1].isdigit()]  # data rows, not the header
    return {"cpu_s": r["cpu_s"], "command": str(exe.relative_to(ROOT) if exe.is_relative_to(ROOT) else exe),
            "rows": [{"case": c, "res": int(n), "dt": float(dt), "error": float(e),
                      "cpu_s": float(cpu)} for c, n, dt, e, cpu, _ in rows]}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--quick", action="store_true")
    mode.add_argument("--full", action="store_true")
    ap.add_argument("--build", default=str(ROOT / "build/release"))
    ap.add_argument("--without", default="",
                    help="bin/ of a build from before the frame-to-frame skip (skip table; "
                         "default: none, the stored bench/results/skip_frame_to_frame.md)")
    ap.add_argument("--out", default=str(ROOT / "docs"))
    ap.add_argument("--only", default="",
                    help="comma-separated gtest ids to run (default: all of the mode); "
                         "'none' for none (a quick look at the rest)")
    ap.add_argument("--ssa", default="",
                    help="Table 1 SSA cases N:N_b:R:t_end,... instead of the mode's")
    ap.add_argument("--reuse", default="",
                    help="a data.json of an earlier run: take its gtest results (same commit!)")
    ap.add_argument("--render", action="store_true",
                    help="run nothing: write validation-report.md and the plots again from "
                         "OUT/validation/data.json (after a change of the markdown only)")
    ap.add_argument("--table1", action="store_true",
                    help="with --quick or --full: run only Table 1's SSA part (the ensembles, tau "
                         "and table1_floor.py) and take every other section from OUT/validation/"
                         "data.json of the last whole run, which the header names")
    ap.add_argument("--paper-lmp", default="",
                    help="the paper code's LAMMPS executable: measure its cost per realization "
                         "in this run, interleaved with ours (paper_cost.py)")
    ap.add_argument("--paper-decks", default="",
                    help="with --paper-lmp: its examples/ssa_tsdpd/cylinder_annihilation/"
                         "temporal_analysis folder")
    ap.add_argument("--paper-pairs", type=int, default=5)
    a = ap.parse_args()
    if bool(a.paper_lmp) != bool(a.paper_decks):
        ap.error("--paper-lmp and --paper-decks go together")
    only = set(filter(None, a.only.split(",")))
    build = pathlib.Path(a.build).resolve()
    out = pathlib.Path(a.out)
    figs = out / "validation"
    figs.mkdir(parents=True, exist_ok=True)
    work = pathlib.Path(tempfile.mkdtemp(prefix="sadr-report-"))
    sadr = build / "bin" / "sadr"
    quick = a.quick
    rev = commit()
    cmd = "bench/validation/report.py " + ("--quick" if quick else "--full")
    started = datetime.datetime.now(datetime.timezone.utc)
    data = {"commit": rev, "mode": "quick" if quick else "full", "gtests": {}}

    def step(msg):
        print(f"[{datetime.datetime.now():%H:%M:%S}] {msg}", flush=True)

    if a.table1 or a.render:
        table1_only(a, data, figs, sadr, rev, cmd, started, build, quick, step)
        return
    reuse = json.loads(pathlib.Path(a.reuse).read_text()).get("gtests", {}) if a.reuse else {}
    for gid, binary, flt, in_quick, *_ in GTESTS:
        if (only and gid not in only) or (not only and quick and not in_quick):
            continue
        if gid in reuse:
            data["gtests"][gid] = reuse[gid]
            continue
        step(f"gtest {gid}")
        data["gtests"][gid] = run_gtest(build, binary, flt, work)
        (figs / "data.json").write_text(json.dumps(data, indent=1, default=str) + "\n")

    step("fluid_error_sweep")
    data["sweep"] = fluid_error_sweep(build, work)

    # Table 1 SSA: one ensemble per (N, N_b); the error of the first r realizations.
    # (N, N_b, R, end): t = 1 s is the paper code's 10,000 steps of 1e-4 s (its quoted cost);
    # t = 4 s is steady (the t = inf reference).
    table1_ssa(a, data, sadr, quick, step)

    step("poiseuille sweep (resolution x sound speed, sadr sweep)")
    data["poiseuille_sweep"] = poiseuille_sweep.run(
        build / "bin", poiseuille_sweep.QUICK_DX if quick else poiseuille_sweep.FULL_DX)
    data["poiseuille_sweep"]["dt_check"] = poiseuille_sweep.dt_check(build / "bin")
    poiseuille_sweep.plot(data["poiseuille_sweep"], figs / "poiseuille_c0_work_precision.png")

    step("coupled tracer (R x resolution, tau; sadr sweep)")
    data["coupled_tracer"] = coupled_tracer.run(
        build / "bin", coupled_tracer.QUICK_DX if quick else coupled_tracer.FULL_DX,
        coupled_tracer.QUICK_R if quick else coupled_tracer.FULL_R)
    coupled_tracer.plot(data["coupled_tracer"], figs / "coupled_tracer.png")

    step("poiseuille example")
    data["poiseuille_example"] = poiseuille_example.measure(build / "bin")

    step("splitting order")
    data["splitting"] = splitting_order.run(build / "bin")
    splitting_order.plot(data["splitting"], figs / "splitting_order.png")

    skip_json = ROOT / "bench/results/skip_frame_to_frame.json"
    if a.without and pathlib.Path(a.without, "sadr").exists():
        step("skip bench")
        run_measured([sys.executable, ROOT / "bench/validation/skip_bench.py", "--without",
                      a.without, "--with", build / "bin", "--pairs", "3" if quick else "5"])
    data["skips"] = json.loads(skip_json.read_text()) if skip_json.exists() else None

    step("plots")
    plots = wp_plots.make_all(data, figs, PAPER_SDPD, PAPER_SSA, PAPER_SSA_ONE, cost_one(data))
    (work / "data.json").write_text(json.dumps(data, indent=1, default=str))
    elapsed = (datetime.datetime.now(datetime.timezone.utc) - started).total_seconds()
    write_markdown(out / "validation-report.md", data, plots, cmd, rev, started, elapsed, build, quick)
    (figs / "data.json").write_text(json.dumps(data, indent=1, default=str) + "\n")
    step(f"wrote {out / 'validation-report.md'} in {elapsed / 60:.1f} min")


def table1_ssa(a, data, sadr, quick, step):
    """Table 1's SSA part: the ensembles, where tau matters, and what sets the cost."""
    ssa_cases = QUICK_SSA_CASES if quick else FULL_SSA_CASES
    if a.ssa:
        ssa_cases = [(int(n), float(nb), int(r), float(t)) for n, nb, r, t in
                     (c.split(":") for c in a.ssa.split(","))]
    step(f"projected CPU time of the Table 1 SSA cases: {projected_cpu_s(ssa_cases) / 3600:.1f} h "
         "(SSA_COST_PER_REALIZATION)")
    data["ssa_projection"] = {
        "per_realization": [[n, nb, v] for (n, nb), v in sorted(SSA_COST_PER_REALIZATION.items())],
        "full_cpu_h": projected_cpu_s(FULL_SSA_CASES) / 3600}
    data["ssa"] = []
    for np_, nb, r, end in ssa_cases:
        step(f"Table 1 SSA N={np_} N_b={nb:g} R={r} t={end:g}")
        res = annihilation_table1.realization_errors(str(sadr), np_, nb, r, end=end)
        res["errors"] = {int(k): v for k, v in res["errors"].items()}
        data["ssa"].append(res)

    step("Table 1 SSA: coupling step tau")
    data["table1_tau"] = annihilation_table1.tau_independence(str(sadr))

    step("Table 1 SSA: fixed cost per realization, events, profile (table1_floor.py)")
    data["table1_split"] = table1_floor.measure(sadr)

    if a.paper_lmp:
        step(f"Table 1: the paper code's cost, {a.paper_pairs} pairs beside ours (paper_cost.py)")
        data["paper_cost"] = paper_cost.measure(pathlib.Path(a.paper_lmp).resolve(),
                                                a.paper_decks, sadr, pairs=a.paper_pairs)
    else:
        data.pop("paper_cost", None)


def table1_only(a, data, figs, sadr, rev, cmd, started, build, quick, step):
    """--table1: Table 1's SSA part now, the other sections from the last whole run.
    --render: everything from the last runs' data.json."""
    old = json.loads((figs / "data.json").read_text())
    for c in old.get("ssa", []):  # JSON turned the realization counts into strings
        c["errors"] = {int(k): v for k, v in c["errors"].items()}
        c["noise"] = {int(k): v for k, v in c["noise"].items()}
    for k, v in old.items():
        if a.render or k not in ("ssa", "table1_tau", "table1_split", "ssa_projection"):
            data[k] = v
    data["commit"], data["mode"] = old["commit"], old["mode"]
    if not a.render:
        table1_ssa(a, data, sadr, quick, step)
    step("plots")
    plots = wp_plots.make_all(data, figs, PAPER_SDPD, PAPER_SSA, PAPER_SSA_ONE, cost_one(data))
    elapsed = (datetime.datetime.now(datetime.timezone.utc) - started).total_seconds()
    if not a.render:
        data["table1_run"] = {"command": cmd + " --table1", "commit": rev,
                              "utc": f"{started:%Y-%m-%d %H:%M}", "minutes": elapsed / 60}
    # The header keeps the whole run's command, commit, date and duration.
    hdr = re.search(r"Generated by `([^`]+)` at commit `(\S+)` on (\S+ \S+) UTC in ([\d.]+) min",
                    (figs.parent / "validation-report.md").read_text())
    whole = datetime.datetime.strptime(hdr[3], "%Y-%m-%d %H:%M")
    write_markdown(figs.parent / "validation-report.md", data, plots, hdr[1], hdr[2], whole,
                   60 * float(hdr[4]), build, old["mode"] == "quick")
    (figs / "data.json").write_text(json.dumps(data, indent=1, default=str) + "\n")
    step(f"wrote {figs.parent / 'validation-report.md'} in {elapsed / 60:.1f} min")


def write_markdown(path, d, plots, cmd, rev, started, elapsed, build, quick):
    import wp_tables  # the markdown, kept apart from the running
    path.write_text(wp_tables.render(d, plots, cmd, rev, started, elapsed, build, quick,
                                     PAPER_SDPD, PAPER_SSA, PAPER_SSA_ONE, cost_one(d), GTESTS))


if __name__ == "__main__":
    main()
