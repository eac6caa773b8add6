# SPDX-License-Identifier: MIT
"""`python3 -m sadr plot DIR [-o PNG] [--species S] [--parameter P]`: the
overview figure of a run (sadr.plots.overview), or for a sweep directory the
species total at the last frame against a swept parameter with its 95 % band
(sadr.plot_sweep; the table plotted, sadr.sweep_summary, is printed as CSV), as
a PNG; `python3 -m sadr series RUN`: the species totals per frame as CSV.
The one home of the sweep summary plot (orchestrator/app/sweep_plot.py calls it)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import open_output


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python3 -m sadr", description=__doc__)
    sub = ap.add_subparsers(dest="command", required=True)
    plot = sub.add_parser("plot", help="overview PNG of a run")
    plot.add_argument("run", type=Path, help="output directory of `sadr run`")
    plot.add_argument("-o", "--output", type=Path, help="PNG path (default: RUN/overview.png)")
    plot.add_argument("--species", help="species to colour by / plot (default: the first)")
    plot.add_argument("--parameter", help="sweep: the swept path on the x axis (default: the first)")
    plot.add_argument("--dpi", type=int, default=80)
    series = sub.add_parser("series", help="species totals per frame (CSV)")
    series.add_argument("run", type=Path)
    args = ap.parse_args(argv)
    try:
        run = open_output(args.run)
    except (FileNotFoundError, ValueError) as e:
        print(f"python3 -m sadr: error: {e}", file=sys.stderr)
        return 1
    from .sweeps import Sweep

    if isinstance(run, Sweep) and args.command == "plot":
        from .plots import plot_sweep, sweep_summary

        if not run.parameters:
            print(f"python3 -m sadr: error: {args.run}: the sweep has no parameters; nothing "
                  "to plot against", file=sys.stderr)
            return 1
        table = run.table()
        names = list(table.columns[len(run.parameters) + 4:])
        species = args.species or names[0]
        param = args.parameter or run.parameters[0]
        for what, value, allowed in (("--species", species, names),
                                     ("--parameter", param, run.parameters)):
            if value not in allowed:
                print(f"python3 -m sadr: error: {what} {value}: allowed: {', '.join(allowed)}",
                      file=sys.stderr)
                return 1
        sys.stdout.write(sweep_summary(table, param, species).to_csv(index=False))
        fig = plot_sweep(table, param, species)
        out = args.output or args.run / "summary.png"
        fig.savefig(out, dpi=args.dpi)
        print(f"python3 -m sadr: wrote {out}")
        return 0
    if not hasattr(run, "frame"):
        print(f"python3 -m sadr: error: {args.run} is not a single run (pick one realization_NNNN)",
              file=sys.stderr)
        return 1
    if args.command == "series":
        run.series().to_csv(sys.stdout)
        return 0
    from .plots import overview

    out = args.output or args.run / "overview.png"
    overview(run, args.species).savefig(out, dpi=args.dpi)
    print(f"python3 -m sadr: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
