# SPDX-License-Identifier: MIT
"""Running sadr and measuring what a run costs, for the validation report.

Cost is CPU time: user + system time of `sadr` and of the services it starts
and reaps (fluid_service, ssa_service), from os.wait4 on the sadr process.
On a shared machine wall time depends on the other users; CPU time much less
(it still grows somewhat under load: caches and memory bandwidth are shared).
"""
import os
import pathlib
import subprocess
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]


def commit() -> str:
    """Short hash of HEAD of this repository, '+dirty' when the tree has changes."""
    try:
        h = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                           capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "-uno"],
                               capture_output=True, text=True).stdout.strip()
        return h + ("+dirty" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


GNU_TIME = "/usr/bin/time"


def run_measured(cmd, cwd=None, env=None, log=None, own_peak=False) -> dict:
    """Runs cmd; returns wall, user, sys, cpu [s], peak RSS [KiB] of the process
    tree that was reaped (ru_maxrss of the largest), and the exit code.
    stdout/stderr go to `log` (a path) or are discarded.

    A process forked from Python starts with Python's own peak RSS as its
    ru_maxrss (Linux carries the forked image's high-water mark across exec), so
    a small command never reads below this script's size. own_peak=True runs
    the command under GNU time (Debian package `time`), whose child is forked
    from a ~2 MB process, and reports that child's peak instead."""
    argv = [str(c) for c in cmd]
    peak_file = None
    if own_peak:
        if not os.access(GNU_TIME, os.X_OK):
            raise RuntimeError(f"{GNU_TIME} not found: install Debian's `time` package")
        fd, peak_file = tempfile.mkstemp(prefix="sadr-peak-")
        os.close(fd)
        argv = [GNU_TIME, "-f", "%M", "-o", peak_file] + argv
    out = open(log, "w") if log else subprocess.DEVNULL
    try:
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
    finally:
        if log:
            out.close()
    peak = ru.ru_maxrss
    if peak_file:
        lines = pathlib.Path(peak_file).read_text().split()
        os.unlink(peak_file)
        peak = int(lines[-1])  # after "Command exited with non-zero status N", if any
    return {"wall_s": wall, "user_s": ru.ru_utime, "sys_s": ru.ru_stime,
            "cpu_s": ru.ru_utime + ru.ru_stime, "maxrss_kib": peak, "rc": p.returncode,
            "cmd": " ".join(str(c) for c in cmd)}


def median(xs):
    s = sorted(xs)
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])
