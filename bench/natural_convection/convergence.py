#!/usr/bin/python3
"""Errors against resolution (docs/natural-convection.md, "Convergence with resolution"), from
analyse.py --json outputs of one Ra at several lattice resolutions, averaged over the same window.

    /usr/bin/python3 bench/natural_convection/convergence.py A41.json=41 A81.json=81 A121.json=121

The number after = is the lattice points across the enclosure (dx = 1/N). Prints, per resolution,
the errors in drawert2019's metric ||.||_2 / n against the continuum reference on its 399 points
and against the digitised profiles on theirs, the maximum abs error against the continuum, the
Nusselt number's relative error, and the observed order ln(e_coarse / e_fine) / ln(dx_coarse /
dx_fine) between successive resolutions (the metric's 1/n makes the 399-point errors comparable
between resolutions: the points are the reference's, not the lattice's).
"""
import math
import sys

from analyse import load_result

COLS = (("theta_err_ref", "theta vs continuum (399 pts)", "%.3e"),
        ("theta_maxabs_ref", "theta max abs vs continuum", "%.4f"),
        ("theta_err_digitised", "theta vs digitised", "%.3e"),
        ("vstar_err_ref", "v* vs continuum (399 pts)", "%.4f"),
        ("vstar_maxabs_ref", "v* max abs vs continuum", "%.3f"),
        ("vstar_err_digitised", "v* vs digitised", "%.3f"),
        ("nu_rel", "Nu_half rel. to continuum", "%+.2f %%"))


def main():
    rows = []
    for arg in sys.argv[1:]:
        a, n = load_result(arg)
        s = dict(a["score"])
        s["nu_rel"] = 100 * (s["Nu_half"] / s["Nu_half_reference"] - 1)
        rows.append((int(n), a, s))
    rows.sort(key=lambda r: r[0])
    print("| lattice | window (frames) | " + " | ".join(c[1] for c in COLS) + " | max abs rho-1 |")
    print("|---|---|" + "---|" * len(COLS) + "---|")
    for n, a, s in rows:
        print("| %d^2 | %g-%g (%d) | " % (n, a["window"][0], a["window"][1], a["frames_averaged"])
              + " | ".join(fmt % s[k] for k, _, fmt in COLS) + " | %.2f %% |" % (100 * s["max_density_variation"]))
    for (n0, _, s0), (n1, _, s1) in zip(rows, rows[1:]):
        parts = []
        for k, name, _ in COLS:
            e0, e1 = abs(s0[k]), abs(s1[k])
            if e0 > 0 and e1 > 0:
                parts.append("%s %.2f" % (name.split(" (")[0], math.log(e0 / e1) / math.log(n1 / n0)))
        print("\nobserved order %d^2 -> %d^2: %s" % (n0, n1, "; ".join(parts)))


if __name__ == "__main__":
    main()
