"""A killed command leaves no process behind: its render workers (and the resource tracker multiprocessing
starts for them) end within a second or so, and stop holding the caller's stderr; so do evaluation
workers. They waited forever, about 460 MB each, and a ``communicate()`` on the command never returned."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from l2p_bullet.core.lifeline import exit_with_parent


def _children() -> dict[int, list[int]]:
    """ppid -> pids, of every process now."""
    out: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:
            continue
        ppid = int(text.rpartition(")")[2].split()[1])
        out.setdefault(ppid, []).append(int(stat.parent.name))
    return out


def _descendants(pid: int) -> set[int]:
    tree, found, todo = _children(), set(), [pid]
    while todo:
        for c in tree.get(todo.pop(), []):
            if c not in found:
                found.add(c)
                todo.append(c)
    return found


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()[0]
    except OSError:
        return False
    return state != "Z"


def _wait_gone(pids: set[int], timeout: float) -> set[int]:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        left = {p for p in pids if _alive(p)}
        if not left:
            return set()
        time.sleep(0.05)
    return {p for p in pids if _alive(p)}


pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc (Linux)")


def test_a_worker_exits_when_its_parent_dies(tmp_path):
    """The lifeline alone: a grandchild watching its parent, which is then SIGKILLed."""
    code = ("import os, sys, time\n"
            "from l2p_bullet.core.lifeline import exit_with_parent\n"
            "me = os.getpid()\n"  # named before the fork: a parent killed first is not mistaken for init
            "pid = os.fork()\n"
            "if pid == 0:\n"
            "    exit_with_parent(me)\n"
            "    time.sleep(60)\n"
            "    os._exit(0)\n"
            "print(pid, flush=True)\n"
            "time.sleep(60)\n")
    parent = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    child = int(parent.stdout.readline())
    assert _alive(child)
    parent.kill()
    parent.wait(timeout=10)
    assert not _wait_gone({child}, 10.0), "the worker outlived its parent"


def test_a_worker_whose_parent_is_already_gone_exits_at_once():
    r = subprocess.run([sys.executable, "-c", "from l2p_bullet.core.lifeline import exit_with_parent; "
                        "exit_with_parent(1 if __import__('os').getppid() != 1 else 2); print('alive')"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and "alive" not in r.stdout


def test_the_watch_leaves_a_living_parent_alone():
    exit_with_parent(os.getppid(), poll_s=0.01)  # this test process's parent is alive: nothing happens
    time.sleep(0.05)


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGKILL, signal.SIGTERM])
def test_killing_a_rendering_perform_leaves_no_process_behind(tmp_path, signum):
    out = tmp_path / "run"
    env = {**os.environ, "L2P_RENDER_WORKERS": "2"}
    proc = subprocess.Popen([sys.executable, "-m", "l2p_bullet.cli", "perform", "move A around B", "--quiet",
                             "--out", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    t0, kids = time.monotonic(), set()
    while len(kids) < 3:  # the resource tracker and two render workers
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - t0 < 180, f"the render workers never started ({kids})"
        time.sleep(0.1)
        kids = _descendants(proc.pid)
    time.sleep(1.0)  # the workers are drawing
    kids = _descendants(proc.pid)
    proc.send_signal(signum)
    code = proc.wait(timeout=30)
    assert code == (-signal.SIGKILL if signum == signal.SIGKILL else 128 + signum)
    left = _wait_gone(kids, 5.0)
    for p in left:  # leave nothing behind on a failure either
        os.kill(p, signal.SIGKILL)
    assert not left, f"{len(left)} of {len(kids)} child processes outlived the killed perform"
    proc.communicate(timeout=10)  # nobody holds its stderr any more
