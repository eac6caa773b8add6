# SPDX-License-Identifier: MIT
"""examples/notebooks/getting_started.ipynb executes end to end (nbconvert,
Debian's python3-nbconvert + python3-ipykernel) and shows its four figures."""
import os
import re
import subprocess
import sys

import nbformat

from conftest import REPO


def test_getting_started_executes(tmp_path):
    src = REPO / "examples" / "notebooks" / "getting_started.ipynb"
    env = dict(os.environ, SADR_NOTEBOOK_OUT=str(tmp_path / "runs"))
    proc = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                           "--ExecutePreprocessor.timeout=300", "--output-dir", str(tmp_path), str(src)],
                          cwd=src.parent, env=env, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-3000:]
    nb = nbformat.read(tmp_path / "getting_started.ipynb", as_version=4)
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    images = [o for o in outputs if "data" in o and "image/png" in o["data"]]
    assert len(images) == 4
    text = "".join(o.get("text", "") for o in outputs)
    assert "molecules per frame (conserved: no reactions, walls 'none'): [8000.]" in text
    # the flow against the start-up solution between the example's effective walls
    # (measured 8e-4 of the centre-line speed at t = 4)
    err = float(re.search(r"profile RMS error / u_centre = (\S+)", text).group(1))
    assert err < 5e-3
    assert (tmp_path / "runs" / "channel" / "run.json").is_file()
    assert len(list((tmp_path / "runs" / "ensemble").glob("realization_*"))) == 6
