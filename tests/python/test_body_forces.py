# SPDX-License-Identifier: MIT
"""Run.body_forces(): the fluid's force and torque on bodies, read from body_forces.csv."""
import json
from pathlib import Path

import pytest

import sadr

SCENE = Path(__file__).resolve().parents[1] / "orchestrator" / "obstacle_defaults" / "obstacle_defaults.yaml"


@pytest.fixture(scope="module")
def obstacle_run(tmp_path_factory, sadr_bin):
    """The obstacle scene, 5 coupling steps, with the force on its disk of wall particles."""
    s = sadr.Scene.load(SCENE)
    s["time.end"] = 0.1
    s["fluid.body_forces"] = ["cell"]
    return s.run(tmp_path_factory.mktemp("obstacle") / "run")


def test_rows_per_stage_and_the_last_equals_run_json(obstacle_run):
    run = sadr.Run(obstacle_run.path)
    table = run.body_forces()
    assert list(table.columns) == ["t", "dt", "body", "Fx", "Fy", "Fz", "Tx", "Ty", "Tz"]
    assert len(table) == 5  # one fluid stage per coupling step (lie splitting)
    assert table["t"].iloc[-1] == pytest.approx(0.1)
    assert (table["dt"] > 0).all()
    manifest = json.loads((run.path / "run.json").read_text())
    last = manifest["body_forces"]["cell"]["force"]
    # 17 significant digits in the CSV: the doubles come back exactly
    assert [table[c].iloc[-1] for c in ("Fx", "Fy", "Fz")] == last
    # the flow is driven along +x: the drag on the disk points downstream
    assert table["Fx"].iloc[-1] > 0
    assert run.body_forces("cell").equals(table)


def test_unknown_body_and_missing_file_are_named(obstacle_run, tmp_path):
    run = sadr.Run(obstacle_run.path)
    with pytest.raises(KeyError, match="no body 'wall' \\(bodies: cell\\)"):
        run.body_forces("wall")
    (tmp_path / "run.json").write_text(json.dumps({"format": "sadr-run"}))
    with pytest.raises(FileNotFoundError, match="no fluid.body_forces"):
        sadr.Run(tmp_path).body_forces()
