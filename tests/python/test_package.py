# SPDX-License-Identifier: MIT
"""python/ is an installable package: pip installs it offline into a venv
that sees Debian's numpy, pandas, scipy, matplotlib and yaml, and the
installed package works away from the checkout."""
import re
import shutil
import subprocess
import sys

import pytest

import sadr
from conftest import REPO


def test_version_is_the_projects():
    cmake = (REPO / "CMakeLists.txt").read_text()
    assert sadr.__version__ == re.search(r"project\(sadr VERSION ([0-9.]+)", cmake).group(1)


def test_pip_installs_offline_into_a_venv(tmp_path, sadr_bin):
    probe = subprocess.run([sys.executable, "-c", "import ensurepip, venv"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip("python3-venv is not installed (apt install python3-venv)")
    source = tmp_path / "src"  # pip builds in place: a copy keeps the checkout clean
    shutil.copytree(REPO / "python", source, ignore=shutil.ignore_patterns("__pycache__", "build",
                                                                           "*.egg-info"))
    env_dir = tmp_path / "env"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", env_dir],
                   check=True)
    python = env_dir / "bin" / "python"
    # Debian's pip (python3-pip) from the system site, no index: nothing is downloaded
    proc = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                           "--no-deps", "--disable-pip-version-check", "-q", source],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    check = subprocess.run([python, "-m", "pip", "check", "--disable-pip-version-check"],
                           capture_output=True, text=True)
    assert "sadr" not in check.stdout, check.stdout  # its dependencies are all installed
    code = ("import sadr, sys; m = sadr.Model.load(sys.argv[1]); print(sadr.__file__); "
            "print(sadr.__version__); print(m.validate().splitlines()[-1])")
    run = subprocess.run([python, "-c", code, REPO / "examples" / "static_reaction_diffusion.yaml"],
                         capture_output=True, text=True, cwd=tmp_path,
                         env={"PATH": "/usr/bin:/bin", "SADR_BIN": str(sadr_bin)})
    assert run.returncode == 0, run.stderr
    where, version, last = run.stdout.splitlines()
    assert where.startswith(str(env_dir)) and version == sadr.__version__
    assert last.endswith(": valid")
