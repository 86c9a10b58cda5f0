"""A real two-node Ray cluster on this machine, for tests: ``ray start --head`` and a second ``ray start
--address`` worker node, both bound to the loopback address, each with one CPU.

Ray resolves 127.0.0.1 to the machine's own address (``services.resolve_ip_for_localhost``); nothing
leaves the machine. Each node runs ``ray start --block`` as a child of the test, so stopping it is a
SIGTERM to a process the test started (Ray drains and stops that node's processes), never ``ray stop``,
which would stop every Ray on the machine. A private ``--temp-dir`` keeps the cluster out of
``/tmp/ray`` (where ``ray.init()`` looks for a cluster to join), and a token made here (RAY_AUTH_TOKEN,
token authentication) keeps it to this test.
"""

from __future__ import annotations

import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

RAY = Path(sys.executable).parent / "ray"
STARTED = "Ray runtime started"


def _free_ports(n: int) -> list[int]:
    socks = [socket.socket() for _ in range(n)]
    try:
        for s in socks:
            s.bind(("127.0.0.1", 0))
        return [s.getsockname()[1] for s in socks]
    finally:
        for s in socks:
            s.close()


def _node_args(ports: list[int]) -> list[str]:
    """Every port a node would otherwise take at a fixed default (two nodes on one machine must differ)."""
    names = ("--node-manager-port", "--object-manager-port", "--metrics-export-port",
             "--dashboard-agent-listen-port", "--dashboard-agent-grpc-port", "--runtime-env-agent-port")
    return [x for name, port in zip(names, ports, strict=True) for x in (name, str(port))]


def _wait(proc: subprocess.Popen, log: Path, timeout: float) -> None:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        text = log.read_text() if log.exists() else ""
        if STARTED in text:
            return
        if proc.poll() is not None:
            raise RuntimeError(f"ray start exited ({proc.returncode}): {text[-1500:]}")
        time.sleep(0.3)
    raise RuntimeError(f"ray start did not come up in {timeout:.0f} s: {log.read_text()[-1500:]}")


def _refresh_ray_config() -> None:
    """Ray reads RAY_AUTH_MODE and the token once, when it is imported: a test process that imported it
    before (another test, ``importorskip``) must re-read them, as Ray itself does when it turns tokens on."""
    if "ray" not in sys.modules:
        return
    from ray._raylet import AuthenticationTokenLoader, Config

    Config.initialize("")
    AuthenticationTokenLoader.instance().reset_cache()


@contextmanager
def two_node_cluster(timeout: float = 120.0) -> Iterator[str]:
    """Start the cluster; yield its address ("127.0.0.1:PORT"); stop both nodes. While it runs, this process
    has the cluster's token in its environment (a driver connecting with ``ray.init(address=...)`` needs it)."""
    tmp = Path(tempfile.mkdtemp(prefix="l2pray", dir="/tmp"))  # short: Ray's socket paths must stay < 108 chars
    saved = {k: os.environ.get(k) for k in ("RAY_AUTH_MODE", "RAY_AUTH_TOKEN", "RAY_USAGE_STATS_ENABLED")}
    os.environ.update(RAY_AUTH_MODE="token", RAY_AUTH_TOKEN=secrets.token_hex(32), RAY_USAGE_STATS_ENABLED="0")
    _refresh_ray_config()
    ports = _free_ports(13)
    common = ["--node-ip-address", "127.0.0.1", "--num-cpus", "1", "--disable-usage-stats", "--block"]
    procs: list[subprocess.Popen] = []
    try:
        for i, args in enumerate([
            ["--head", "--port", str(ports[0]), "--temp-dir", str(tmp), "--include-dashboard", "false",
             *_node_args(ports[1:7])],
            ["--address", f"127.0.0.1:{ports[0]}", *_node_args(ports[7:13])],
        ]):
            log = tmp / f"node{i}.log"
            with log.open("w") as out:
                procs.append(subprocess.Popen([str(RAY), "start", *args, *common], stdout=out,
                                              stderr=subprocess.STDOUT, env=dict(os.environ), start_new_session=True))
            _wait(procs[-1], log, timeout)
        yield f"127.0.0.1:{ports[0]}"
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in reversed(procs):
            try:
                p.wait(timeout=60)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
        _refresh_ray_config()
        shutil.rmtree(tmp, ignore_errors=True)
