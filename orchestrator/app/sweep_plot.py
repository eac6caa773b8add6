#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Summary plot of a sadr sweep (docs/sweeps.md): a shortcut for

    PYTHONPATH=python /usr/bin/python3 -m sadr plot SWEEP_DIR [--species A] [--parameter PATH]
                      [-o SWEEP_DIR/summary.png]

which is its one home (python/sadr/__main__.py, sadr.plot_sweep): the mean
species total at the last frame against a swept parameter with 95 % confidence
bands, from SWEEP_DIR/observables.csv, and the table it plotted on stdout.
Needs Debian's python3-matplotlib and python3-pandas (deploy/install-deps.sh)."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))

from sadr.__main__ import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(["plot"] + sys.argv[1:]))
