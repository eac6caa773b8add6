# SPDX-License-Identifier: MIT
"""The markdown of the sweep-based sections of docs/validation-report.md (report.py):
Poiseuille start-up against resolution and sound speed, the coupled tracer
against R, resolution and tau, and where tau matters in Table 1."""
import math


def e(x):
    return f"{x:.2e}"


def order(xs, ys):
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def poiseuille(d, rev):
    p = d.get("poiseuille_sweep")
    if not p:
        return []
    L = []
    w = L.append
    ok = [r for r in p["rows"] if "failed" not in r]
    w("## Poiseuille start-up: resolution x sound speed (`sadr sweep`)\n")
    w("![Poiseuille resolution x sound speed](validation/poiseuille_c0_work_precision.png)\n")
    w(f"Command: `{p['command']}` (one `sadr sweep`: `particles.spacing` zipped with the box, "
      "x `fluid.sound_speed`), commit `" + rev + "`. Reference: the start-up series (Morris, "
      f"Fox & Zhu 1997) with walls at y = 0, 1, g = {p['g']}, nu = {p['nu']} (u_max = 0.1); "
      f"error = RMS over the fluid particles of u_x - u_ref at t = {p['end']:g}, divided by "
      "u_ref(H/2). Paper: - (not in either paper). CPU s = worker + services of the run "
      "(`result.json` cpu_s) on a loaded machine; the wall column is the coupling loop from "
      "`run.json`, **to be re-measured in a quiet window**.\n")
    w("| dx | c0 | c0 / u_max | fluid particles | error | max abs(rho - 1) | CPU s | wall s (loaded) |"
      "\n|---|---|---|---|---|---|---|---|")
    for r in p["rows"]:
        if "failed" in r:
            w(f"| {r['dx']:g} | {r['c0']:g} | {r['c0'] / 0.1:g} | - | failed (exit "
              f"{r['exit_code']}): {r['failed'][:160]} | - | {r['cpu_s']:.2f} | - |")
            continue
        w(f"| {r['dx']:g} | {r['c0']:g} | {r['c0'] / 0.1:g} | {r['fluid_particles']} | "
          f"{e(r['error'])} | {r['max_density_dev']:.1e} | {r['cpu_s']:.2f} | "
          f"{r['wall_loop_s']:.2f} |")
    by_c0 = {}
    for r in ok:
        by_c0.setdefault(r["c0"], []).append(r)
    fits = []
    for c0, rs in sorted(by_c0.items()):
        if len(rs) > 1:
            rs = sorted(rs, key=lambda r: r["dx"])
            fits.append(f"c0 = {c0:g}: {order([r['dx'] for r in rs], [r['error'] for r in rs]):.2f}")
    w("\nObserved order in dx (least squares over the resolutions): " + "; ".join(fits) + ".")
    dt = p.get("dt_check")
    if dt:
        w(f" Time step: at dx = {dt['dx']:g}, c0 = {dt['c0']:g}, the error is "
          f"{e(dt['limit']['error'])} at the stability limit and {e(dt['capped']['error'])} with "
          f"the sub-step capped at {dt['capped']['max_time_step']:g} (`fluid.max_time_step`, "
          "about a tenth of the viscous limit): the sub-step is not what sets the error.")
    w("\nWhat this shows: the error is first order in dx, set by the wall treatment "
      "(stationary wall particles put the no-slip planes about half a spacing beyond the "
      "walls, `examples/poiseuille_tracer_2d.yaml`). The classic weak-compressibility error "
      "(density variation ~ (u_max / c0)^2) does not show: this flow is parallel, div u = 0, "
      "and the density stays within the max abs(rho - 1) column even at c0 = u_max. The sound "
      "speed enters through the wall: the highest c0 lowers the error at the finer "
      "resolutions (the fluid-wall pressure term moves the effective no-slip plane), at a "
      "cost that grows as c0 once the acoustic limit takes over from the viscous one (the "
      "CPU column). The cheapest run at a given error is at the lowest c0 that still holds "
      "the density variation a scene needs (1 % is the usual rule: c0 >= 10 u_max). Reduced "
      "version: `ctest -L validation -R validation_poiseuille_sweep` (order 0.8-1.2 in dx).\n")
    return L


