#!/usr/bin/python3
"""The stochastic variant's errors and noise against molecules per particle, realizations and
frames (docs/natural-convection.md, "Stochastic variant"), from analyse.py --json outputs.

    /usr/bin/python3 bench/natural_convection/stochastic_table.py A.json[=LABEL] [B.json[=LABEL] ...]

One row per JSON: N (molecules per particle at theta = 1; 0 = deterministic), realizations x frames
averaged, the errors in drawert2019's metric against the digitised profiles and the continuum
reference, the noise of the averaged profile in the same metric (sigma_frame over the window's
frames, divided by sqrt(frames): analyse.py's noise_metric_average), the rms difference from the
deterministic run at equal frame times where analyse.py was given --against, and Nu_half with the
standard deviation of one frame's Nu.
"""
import sys

from analyse import load_result


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| run | N | realizations x frames | theta vs digitised | theta vs continuum | noise of the average, theta "
          "| v* vs digitised | v* vs continuum | noise of the average, v* | rms theta - deterministic "
          "| Nu_half (sd of a frame) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for arg in sys.argv[1:]:
        a, label = load_result(arg)
        s = a["score"]
        frames = a["frames_averaged"] // max(a["realizations"], 1)
        diff = a.get("against", {}).get("theta_rms_diff")
        print("| %s | %s | %d x %d (t = %g-%g) | %.3e | %.3e | %.1e | %.3f | %.3f | %.3f | %s | %.3f (%.3f) |" % (
            label or arg, "%g" % a["molecules"] if a["molecules"] else "deterministic", a["realizations"], frames,
            a["window"][0], a["window"][1], s["theta_err_digitised"], s["theta_err_ref_at_digitised_x"],
            a["theta_noise_metric_average"], s["vstar_err_digitised"], s["vstar_err_ref_at_digitised_x"],
            a["vstar_noise_metric_average"], "-" if diff is None else "%.4f" % diff, s["Nu_half"],
            a["Nu_half_sd_frames"]))


if __name__ == "__main__":
    main()
