# SPDX-License-Identifier: MIT
"""Fixtures: small runs written by the product (the `sadr` of $SADR_BIN, set
by ctest to the build's bin folder), shared by the tests of one session."""
import os
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "python"))

import sadr  # noqa: E402

EXAMPLES = REPO / "examples"
# One OpenMP thread per service: the suite runs next to other ctest jobs.
os.environ.setdefault("OMP_NUM_THREADS", "1")
if os.environ.get("SADR_BIN"):  # absolute: some tests run sadr from other folders
    os.environ["SADR_BIN"] = str(Path(os.environ["SADR_BIN"]).resolve())


def pytest_report_header(config):
    try:
        return f"sadr executable: {sadr.find_sadr()}"
    except FileNotFoundError as e:
        return f"sadr executable: none ({e})"


@pytest.fixture(scope="session")
def sadr_bin():
    path = sadr.find_sadr()  # raises with the search order if missing: a failure, not a skip
    return path


def poiseuille(end=0.5, every=0.1, encoding="binary", formats=("vtu", "vtp", "csv")):
    """The Poiseuille tracer example, shortened: particles move, T is advected."""
    s = sadr.Scene.load(EXAMPLES / "poiseuille_tracer_2d.yaml")
    s["time.end"] = end
    s["output.every"] = every
    s["output.formats"] = list(formats)
    s["output.vtk_encoding"] = encoding
    return s


@pytest.fixture(scope="session")
def poiseuille_runs(tmp_path_factory, sadr_bin):
    """The same short Poiseuille run written with binary and with ASCII VTK."""
    root = tmp_path_factory.mktemp("poiseuille")
    return {enc: poiseuille(encoding=enc).run(root / enc) for enc in ("binary", "ascii")}


def static_scene(end=0.5, every=0.25):
    s = sadr.Scene.load(EXAMPLES / "static_reaction_diffusion.yaml")
    s["time.end"] = end
    s["output.every"] = every
    return s


@pytest.fixture(scope="session")
def static_ensemble(tmp_path_factory, sadr_bin):
    """4 realizations of the static reaction-diffusion example (stochastic A, deterministic B)."""
    root = tmp_path_factory.mktemp("ensemble")
    return static_scene().run(root / "ens", realizations=4, jobs=2)
