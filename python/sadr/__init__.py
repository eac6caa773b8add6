# SPDX-License-Identifier: MIT
"""sadr in Python: read runs, ensembles and sweeps, reduce them to time
series with confidence bands, build, edit and run scenes, and plot (docs/python.md).

From a checkout, with no installation: ``export PYTHONPATH=$PWD/python``
(Debian's /usr/bin/python3 with python3-numpy; pandas, xarray, matplotlib,
yaml and distributed where their parts are used).

    import sadr
    run = sadr.open("runs/quickstart")            # a Run, Ensemble or Sweep
    f = run.frame(-1)                             # the last frame, numpy arrays
    f.positions, f.velocity, f.species["T"]
    run.series("T", region=sadr.Box([0, 0], [0.5, 1]))
    sadr.plot_particles(f, color="T").savefig("T.png")
"""
from .cli import (EXIT_CODES, InvalidInput, Interrupted, IoFailure, NumericalFailure, SadrError,
                  ServiceFailure, UsageError, find_sadr, run_cli)
from .frames import (KIND_NAMES, Frame, FrameFormatError, read_csv_frame, read_ensemble_frame,
                     read_frame, read_pvd, read_vtk_arrays, read_vtk_frame)
from .geometry import Geometry
from .model import Expression, Hill, Law, MichaelisMenten, Model
from .regions import Box, Disk, Everything, Kinds, Region
from .runs import Ensemble, Run, open_output
from .scene import Scene
from .series import band, observe
from .sweep_file import SweepFile
from .sweeps import Sweep

__version__ = "0.1.0"  # the project's version (CMakeLists.txt; tests/python/test_package.py compares)

open = open_output  # noqa: A001 - sadr.open(path), like xarray.open_dataset


_PLOTS = ("plot_geometry", "plot_overview", "plot_particles", "plot_profile", "plot_series", "plot_sweep",
          "profile", "sweep_summary")


def __getattr__(name: str):
    # matplotlib (and Dask) only when asked for: sadr.plots, sadr.plot_*, sadr.dask_runner
    if name in _PLOTS or name in ("plots", "dask_runner"):
        import importlib

        module = importlib.import_module(f".{'plots' if name in _PLOTS else name}", __name__)
        return module if name in ("plots", "dask_runner") else getattr(module, name)
    raise AttributeError(f"module 'sadr' has no attribute '{name}'")


__all__ = [
    "Box", "Disk", "Ensemble", "Everything", "EXIT_CODES", "Expression", "Frame", "FrameFormatError", "Geometry",
    "Hill", "InvalidInput", "Interrupted", "IoFailure", "KIND_NAMES", "Kinds", "Law", "MichaelisMenten",
    "Model", "NumericalFailure",
    "Region", "Run", "SadrError", "Scene", "ServiceFailure", "Sweep", "SweepFile", "UsageError", "band", "find_sadr",
    "observe", "open", "open_output", "plot_geometry", "plot_overview", "plot_particles", "plot_profile", "plot_series",
    "plot_sweep", "profile", "read_csv_frame", "read_ensemble_frame", "read_frame", "read_pvd",
    "read_vtk_arrays", "read_vtk_frame", "run_cli", "sweep_summary",
]
