#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Well-mixed reference of the li2015 coagulation cascade (sec. III C, Tables II-V).

The 25-species model of Anand et al. as li2015 prints it (Table III: 23 source terms, two
algebraic species Z = [VIIIa][IXa]/0.56 and W = [Va][Xa]/0.1), in tDPD units with the reactions
accelerated 1000x (Table V, the parenthesised column), solved as an ODE system with no flow and
no diffusion by scipy's Radau (5th-order implicit Runge-Kutta) at rtol 1e-11, and cross-checked
by BDF at rtol 1e-11 and by LSODA. docs/coagulation.md states the model and every correction of
the printed tables (section "Typos in the paper and what we use"); this file is the one place
the numbers live for the references, and the scenes repeat them.

Two cases, both in the CSV (column `case`):
  table3  Table III only: the plasma of Table II with 0.1 % active enzymes and no injury. The
          initial enzymes are quenched by the inhibitors: no thrombin burst.
  injury  Table III plus the injury terms of Table IV acting as volume sources in one
          well-mixed voxel next to the injured wall: each Table IV flux density (rate law times
          L, L = 100 the channel length) spread over a wall layer of thickness delta = 1. This
          is the chemistry at the injury site without transport; it shows the burst.

Usage: /usr/bin/python3 cascade_reference.py [--out cascade_reference.csv] [--check]
"""
import argparse
import math
import sys

import numpy as np
from scipy.integrate import solve_ivp

# Table II: (name in scenes, paper index, C_i0 [nM = tDPD concentration unit], Schmidt number)
SPECIES = [
    ("IXa", 1, 0.09, 15949), ("IX", 2, 90.0, 17762), ("VIIIa", 3, 0.0007, 25510),
    ("VIII", 4, 0.7, 32051), ("Va", 5, 0.02, 26178), ("V", 6, 20.0, 17762),
    ("Xa", 7, 0.17, 13568), ("X", 8, 170.0, 17762), ("IIa", 9, 1.4, 15456),
    ("II", 10, 1400.0, 19194), ("Ia", 11, 7.0, 40486), ("I", 12, 7000.0, 32258),
    ("XIa", 13, 0.03, 20000), ("XI", 14, 30.0, 25189), ("ATIII", 15, 2410.0, 17953),
    ("TFPI", 16, 2.5, 15873), ("APC", 17, 0.06, 18182), ("PC", 18, 60.0, 18382),
    ("a1AT", 19, 45000.0, 17182), ("tPA", 20, 0.08, 18939), ("PLA", 21, 2.18, 20284),
    ("PLS", 22, 2180.0, 20790), ("a2AP", 23, 105.0, 19048),
]
ASSIGNED = [("Z", 24, "VIIIa*IXa/0.56"), ("W", 25, "Va*Xa/0.1")]
NU = 138.6            # tDPD kinematic viscosity (li2015 sec. III C)
D_SELF = 0.00261      # D at kappa = 0
D_SLOPE = 0.0645      # D_i = 0.00261 + 0.0645 kappa_i
ACCELERATION = 1000.0
MINUTE = 60.0 / 1.386e-4  # one minute in tDPD time units (t* = 1.386e-4 s)

# Table V, tDPD units, NOT accelerated (the printed column without parentheses), with the
# corrections of docs/coagulation.md: h1 = 3.465e-3 (printed 3.456e-3), the second "K1M" is H1M,
# the decay rate of k_tPA^IIa is 134.8 / min (printed 972 580, i.e. multiplied by 1/t* instead
# of t*). Rate constants (k*, h*, phi11, ktPA*) are multiplied by ACCELERATION below;
# Michaelis constants and the wall densities are not.
TABLE_V = {
    "k9": 2.54e-5, "K9M": 160.0, "h9": 3.74e-8,
    "k8": 4.49e-4, "K8M": 1.12e5, "h8": 5.13e-7, "hC8": 2.36e-5, "HC8M": 14.6,
    "k5": 6.24e-5, "K5M": 140.5, "h5": 3.93e-7, "hC5": 2.36e-5, "HC5M": 14.6,
    "k10": 5.523e-3, "K10M": 160.0, "h10": 8.01e-7, "hTFPI": 1.11e-6,
    "k2": 3.105e-3, "K2M": 1060.0, "h2": 1.65e-6,
    "k1": 8.177e-3, "K1M": 3160.0, "h1": 3.465e-3, "H1M": 2.50e5,
    "k11": 1.80e-8, "K11M": 50.0, "h11A3": 3.70e-9, "h11L1": 3.00e-11,
    "kPC": 9.01e-5, "KPCM": 3190.0, "hPC": 1.52e-12,
    "kPLA": 2.77e-5, "KPLAM": 18.0, "hPLA": 2.22e-7,
    # Table IV (injury) parameters
    "k79": 7.48e-5, "K79M": 24.0, "k710": 2.38e-4, "K710M": 240.0,
    "phi11": 7.85e-8, "PHI11M": 2000.0,
    "ktPAC": 1.51e-6, "ktPAIIa": 2.14e-5, "ktPAIIa_decay": 134.8 / MINUTE, "ktPAIa": 1.17e-11,
    "TFVIIa": 0.25, "ENDO": 2.0e-3, "XIIa": 375.0,
}
# The physical column of Table V [min^-1, nM^-1 min^-1, or micrometre^2 min^-1 for ktPA*]:
# each tDPD value above is physical / MINUTE; check_table_v() asserts that to 0.5 %.
PHYSICAL = {
    "k9": 11, "h9": 0.0162, "k8": 194.4, "h8": 0.222, "hC8": 10.2, "k5": 27.0, "h5": 0.17,
    "hC5": 10.2, "k10": 2391, "h10": 0.347, "hTFPI": 0.48, "k2": 1344, "h2": 0.714,
    "k1": 3540, "h1": 1500, "k11": 0.0078, "h11A3": 1.6e-3, "h11L1": 1.3e-5, "kPC": 39.0,
    "hPC": 6.6e-7, "kPLA": 12.0, "hPLA": 0.096, "k79": 32.4, "k710": 103, "phi11": 0.034,
    "ktPAC": 0.652, "ktPAIIa": 9.27, "ktPAIIa_decay": 134.8, "ktPAIa": 5.059e-6,
}
L_INJURY = 100.0  # the length L of Table IV (= channel length; docs/coagulation.md)
DELTA = 1.0       # thickness of the wall layer that receives the flux in the well-mixed case


def rate_parameters():
    """Table V in tDPD units with the reactions accelerated (the values the scenes use)."""
    p = {}
    for k, v in TABLE_V.items():
        accelerated = k[0] in "kh" or k.startswith("phi")
        p[k] = v * ACCELERATION if accelerated else v
    return p


def check_table_v():
    worst = 0.0
    for k, phys in PHYSICAL.items():
        dev = abs(TABLE_V[k] / (phys / MINUTE) - 1.0)
        worst = max(worst, dev)
        if dev > 5e-3:
            raise SystemExit(f"Table V {k}: {TABLE_V[k]} vs physical/minute {phys / MINUTE}")
    return worst


def diffusivities():
    """(D_i = nu / Sc_i, kappa_i = (D_i - 0.00261) / 0.0645) per transported species."""
    return [(n, NU / sc, (NU / sc - D_SELF) / D_SLOPE) for n, _, _, sc in SPECIES]


def mm(k, km, e, s):
    return k * e * s / (km + s)


def table3_rates(p, y):
    """Table III source terms Q1..Q23 of the state y (23 x ... arrays: one voxel or many)."""
    (IXa, IX, VIIIa, VIII, Va, V, Xa, X, IIa, II, Ia, I, XIa, XI, AT, TFPI, APC, PC, a1AT,
     tPA, PLA, PLS, a2AP) = y
    Z = VIIIa * IXa / 0.56
    W = Va * Xa / 0.1
    r9 = mm(p["k9"], p["K9M"], XIa, IX)
    r8 = mm(p["k8"], p["K8M"], IIa, VIII)
    rc8 = mm(p["hC8"], p["HC8M"], APC, VIIIa)
    r5 = mm(p["k5"], p["K5M"], IIa, V)
    rc5 = mm(p["hC5"], p["HC5M"], APC, Va)
    r10 = mm(p["k10"], p["K10M"], Z, X)
    r2 = mm(p["k2"], p["K2M"], W, II)
    r1 = mm(p["k1"], p["K1M"], IIa, I)
    rh1 = mm(p["h1"], p["H1M"], PLA, Ia)
    r11 = mm(p["k11"], p["K11M"], IIa, XI)
    rpc = mm(p["kPC"], p["KPCM"], IIa, PC)
    rpla = mm(p["kPLA"], p["KPLAM"], tPA, PLS)
    return np.array([
        r9 - p["h9"] * IXa * AT, -r9,
        r8 - p["h8"] * VIIIa - rc8, -r8,  # Q4: sign corrected (VIII is consumed)
        r5 - p["h5"] * Va - rc5, -r5,
        r10 - p["h10"] * Xa * AT - p["hTFPI"] * TFPI * Xa, -r10,
        r2 - p["h2"] * IIa * AT, -r2,
        r1 - rh1, -r1,
        r11 - p["h11A3"] * XIa * AT - p["h11L1"] * XIa * a1AT, -r11,
        -(p["h9"] * IXa + p["h10"] * Xa + p["h2"] * IIa + p["h11A3"] * XIa) * AT,
        -p["hTFPI"] * TFPI * Xa,
        rpc - p["hPC"] * APC * a1AT, -rpc,
        -p["hPC"] * APC * a1AT - p["h11L1"] * XIa * a1AT,
        0.0 * tPA,  # Q20 = 0: tPA only enters through the wall
        rpla - p["hPLA"] * PLA * a2AP, -rpla, -p["hPLA"] * PLA * a2AP,
    ])


def add_injury_rates(p, t, y, d, f):
    """Adds the Table IV terms (flux densities) times f = L / delta to d, in place."""
    IX, X, IIa, Ia, XI = y[1], y[7], y[8], y[10], y[13]
    a = f * mm(p["k79"], p["K79M"], p["TFVIIa"], IX)
    b = f * mm(p["k710"], p["K710M"], p["TFVIIa"], X)
    c = f * mm(p["phi11"], p["PHI11M"], p["XIIa"], XI)
    ktpa = (p["ktPAC"] + p["ktPAIIa"] * math.exp(-p["ktPAIIa_decay"] * t) * IIa +
            p["ktPAIa"] * Ia)
    d[0] += a
    d[1] -= a
    d[6] += b
    d[7] -= b
    d[12] += c
    d[13] -= c
    d[19] += f * ktpa * p["ENDO"]


def rhs_factory(p, injury):
    flux_to_volume = L_INJURY / DELTA

    def rhs(t, y):
        d = table3_rates(p, y)
        if injury:
            add_injury_rates(p, t, y, d, flux_to_volume)
        return d

    return rhs


def solve(case, times, method="Radau", rtol=1e-11):
    p = rate_parameters()
    y0 = [c for _, _, c, _ in SPECIES]
    atol = [rtol * max(c, 1e-3) * 1e-3 for c in y0]
    sol = solve_ivp(rhs_factory(p, case == "injury"), (times[0], times[-1]), y0, method=method,
                    rtol=rtol, atol=atol, t_eval=times, dense_output=False)
    if not sol.success:
        raise SystemExit(f"{case}/{method}: {sol.message}")
    y = sol.y
    z = y[2] * y[0] / 0.56
    w = y[4] * y[6] / 0.1
    return np.vstack([y, z, w])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="cascade_reference.csv")
    ap.add_argument("--end", type=float, default=400.0)
    ap.add_argument("--every", type=float, default=5.0, help="output period after t = 5")
    args = ap.parse_args()
    worst_v = check_table_v()
    # every 0.25 up to t = 5 (the initial enzymes are quenched on that scale), then every `every`
    n = int(round(args.end / args.every))
    times = np.unique(np.concatenate([np.linspace(0.0, min(5.0, args.end), 21),
                                      np.linspace(0.0, args.end, n + 1)]))
    names = [s[0] for s in SPECIES] + [a[0] for a in ASSIGNED]
    rows = []
    checks = []
    for case in ("table3", "injury"):
        ref = solve(case, times, "Radau", 1e-11)
        bdf = solve(case, times, "BDF", 1e-11)
        lsoda = solve(case, times, "LSODA", 1e-10)
        scale = np.maximum(np.max(np.abs(ref), axis=1), 1e-30)[:, None]
        d_bdf = float(np.max(np.abs(ref - bdf) / scale))
        d_lsoda = float(np.max(np.abs(ref - lsoda) / scale))
        checks.append((case, d_bdf, d_lsoda))
        for k, t in enumerate(times):
            rows.append((case, t, ref[:, k]))
    with open(args.out, "w") as f:
        f.write("# li2015 sec. III C coagulation cascade (Anand et al. model), well-mixed: no flow, "
                "no diffusion; tDPD units, reactions accelerated 1000x (Table V parenthesised)\n")
        f.write("# generator: tests/data/refs/coagulation/cascade_reference.py (scipy Radau rtol "
                "1e-11, atol 1e-14 max(C0, 1e-3)); model and corrections: docs/coagulation.md\n")
        f.write(f"# command: /usr/bin/python3 cascade_reference.py --out {args.out} --end "
                f"{args.end:g} --every {args.every:g} (times: every 0.25 to 5, then every "
                f"{args.every:g})\n")
        f.write(f"# Table V tDPD column vs physical / minute: worst deviation {worst_v:.2e}\n")
        for case, d_bdf, d_lsoda in checks:
            f.write(f"# check {case}: max |Radau - BDF(1e-11)| / scale = {d_bdf:.2e}, "
                    f"|Radau - LSODA(1e-10)| / scale = {d_lsoda:.2e} (scale = max over t of the "
                    "species)\n")
        f.write("# column case: table3 (Table III only) or injury (Table III + Table IV as "
                f"volume sources, flux x L / delta, L = {L_INJURY:g}, delta = {DELTA:g})\n")
        f.write("# column t: time [tDPD units, t* = 1.386e-4 s; 1 min of accelerated chemistry = "
                f"{MINUTE / ACCELERATION:.4f}]\n")
        for (nm, idx, _, _) in SPECIES:
            f.write(f"# column {nm}: [{idx}] concentration [nM]\n")
        for (nm, idx, expr) in ASSIGNED:
            f.write(f"# column {nm}: [{idx}] = {expr} (assigned) [nM]\n")
        f.write("case,t," + ",".join(names) + "\n")
        for case, t, y in rows:
            f.write(f"{case},{t:.10g}," + ",".join(f"{v:.12e}" for v in y) + "\n")
    for case, d_bdf, d_lsoda in checks:
        print(f"{case}: Radau vs BDF {d_bdf:.2e}, vs LSODA {d_lsoda:.2e} (scaled max)")
    print(f"Table V worst deviation from physical/minute: {worst_v:.2e}; wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