def coupled(d, rev):
    c = d.get("coupled_tracer")
    if not c:
        return []
    L = []
    w = L.append
    w("## Coupled stochastic case: a tracer in a flow, against R, resolution and tau\n")
    w("![Tracer in a flow](validation/coupled_tracer.png)\n")
    w(f"Command: `{c['command']}`, commit `{rev}` (`sadr sweep` over `particles.spacing` x R "
      "realizations, then over `time.coupling_step`). A periodic 1D SDPD fluid at k_B T = 0 is "
      f"accelerated uniformly by g = {c['g']}, so the lattice translates rigidly by g t^2 / 2; "
      f"the stochastic tracer ({c['n0']} molecules per particle in the stripe "
      f"{c['stripe'][0]} <= x <= {c['stripe'][1]}, D = {c['D']}, NSM on the particle graph the "
      "SSA rebuilds from the fluid's positions every coupling step) rides along. Reference: the "
      "exact periodic stripe solution of the heat equation, shifted by g t^2 / 2, with the "
      f"diffusivity the particle graph converges to, kappa_eff = {c['kappa_ratio']:.4f} D "
      f"(h = {c['h_over_dx']:g} dx, eps_h = 0.01: `tests/data/refs/sph_consistency.csv`, "
      "docs/ssa-core.md); the error against D itself (the documented regularisation bias) is "
      "the second error column. Error: RMS "
      f"over the particles of E_r[X_i] / n0 - c(x_i, t) / c0 at t = {c['T']:g}; noise level: "
      "the error expected from noise alone. Paper: - (neither paper has this case). CPU s: the "
      "r runs' workers and services (loaded machine).\n")
    w("| dx | particles | r | error (kappa_eff) | error (D) | noise level | CPU s of the r runs |"
      "\n|---|---|---|---|---|---|---|")
    finals = []
    for row in c["rows"]:
        rs = sorted(row["by_r"], key=int)
        for r in rs:
            v = row["by_r"][r]
            w(f"| 1/{round(1 / row['dx'])} | {row['particles']} | {r} | {e(v['error'])} | "
              f"{e(v['error_vs_kappa'])} | {e(v['noise'])} | {v['cpu_s']:.2f} |")
        finals.append((row["dx"], row["by_r"][rs[-1]]))
    rows1 = c["rows"][-1]["by_r"]  # the finest resolution: the least bias
    rs = sorted(rows1, key=int)
    w(f"\nAgainst R (dx = 1/{round(1 / c['rows'][-1]['dx'])}): observed slope of the error "
      f"{order([int(r) for r in rs], [rows1[r]['error'] for r in rs]):.2f} (noise alone: -0.5). "
      "Against dx at the largest R: " + ", ".join(
          f"dx = 1/{round(1 / dx)}: error {e(v['error'])} (noise {e(v['noise'])}, bias "
          f"{e(math.sqrt(max(0.0, v['error'] ** 2 - v['noise'] ** 2)))})" for dx, v in finals)
      + " (against kappa_eff). Where the error is at the noise level, more realizations, not "
      "resolution, reduce it; against D the error stops at the regularisation bias. Reduced "
      "version: `ctest -L validation -R validation_coupled_tracer` (error within 2 noise "
      "levels of the kappa_eff answer, and not of D's).\n")
    if c.get("tau_rows"):
        w("| coupling step tau | dx | R | error (kappa_eff) | noise level |\n|---|---|---|---|---|")
        for r in c["tau_rows"]:
            w(f"| {r['tau']:g} | 1/{round(1 / r['dx'])} | {r['R']} | {e(r['error'])} | "
              f"{e(r['noise'])} |")
        w("\nThe graph only translates here, so tau must not change the answer beyond noise "
          "(Lie splitting of transport and reactions has no reaction to split from); the "
          "splitting error against tau is measured on the buoyancy case below.\n")
    return L


def table1_tau(d, rev):
    t = d.get("table1_tau")
    if not t:
        return []
    rows = t["rows"]
    det = sorted({r["dt"] for r in d["sweep"]["rows"] if r["case"].startswith("annihilation")})
    return [
        "## Table 1: where tau matters\n",
        f"SSA column (N = {t['Np']}, N_b = {t['N_b']:g}, t = {t['end']:g}, one realization per "
        "tau, commit `" + rev + "`, `annihilation_table1.tau_independence`): coupling steps "
        + ", ".join(f"{r['tau']:g}" for r in rows) + " give "
        + ("**byte-identical frames**" if t["identical"] else "**different frames**")
        + " (CPU s " + ", ".join(f"{r['cpu_s']:.2f}" for r in rows) + "): nothing moves in this "
        "scene, so the plan advances the SSA from output time to output time and tau does not "
        "enter. In the deterministic column the sub-step does: `fluid_error_sweep` runs each N "
        "at dt = " + ", ".join(f"{x:g}" for x in det) + " (the work-precision points above).\n"]


def ssa_cost(d, cost_table, projected_h):
    """Measured CPU s per realization of every Table 1 SSA case of this run, and the
    table the --full projection uses."""
    L = ["## Table 1 SSA cost per realization, and what `--full` costs\n",
         "| N | N_b | t | R run | CPU s per realization (this run) | R = 100 projected CPU s |"
         "\n|---|---|---|---|---|---|"]
    for c in d["ssa"]:
        per = c["cpu_s"] / c["realizations"]
        L.append(f"| {c['Np']} | {c['N_b']:g} | {c['end']:g} | {c['realizations']} | "
                 f"{per:.3f} | {100 * per:.0f} |")
    L.append("\nThe `--full` projection (`report.py`, SSA_COST_PER_REALIZATION, CPU s per "
             "realization to t = 1, measured on a loaded machine): "
             + ", ".join(f"N = {n}, N_b = {nb:g}: {v:g}" for (n, nb), v in
                         sorted(cost_table.items()))
             + f"; the --full SSA cases sum to about {projected_h:.1f} h of CPU.\n")
    return L
