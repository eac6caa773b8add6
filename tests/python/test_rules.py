# SPDX-License-Identifier: MIT
"""The package uses the product's rules, each defined once: the CLI's exit
codes, the --set path syntax, the region boundary tolerance, and the
Student t quantile of every band."""
import re
import subprocess
import sys

import numpy as np
import pytest

import sadr
from conftest import EXAMPLES, REPO
from sadr.paths import PathError, get_path, load_yaml, set_path, split_path

STATIC = EXAMPLES / "static_reaction_diffusion.yaml"


def test_exit_codes_are_the_cli_enum():
    """EXIT_CODES is the ExitCode enum of the CLI's source, code for code."""
    header = REPO / "orchestrator" / "campaign" / "include" / "sadr" / "orchestrator" / "exit_codes.hpp"
    text = header.read_text()
    enum = dict((name, int(code)) for name, code in re.findall(r"kExit(\w+) = (\d+),", text))
    assert enum.pop("Ok") == 0
    names = {"InvalidInput": sadr.InvalidInput, "Usage": sadr.UsageError,
             "ServiceFailure": sadr.ServiceFailure, "NumericalFailure": sadr.NumericalFailure,
             "IoFailure": sadr.IoFailure, "Interrupted": sadr.Interrupted}
    assert {code: names[name] for name, code in enum.items()} == sadr.EXIT_CODES
    e = sadr.cli.error_for(4, "sadr: error: blow-up\n  at step 3\n", ["sadr", "run"], "realization 2: sadr")
    assert type(e) is sadr.NumericalFailure and e.code == 4
    assert e.message == "realization 2: sadr exited with 4: sadr: error: blow-up\n  at step 3"
    assert type(sadr.cli.error_for(77, "", ["sadr"])) is sadr.SadrError


# Paths the CLI's parser takes or refuses (scene_override.cpp), with what they select.
GOOD = {"time.end": 0.3, "reactions[decay_A].rate": 2.5, "species[1].diffusivity": 0.02,
        "reactions[0].rate": 3000, "output.formats": ["csv"]}
BAD = ["a..b", "[0].x", "species[]", "time]end", "time.", "species[0]name", "species[0", ""]


def test_override_paths_select_what_the_cli_selects(tmp_path):
    """Setting each path in Python gives the scene `sadr validate --set` gives."""
    data = load_yaml(STATIC.read_text())
    for path, value in GOOD.items():
        set_path(data, path, value)
        assert get_path(data, path) == value
    edited = tmp_path / "edited.yaml"
    sadr.Scene(data).write(edited)
    by_cli = sadr.run_cli(["validate", STATIC] + sadr.scene.set_options(GOOD)).stderr
    by_python = sadr.run_cli(["validate", edited]).stderr
    assert by_python.replace(str(edited), "S") == by_cli.replace(str(STATIC), "S")
    assert "t_end = 0.3" in by_cli and by_cli != sadr.run_cli(["validate", STATIC]).stderr


@pytest.mark.parametrize("path", BAD)
def test_override_syntax_errors_are_the_clis(path):
    with pytest.raises(PathError, match="path"):
        split_path(path)
    proc = sadr.run_cli(["validate", STATIC, "--set", f"{path}=1"], check=False)
    assert proc.returncode == 1 and "--set" in proc.stderr, proc.stderr


def test_unknown_names_and_indices_raise():
    data = load_yaml(STATIC.read_text())
    with pytest.raises(PathError, match="no item named 'decay_X'.*decay_A"):
        set_path(data, "reactions[decay_X].rate", 1)
    with pytest.raises(PathError, match="index 9 is out of range"):
        get_path(data, "species[9].name")
    s = sadr.Scene(data)
    with pytest.warns(DeprecationWarning, match=r"species\[0\]\.name"):
        assert s["species.0.name"] == "A"  # the older dotted index still reads


def _frame(x):
    x = np.asarray(x, dtype=float)
    n = len(x)
    pos = np.zeros((n, 3))
    pos[:, 0] = x
    return sadr.Frame(0.0, np.arange(n, dtype=np.uint64), np.zeros(n, np.uint8), pos, np.zeros((n, 3)),
                      np.ones(n), np.ones(n), {})


def test_region_tolerance_is_the_loaders(tmp_path):
    """A 1D lattice x = k/10 and regions whose faces sit 5e-10 inside a lattice
    point (within the tolerance 1e-9 * box length: a member) or 5e-9 inside it
    (not a member). The scene loader marks its members with one molecule each;
    Python's regions select exactly those particles of the frame."""
    lower, upper = 0.2 + 5e-10, 0.5 - 5e-9
    scene = {"dimension": 1, "box": {"lower": [0.0], "upper": [1.0]},
             "regions": [{"name": "slab", "shape": "box", "lower": [lower], "upper": [upper]},
                         {"name": "ball", "shape": "disk", "center": [0.7], "radius": 0.1 - 5e-10}],
             "particles": {"spacing": 0.1}, "fluid": {"backend": "static", "h_over_dx": 2.0},
             "species": [{"name": "S", "diffusivity": 0.0, "initial": [{"region": "slab", "count": 1}]},
                         {"name": "D", "diffusivity": 0.0, "initial": [{"region": "ball", "count": 1}]}],
             "time": {"coupling_step": 0.1, "end": 0.1}, "output": {"times": [0.0], "formats": ["csv"]}}
    run = sadr.Scene(scene).run(tmp_path / "tol")
    f = run.frame(0)
    assert f.box_extent == 1.0
    for name, region in (("S", sadr.Box([lower], [upper])), ("D", sadr.Disk([0.7], 0.1 - 5e-10))):
        members = f.species[name] == 1
        np.testing.assert_array_equal(region.mask(f), members)
        assert members.sum() == 3  # 0.2, 0.3, 0.4 (not 0.5); 0.6, 0.7, 0.8


def test_frame_tolerance_from_the_run(static_ensemble):
    run = static_ensemble[0]
    assert run.box_extent == 1.0  # the scene's box, read through run.json
    f = run.frame(0)
    assert f.box_extent == 1.0 and sadr.regions.frame_tolerance(f) == 1e-9
    x = f.positions[0, 0]
    assert sadr.Box([x + 0.9e-9], [1.0]).mask(f)[0] and not sadr.Box([x + 1.1e-9], [1.0]).mask(f)[0]


def test_t_quantile_is_scipys_and_scipy_is_required():
    from scipy import stats

    for p, dof in ((0.975, 1), (0.975, 4), (0.995, 30), (0.6, 2)):
        assert sadr.series.t_quantile(p, dof) == stats.t.ppf(p, dof)
    code = ("import sys; sys.modules['scipy'] = None; import sadr\n"
            "try:\n    sadr.series.t_quantile(0.975, 4)\n"
            "except ImportError as e:\n    print('ImportError:', e)\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=REPO / "python")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("ImportError: sadr: confidence bands need scipy"), proc.stdout
