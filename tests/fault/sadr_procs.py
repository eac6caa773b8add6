"""What the process-level tests share: a process's children and name, whether
it still runs, and the files a sadr process may leave behind (issue #18).
Used by tests/fault/campaign.py and tests/hostile/parent_death_test.py."""
import glob, os, tempfile

TMP = tempfile.gettempdir()


def children(pid):
    """Child pids of `pid` (every thread's children)."""
    out = []
    for tid in glob.glob(f"/proc/{pid}/task/*"):
        try:
            with open(tid + "/children") as f:
                out += [int(c) for c in f.read().split()]
        except OSError:
            pass
    return out


def comm(pid):
    """The process name ("" once it is gone)."""
    try:
        with open(f"/proc/{pid}/comm") as f:
            return f.read().strip()
    except OSError:
        return ""


def running(pid):
    """True while `pid` exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def traces(pid):
    """Geometry segments, run directories and sockets named after sadr process `pid`."""
    return (glob.glob(f"/dev/shm/sadr-geometry-{pid}-*") +
            glob.glob(os.path.join(TMP, f"sadr-run-{pid}-*")) +
            glob.glob(os.path.join(TMP, f"sadr-{pid}-*")))
