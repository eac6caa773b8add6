#!/usr/bin/python3
"""The docs table of steady, averaged natural-convection runs (docs/natural-convection.md), from
analyse.py --json outputs, beside drawert2019's Table 2 and the continuum reference's own floor.

    /usr/bin/python3 bench/natural_convection/table.py A.json[=NOTE] [B.json[=NOTE] ...]

NOTE (optional) is appended to the row's variant, e.g. "stationary walls, c0 = 3.5" for a run of
an older version of the scene.

Errors in drawert2019's metric ||f - f_ref||_2 / n on the digitised points (n as in the paper's
Table 2): against the digitised Moukalled & Acharya profiles, and against the continuum reference
interpolated to the same points.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tests", "data", "refs", "natural_convection"))
from compare_digitised import load  # noqa: E402
from analyse import load_result  # noqa: E402

# drawert2019 Table 2: (theta SDPD, theta SSA, v* SDPD, v* SSA)
PAPER = {10000: (2.587e-3, 2.205e-3, 0.347, 0.347), 100000: (2.307e-3, 2.447e-3, 1.373, 1.409),
         1000000: (3.222e-3, 2.867e-3, 4.378, 4.666)}


def main():
    floor = load(os.path.join(HERE, "..", "..", "tests", "data", "refs", "natural_convection",
                              "continuum_vs_digitised.csv"))
    rows = []
    for arg in sys.argv[1:]:
        a, note = load_result(arg)
        a["note"] = note
        rows.append(a)
    print("| Ra | variant | t steady | window (frames) | theta vs digitised | theta vs continuum "
          "| v* vs digitised | v* vs continuum | Nu_half (rel. to continuum) | max abs rho-1 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for ra in sorted({a["Ra"] for a in rows}):
        p = PAPER[ra]
        k = list(floor["Ra"]).index(ra)
        e = "1e%d" % round(math.log10(ra))
        print("| %s | drawert2019 Table 2, SDPD / SSA | (t = 50) | 100 realizations | %.3e / %.3e | - "
              "| %.3f / %.3f | - | - | - |" % (e, p[0], p[1], p[2], p[3]))
        print("| %s | continuum reference (floor) | steady | - | %.2e | 0 | %.3f | 0 | %.4f | - |"
              % (e, floor["theta_error"][k], floor["vstar_error"][k], floor["Nu_half_cylinder"][k]))
        for a in [a for a in rows if a["Ra"] == ra]:
            s = a["score"]
            var = "SSA, N = %g, %d real." % (a["molecules"], a["realizations"]) if a["molecules"] else "SDPD"
            if a["note"]:
                var += ", " + a["note"]
            nu = s["Nu_half"] / s["Nu_half_reference"] - 1
            ts = "%g" % max(a["t_steady"]) if a["steady"] else "not steady (last rates E/Nu_c/Nu_e %s); --from %g" % (
                "/".join("%.0e" % v if v is not None else "-" for r in a["last_rates"].values() for v in r.values()), a["window"][0])
            print("| %s | %s | %s | %g-%g (%d) | **%.3e** | %.3e | **%.3f** | %.3f | %.3f (%+.1f %%) | %.2f %% |"
                  % (e, var, ts, a["window"][0], a["window"][1], a["frames_averaged"],
                     s["theta_err_digitised"], s["theta_err_ref_at_digitised_x"], s["vstar_err_digitised"],
                     s["vstar_err_ref_at_digitised_x"], s["Nu_half"], 100 * nu, 100 * s["max_density_variation"]))


if __name__ == "__main__":
    main()
