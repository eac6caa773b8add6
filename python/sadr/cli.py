# SPDX-License-Identifier: MIT
"""Calling the `sadr` executable: where it is, and its exit codes as exceptions.

The executable is, in this order: ``$SADR_BIN`` (the file, or the folder
holding it), ``sadr`` on ``PATH``, then ``build/release/bin/sadr`` and
``build/ci/bin/sadr`` of the repository this package sits in.
"""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path


class SadrError(RuntimeError):
    """`sadr` exited with a non-zero code; ``message`` is what it printed on
    stderr (its error lines), ``code`` the exit code, ``command`` the command
    and ``stderr`` all it printed there."""

    code: int | None = None

    def __init__(self, message: str, code: int | None, command, stderr: str = ""):
        super().__init__(message)
        self.message, self.code, self.command, self.stderr = message, code, command, stderr


class InvalidInput(SadrError):
    """Exit 1: invalid scene or input."""


class UsageError(SadrError):
    """Exit 2: unknown command or option, missing argument."""


class ServiceFailure(SadrError):
    """Exit 3: a service died, did not answer, or refused the protocol."""


class NumericalFailure(SadrError):
    """Exit 4: non-finite values, blow-up, broken stability limit."""


class IoFailure(SadrError):
    """Exit 5: cannot write outputs or checkpoints."""


class Interrupted(SadrError):
    """Exit 130: SIGINT/SIGTERM (a checkpoint was written)."""


EXIT_CODES: dict[int, type[SadrError]] = {
    1: InvalidInput, 2: UsageError, 3: ServiceFailure, 4: NumericalFailure, 5: IoFailure,
    130: Interrupted}
"""The CLI's exit codes (the ExitCode enum of
orchestrator/campaign/include/sadr/orchestrator/exit_codes.hpp; tests/python/test_rules.py
compares them) and the exception of each. The one
table in this package: every failing `sadr` call raises through error_for()."""


def error_for(returncode: int, stderr: str, command, what: str = "sadr") -> SadrError:
    """The exception for a `sadr` process that exited with ``returncode``:
    the SadrError subclass of the code (SadrError for an unknown code), its
    message "WHAT exited with CODE: <the CLI's error lines>"."""
    cls = EXIT_CODES.get(returncode, SadrError)
    return cls(f"{what} exited with {returncode}: {_message(stderr or '')}", returncode,
               command, stderr or "")


def find_sadr() -> Path:
    """Path of the `sadr` executable (see the module doc for the search order)."""
    env = os.environ.get("SADR_BIN")
    if env:
        p = Path(env)
        if p.is_dir():
            p = p / "sadr"
        if not os.access(p, os.X_OK):
            raise FileNotFoundError(f"SADR_BIN={env}: no executable sadr there")
        return p
    on_path = shutil.which("sadr")
    if on_path:
        return Path(on_path)
    repo = Path(__file__).resolve().parents[2]
    for preset in ("release", "ci"):
        p = repo / "build" / preset / "bin" / "sadr"
        if os.access(p, os.X_OK):
            return p
    raise FileNotFoundError("no sadr executable: set SADR_BIN to it (or its folder), put it on "
                            f"PATH, or build it ({repo}/build/release/bin/sadr)")


def _message(stderr: str) -> str:
    """The CLI's error text: from its first 'error:' line to the end (the error
    and the lines that detail it), else the last lines of stderr."""
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    first = next((i for i, ln in enumerate(lines) if "error:" in ln), None)
    return "\n".join(lines[first:] if first is not None else lines[-20:]) or "(no message on stderr)"


def run_cli(args, *, check: bool = True, capture: bool = True, cwd=None,
            env=None) -> subprocess.CompletedProcess:
    """Runs ``sadr ARGS...``; returns the CompletedProcess (text stdout/stderr
    when ``capture``). A non-zero exit raises the SadrError subclass of its
    code, carrying the CLI's message."""
    command = [str(find_sadr())] + [str(a) for a in args]
    kwargs = {"stdout": subprocess.PIPE, "stderr": subprocess.PIPE} if capture else {}
    proc = subprocess.run(command, text=True, cwd=cwd, env=env, **kwargs)
    if check and proc.returncode != 0:
        raise error_for(proc.returncode, proc.stderr, command)
    return proc
