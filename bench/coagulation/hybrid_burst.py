#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Stretch of #17: the thrombin-burst time of the well-mixed injury voxel when the initiating
enzymes are a few molecules (stochastic) and the rest of the cascade is deterministic.

The voxel is the reference's `injury` case (tests/data/refs/coagulation/cascade_reference.py:
Table III + the Table IV injury terms over a wall layer of delta = 1) at its physical volume
V = 1 um^3: 1 nM there is 0.6022 molecules, so each voxel is a particle of volume 0.6022 in the
scene's units (concentrations stay in nM, counts are molecules). IXa, Xa and XIa, the enzymes
the injury makes, are stochastic (~10, ~1 and < 1 molecules per voxel); the 20 other species are
deterministic. A reaction that changes species of both paths is written as one reaction per
path with the same law (docs/scene-format.md, "Hybrid reactions"); the assigned Z and W are
written into the laws that read them. N voxels with no diffusion in one run are N independent
realizations. The burst time of a voxel is the first time (after the initial quench, t > 20) its
thrombin reaches half the deterministic peak (0.362 nM), linearly interpolated between frames;
the deterministic burst time is the same crossing of the same model with every species
deterministic (scipy Radau). The time of each voxel's thrombin maximum is printed too (a poor
estimator: the deterministic peak is broad).

  /usr/bin/python3 bench/coagulation/hybrid_burst.py --sadr build/release/bin/sadr --voxels 64
