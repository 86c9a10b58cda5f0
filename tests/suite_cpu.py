"""CPU seconds per test and per unit of work (an xdist group), for sizing the suite on a shared machine, where wall
time says more about the neighbours than about the tests.

As a pytest plugin (tests/ is on pytest's ``pythonpath``), with ``SUITE_CPU`` naming a file prefix::

    SUITE_CPU=/tmp/cpu nice -n 10 .venv/bin/python -m pytest -q -n auto --dist loadgroup -p suite_cpu

each worker appends one JSON line per test to ``/tmp/cpu.<worker>.jsonl``: the CPU time of the worker itself and of
the processes it started and waited for (a test's subprocesses: pip, a trained plugin's CLI, a benchmark), from
the test's setup to its teardown, so a module fixture counts in the test that made it. A browser started for the
session (Chromium) is waited for only at the end, and is not counted. Then::

    .venv/bin/python tests/suite_cpu.py /tmp/cpu [N]

prints the N costliest groups and tests, and the two workers' loads when the groups are handed out longest first
(the scheduler's order, tests/conftest.py), measured rather than guessed."""

from __future__ import annotations

import heapq
import json
import os
import resource
import sys
import time
from collections import defaultdict
from pathlib import Path

import pytest

VARIABLE = "SUITE_CPU"


def _cpu() -> tuple[float, float]:
    own, waited = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime, waited.ru_utime + waited.ru_stime


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    prefix = os.environ.get(VARIABLE)
    if not prefix:
        yield
        return
    (own0, waited0), wall0 = _cpu(), time.perf_counter()
    yield
    (own1, waited1), wall1 = _cpu(), time.perf_counter()
    mark = item.get_closest_marker("xdist_group")
    group = str(mark.args[0]) if mark is not None and mark.args else item.nodeid.split("::")[0]
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    row = {"test": item.nodeid.split("@")[0], "group": group, "own_s": round(own1 - own0, 3),
           "children_s": round(waited1 - waited0, 3), "wall_s": round(wall1 - wall0, 3), "worker": worker}
    with open(f"{prefix}.{worker}.jsonl", "a") as f:
        f.write(json.dumps(row) + "\n")


def load(prefix: str) -> list[dict]:
    """Every row the workers wrote under ``prefix``."""
    folder, stem = Path(prefix).parent, Path(prefix).name
    return [json.loads(line) for path in sorted(folder.glob(f"{stem}.*.jsonl")) for line in path.open()]


def two_workers(seconds: dict[str, float], workers: int = 2) -> list[float]:
    """Each worker's CPU seconds when the groups go, longest first, to whichever worker is free first."""
    free = [(0.0, w) for w in range(workers)]
    loads = [0.0] * workers
    for group in sorted(seconds, key=lambda g: -seconds[g]):
        at, w = heapq.heappop(free)
        loads[w] = at + seconds[group]
        heapq.heappush(free, (loads[w], w))
    return loads


def report(rows: list[dict], n: int = 30) -> str:
    groups: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0, 0])
    for r in rows:
        g = groups[r["group"]]
        g[0] += r["own_s"]
        g[1] += r["children_s"]
        g[2] += 1
    seconds = {k: v[0] + v[1] for k, v in groups.items()}
    total = sum(seconds.values())
    lines = [f"{len(rows)} tests, {len(groups)} groups, {total:.1f} CPU s "
             f"({sum(v[0] for v in groups.values()):.1f} in the workers, "
             f"{sum(v[1] for v in groups.values()):.1f} in their subprocesses)",
             "two workers, longest group first: " + " + ".join(f"{s:.1f}" for s in two_workers(seconds)) + " CPU s",
             "", f"{'CPU s':>7} {'own':>7} {'child':>7} {'tests':>5}  group"]
    for k in sorted(seconds, key=lambda k: -seconds[k])[:n]:
        own, child, count = groups[k]
        lines.append(f"{own + child:7.1f} {own:7.1f} {child:7.1f} {count:5d}  {k}")
    lines += ["", f"{'CPU s':>7}  test"]
    for r in sorted(rows, key=lambda r: -(r["own_s"] + r["children_s"]))[:n]:
        lines.append(f"{r['own_s'] + r['children_s']:7.1f}  {r['test']}")
    return "\n".join(lines)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: python tests/suite_cpu.py PREFIX [N]")
    print(report(load(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 30))
