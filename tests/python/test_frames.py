# SPDX-License-Identifier: MIT
"""Frame loaders against frames written by the product: CSV, VTU and VTP,
binary and ASCII VTK, all bit-identical; an independent CSV parse (Python's
csv + float) and, where python3-vtk9 is installed, VTK's own reader."""
import csv
import importlib.util

import numpy as np
import pandas as pd
import pytest

import sadr

FIELDS = ("ids", "kinds", "positions", "velocity", "density", "mass")


def assert_frames_equal(a, b):
    assert a.time == b.time
    for name in FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert np.array_equal(x, y), f"{name} differs between {a.path} and {b.path}"
    assert list(a.species) == list(b.species)
    for s in a.species:
        assert np.array_equal(a.species[s], b.species[s]), s


def test_run_layout(poiseuille_runs):
    run = poiseuille_runs["binary"]
    assert run.status == "ok"
    assert len(run) == 6
    assert run.times.tolist() == [k * 0.1 for k in range(6)]  # frame k at k * every, exactly
    assert run.species == ["T"]
    assert {"fluid", "transfer", "output"} <= set(run.timings)
    f = run.frame(0)
    assert len(f) == 560 and f.positions.shape == (560, 3)
    assert np.count_nonzero(f.kinds == 1) == 160  # 4 wall rows of 20 at each side


def test_csv_vtu_vtp_identical_both_encodings(poiseuille_runs):
    binary, ascii_ = poiseuille_runs["binary"], poiseuille_runs["ascii"]
    moved = False
    for k in range(len(binary)):
        ref = binary.frame(k, "csv")
        assert ref.time == binary.times[k]
        for run in (binary, ascii_):
            for fmt in ("csv", "vtu", "vtp"):
                assert_frames_equal(ref, run.frame(k, fmt))
        moved |= not np.array_equal(ref.positions, binary.frame(0).positions)
    assert moved, "the fluid particles should move in the Poiseuille flow"
    # the ASCII file really is ASCII, the binary one really is appended raw data
    assert b'format="ascii"' in ascii_.files[1]["vtu"].read_bytes()
    assert b'<AppendedData encoding="raw">' in binary.files[1]["vtu"].read_bytes()


def test_csv_against_python_float(poiseuille_runs):
    """An independent parse: csv module + float() (correctly rounded)."""
    run = poiseuille_runs["binary"]
    f = run.frame(-1)
    with open(run.files[-1]["csv"], newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(f)
    assert [int(r["id"]) for r in rows] == f.ids.tolist()
    assert [int(r["kind"]) for r in rows] == f.kinds.tolist()
    for a, name in enumerate("xyz"):
        assert [float(r[name]) for r in rows] == f.positions[:, a].tolist()
    for a, name in enumerate(("vx", "vy", "vz")):
        assert [float(r[name]) for r in rows] == f.velocity[:, a].tolist()
    assert [float(r["density"]) for r in rows] == f.density.tolist()
    assert [float(r["T"]) for r in rows] == f.species["T"].tolist()


def test_pandas_needs_round_trip(poiseuille_runs):
    """What docs/python.md says: pandas is exact with float_precision='round_trip'."""
    run = poiseuille_runs["binary"]
    f = run.frame(-1)
    df = pd.read_csv(run.files[-1]["csv"], float_precision="round_trip")
    assert np.array_equal(df["density"].to_numpy(), f.density)
    assert np.array_equal(df[["x", "y", "z"]].to_numpy(), f.positions)
    pd.testing.assert_frame_equal(f.to_pandas(), df, check_dtype=False, check_exact=True)


def test_tracer_conserved_and_advected(poiseuille_runs):
    """T has no reactions and 'none' walls: every frame holds the initial 8000
    molecules (100 on each of the 80 stripe particles)."""
    run = poiseuille_runs["binary"]
    totals = run.series("T")["T"].to_numpy()
    assert totals.tolist() == [8000.0] * len(run)
    walls = run.series("T", region="wall")["T"].to_numpy()
    assert walls.tolist() == [0.0] * len(run)
    last = run.frame(-1)
    assert last.speed[last.kinds == 0].max() > 0  # the body force has set the fluid moving


def test_errors_name_the_file(tmp_path, poiseuille_runs):
    bad = tmp_path / "frame_000000.csv"
    bad.write_text("a,b\n1,2\n")
    with pytest.raises(sadr.FrameFormatError, match="frame_000000.csv:1: not a sadr frame CSV"):
        sadr.read_frame(bad)
    vtu = poiseuille_runs["binary"].files[0]["vtu"].read_bytes()
    cut = tmp_path / "cut.vtu"
    cut.write_bytes(vtu.replace(b'Name="mass"', b'Name="massive"'))
    with pytest.raises(sadr.FrameFormatError, match="missing point arrays: mass"):
        sadr.read_frame(cut)
    with pytest.raises(FileNotFoundError, match="no run.json"):
        sadr.Run(tmp_path)


HAVE_VTK = importlib.util.find_spec("vtk") is not None


@pytest.mark.skipif(not HAVE_VTK, reason="python3-vtk9 is not installed (apt-get install "
                    "python3-vtk9 to compare against VTK's own XML readers)")
@pytest.mark.parametrize("encoding", ["binary", "ascii"])
def test_against_vtk_reader(poiseuille_runs, encoding):
    from vtk import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
    from vtk.util.numpy_support import vtk_to_numpy

    run = poiseuille_runs[encoding]
    for fmt, cls in (("vtu", vtkXMLUnstructuredGridReader), ("vtp", vtkXMLPolyDataReader)):
        path = run.files[-1][fmt]
        ours = sadr.read_frame(path)
        reader = cls()
        reader.SetFileName(str(path))
        reader.Update()
        grid = reader.GetOutput()
        pd_ = grid.GetPointData()
        assert np.array_equal(vtk_to_numpy(grid.GetPoints().GetData()), ours.positions)
        assert np.array_equal(vtk_to_numpy(pd_.GetArray("id")), ours.ids)
        assert np.array_equal(vtk_to_numpy(pd_.GetArray("kind")), ours.kinds)
        assert np.array_equal(vtk_to_numpy(pd_.GetArray("velocity")), ours.velocity)
        for name in ("density", "mass", "T"):
            assert np.array_equal(vtk_to_numpy(pd_.GetArray(name)), ours.field(name)), name
        t = vtk_to_numpy(grid.GetFieldData().GetArray("TimeValue"))
        assert t[0] == ours.time