"""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_scenes  # noqa: E402

ref = make_scenes.ref
sys.path.insert(0, str(make_scenes.REPO / "python"))
import sadr  # noqa: E402

MOLECULES_PER_NM_UM3 = 0.60221  # 1 nM in 1 um^3
STOCHASTIC = {"IXa", "Xa", "XIa"}
INLINE = {"Z": "(VIIIa*IXa/0.56)", "W": "(Va*Xa/0.1)"}


def law_text(law, p, reactants):
    """Every law as an expression of concentrations (Z and W written out)."""
    if law[0] == "ma":
        return "*".join([make_scenes.num(p[law[1]])] + reactants)
    if law[0] == "mm":
        kcat, km, e = make_scenes.num(p[law[1]]), make_scenes.num(p[law[2]]), law[3]
        s = reactants[0]
        return f"{kcat}*{INLINE.get(e, e)}*{s}/({km} + {s})"
    return law[1]


def split(name, equation, expr, stochastic=True):
    """One reaction per path: each keeps the species of its path, both the same law."""
    lhs, rhs = (side.strip() for side in equation.split("->"))
    terms = {side: [t.strip() for t in part.split("+") if t.strip() not in ("", "0")]
             for side, part in (("l", lhs), ("r", rhs))}
    parts = []
    stoch = STOCHASTIC if stochastic else set()
    for path, keep in (("ssa", lambda s: s in stoch), ("fluid", lambda s: s not in stoch)):
        lt = [t for t in terms["l"] if keep(t)]
        rt = [t for t in terms["r"] if keep(t)]
        if lt or rt:
            parts.append((path, f"{' + '.join(lt) or '0'} -> {' + '.join(rt) or '0'}"))
    return [f'  - {{name: {name}{"_" + path if len(parts) > 1 else ""}, equation: "{eq}", '
            f'law: {{type: expression, expression: "{expr}"}}}}' for path, eq in parts]


def scene(n, tau, end, every, volume=1.0, stochastic=True):
    p = ref.rate_parameters()
    vol = MOLECULES_PER_NM_UM3 * volume
    lines = [
        f"# bench/coagulation/hybrid_burst.py: N independent injury voxels of {volume:g} um^3",
        "name: coagulation_hybrid_burst",
        "dimension: 1",
        f"box: {{lower: [0.0], upper: [{n * vol:.10g}], periodic: [true]}}",
        f"particles: {{spacing: {vol:.10g}}}   # 0.6022 per um^3: counts are molecules",
        "fluid: {backend: static, h_over_dx: 2.0}   # sub-step: the reaction stability limit",
    ]
    lines += make_scenes.parameters_yaml(p, [("LF", ref.L_INJURY / ref.DELTA)])
    lines.append("species:")
    for name, idx, c0, _ in ref.SPECIES:
        stoch = "" if (stochastic and name in STOCHASTIC) else "stochastic: false, "
        lines.append(f"  - {{name: {name}, {stoch}diffusivity: 0, "
                     f"initial: [{{concentration: {make_scenes.num(c0)}}}]}}   # [{idx}]")
    lines.append("reactions:")
    for name, eq, law in make_scenes.REACTIONS:
        reactants = [t.strip() for t in eq.split("->")[0].split("+") if t.strip() != "0"]
        lines += split(name, eq, law_text(law, p, reactants), stochastic)
    for gain, lose, expr in make_scenes.INJURY:
        eq = f"{lose} -> {gain}" if lose else f"0 -> {gain}"
        lines += split(f"injury_{gain}", eq, f"LF*{expr}", stochastic)
    lines += [
        f"time: {{coupling_step: {tau}, end: {end}}}",
        f"output: {{every: {every}, formats: [csv], species: [IIa, IXa, Xa, XIa, Ia]}}",
        "seed: 17",
    ]
    return "\n".join(lines) + "\n"


QUENCH = 20.0  # the 0.1 % enzymes are quenched by then (thrombin 1.4 -> ~0.01)


def first_crossing(t, c, level):
    """First upward crossing of level after QUENCH (linear between samples), nan if none."""
    k0 = max(1, int(np.searchsorted(t, QUENCH)))
    up = np.nonzero((c[k0 - 1:-1] < level) & (c[k0:] >= level))[0]
    if len(up) == 0:
        return float("nan")
    k = k0 + up[0]
    return t[k - 1] + (level - c[k - 1]) * (t[k] - t[k - 1]) / (c[k] - c[k - 1])


def deterministic(end, every, zero_enzymes):
    """(t, thrombin) of the all-deterministic voxel."""
    p = ref.rate_parameters()
    y0 = [0.0 if (zero_enzymes and n in STOCHASTIC) else c for n, _, c, _ in ref.SPECIES]
    t = np.arange(0.0, end + 1e-9, every)
    sol = solve_ivp(ref.rhs_factory(p, True), (0, end), y0, method="Radau", rtol=1e-10,
                    atol=1e-12, t_eval=t)
    return t, sol.y[8]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sadr", default="build/release/bin/sadr")
    ap.add_argument("--voxels", type=int, default=64)
    ap.add_argument("--tau", type=float, default=0.05)
    ap.add_argument("--end", type=float, default=160.0)
    ap.add_argument("--every", type=float, default=1.0)
    ap.add_argument("--volume", type=float, default=1.0, help="voxel volume [um^3]")
    ap.add_argument("--deterministic", action="store_true",
                    help="every species deterministic (the same scene through the fluid only)")
    ap.add_argument("--out", default=None, help="run directory (default: a temporary one)")
    ap.add_argument("--reuse", action="store_true", help="analyse OUT/run if it exists")
    args = ap.parse_args()
    out = Path(args.out or tempfile.mkdtemp(prefix="coag-hybrid-"))
    out.mkdir(parents=True, exist_ok=True)
    path = out / "scene.yaml"
    path.write_text(scene(args.voxels, args.tau, args.end, args.every, args.volume,
                          not args.deterministic))
    if not (args.reuse and (out / "run" / "run.json").exists()):
        subprocess.run([args.sadr, "run", str(path), "-o", str(out / "run"), "--force", "-q"],
                       check=True)
    run = sadr.Run(out / "run")
    t = np.array([run.frame(k).time for k in range(len(run))])
    iia = np.array([run.frame(k).species["IIa"] for k in range(len(run))])  # (time, voxel)
    # frames hold molecules for stochastic species and concentrations (nM) for deterministic ones
    per_nm = MOLECULES_PER_NM_UM3 * args.volume if args.deterministic else 1.0
    xa = np.array([run.frame(k).species["Xa"] for k in range(len(run))]) * per_nm
    ixa = np.array([run.frame(k).species["IXa"] for k in range(len(run))]) * per_nm
    td_t, td_c = deterministic(max(args.end, 160.0), 0.05, False)  # the whole peak
    level = 0.5 * td_c[td_t > QUENCH].max()
    t_det = first_crossing(td_t, td_c, level)
    t_det0 = first_crossing(*deterministic(max(args.end, 160.0), 0.05, True), level)
    burst = np.array([first_crossing(t, iia[:, v], level) for v in range(iia.shape[1])])
    k0 = int(np.searchsorted(t, QUENCH))
    tmax = t[k0 + np.argmax(iia[k0:], axis=0)]
    peak = iia[k0:].max(axis=0)
    ok = np.isfinite(burst)
    b = burst[ok]
    n = len(burst)
    mean = iia.mean(axis=1)
    det_on_t = np.interp(t, td_t, td_c)
    se = iia.std(axis=1, ddof=1) / np.sqrt(n)
    z = np.abs(mean - det_on_t)[k0:] / np.maximum(se[k0:], 1e-300)
    print(f"{n} voxels of {args.volume:g} um^3{' (all deterministic)' if args.deterministic else ''}, "
          f"tau = {args.tau:g}, output every {args.every:g}, t <= {args.end:g}")
    k40 = int(np.searchsorted(t, 40.0))
    print(f"molecules per voxel at t = 40: IXa mean {ixa[k40].mean():.2f}, Xa mean "
          f"{xa[k40].mean():.2f}")
    print(f"burst (thrombin first >= {level:.4g} nM after t = {QUENCH:g}): deterministic "
          f"t = {t_det:.2f} (t = {t_det0:.2f} with IXa, Xa, XIa starting at 0)")
    if len(b) > 1:
        print(f"hybrid: {len(b)} of {n} voxels burst by t = {args.end:g}: mean {b.mean():.2f} +- "
              f"{b.std(ddof=1) / np.sqrt(len(b)):.2f}, sd {b.std(ddof=1):.2f}, median "
              f"{np.median(b):.2f}, 10-90 % {np.percentile(b, 10):.1f} - {np.percentile(b, 90):.1f}")
    print(f"per-voxel thrombin maximum: {peak.mean():.4g} nM mean (sd {peak.std(ddof=1):.3g}) at "
          f"t = {tmax.mean():.1f} mean (deterministic {td_c[td_t > QUENCH].max():.4g} nM at "
          f"t = {td_t[td_t > QUENCH][np.argmax(td_c[td_t > QUENCH])]:.2f})")
    print(f"ensemble-mean thrombin against the deterministic curve: max |z| = {z.max():.2f} over "
          f"{len(z)} frames, max |mean - det| = {np.abs(mean - det_on_t)[k0:].max():.4g} nM")
    print("burst times: " + " ".join(f"{x:.1f}" for x in np.sort(b)) +
          (f" (+{n - len(b)} not by t = {args.end:g})" if len(b) < n else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
