# SPDX-License-Identifier: MIT
"""`python3 -m sadr plot DIR [-o PNG] [--species S] [--parameter P]`: the
overview figure of a run (sadr.plots.overview), or for a sweep directory the
species total at the last frame against a swept parameter with its 95 % band
(sadr.plot_sweep; the table plotted, sadr.sweep_summary, is printed as CSV), as
a PNG; `python3 -m sadr series RUN`: the species totals per frame as CSV;
`python3 -m sadr plot-geometry DIR_OR_SCENE [-o PNG] [--color kind|regions|REGION]`:
the particles `sadr geometry` made (DIR/particles.csv, or a scene's geometry
section, built with `sadr geometry` into a temporary folder), coloured by kind
or region (sadr.plot_geometry: 2D a scatter, 3D three slices through the centre).
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
    geo = sub.add_parser("plot-geometry", help="particles of `sadr geometry` coloured by kind or region (PNG)")
    geo.add_argument("source", type=Path, help="output folder of `sadr geometry`, or a scene file with a "
                     "geometry section")
    geo.add_argument("-o", "--output", type=Path,
                     help="PNG path (default: DIR/geometry.png, or SCENE_STEM-geometry.png here)")
    geo.add_argument("--color", default="kind", help="kind (default), regions, or a region's name")
    geo.add_argument("--dpi", type=int, default=80)
    args = ap.parse_args(argv)
    if args.command == "plot-geometry":
        return plot_geometry_command(args)
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


def plot_geometry_command(args: argparse.Namespace) -> int:
    """`plot-geometry`: read or make the particles, draw them, write the PNG."""
    import tempfile

    from .cli import SadrError, run_cli
    from .geometry import read_particles

    source: Path = args.source
    try:
        if source.is_dir():
            particles = read_particles(source)
            out = args.output or source / "geometry.png"
        elif source.is_file():
            with tempfile.TemporaryDirectory(prefix="sadr-geometry-") as tmp:
                proc = run_cli(["geometry", source, "--output", tmp])
                sys.stdout.writelines(ln for ln in proc.stdout.splitlines(True)
                                      if not ln.startswith("wrote "))  # the folder is temporary
                particles = read_particles(tmp)
            out = args.output or Path(f"{source.stem}-geometry.png")
        else:
            raise FileNotFoundError(f"{source}: no such folder or scene file")
        from .plots import plot_geometry

        fig = plot_geometry(particles, args.color, title=f"{source}: {len(particles)} particles by {args.color}")
    except SadrError as e:
        print(f"python3 -m sadr: error: {e.message}", file=sys.stderr)
        return 1
    except (FileNotFoundError, ValueError) as e:
        print(f"python3 -m sadr: error: {e}", file=sys.stderr)
        return 1
    fig.savefig(out, dpi=args.dpi)
    print(f"python3 -m sadr: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
