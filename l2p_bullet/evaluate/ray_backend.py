"""The Ray backend: the same tasks on Ray actors, one :class:`~l2p_bullet.evaluate.worker.Worker` per actor.

``address`` is a cluster's address (``ray://host:10001``, ``host:6379``), ``auto`` (the cluster this
machine belongs to), or ``local``: an embedded Ray started here with ``workers`` CPUs and stopped at the
end, which is how CI tests this path without a cluster. Actors live for the whole evaluation, so each
keeps its loaded bundles like a pool worker does; tasks go to whichever actor is free. A lost actor
(its process died, its node went away) turns its task into a row with the error and is replaced.

Ray is an optional extra (``pip install 'l2p-bullet[ray]'``) and is imported only here. Its usage
statistics are switched off (``RAY_USAGE_STATS_ENABLED=0``) unless the user set that variable: nothing
is sent off the machine. Every node of a cluster needs l2p-bullet (and any action plugins) installed;
kept run folders are written on the node that ran them.
"""

from __future__ import annotations

import os
import signal
import socket
import threading
from collections.abc import Callable, Iterable

from ..errors import EvaluationError, MissingExtraError
from .tasks import Task
from .worker import Worker, error_row


def _import_ray():
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
    os.environ.setdefault("RAY_DEDUP_LOGS", "0")
    try:
        # lazy: ray is an optional extra (l2p-bullet[ray])
        import ray
    except ImportError:
        raise MissingExtraError("ray", "ray", "--ray") from None
    return ray


class _Actor:
    """The body of a Ray actor: one Worker, kept for the actor's life."""

    def __init__(self) -> None:
        signal.signal(signal.SIGINT, signal.SIG_IGN)

        self.worker = Worker()

    def run(self, task: dict) -> dict:
        return self.worker.run(Task(**task))


CONNECT_TIMEOUT_S = 30.0
"""How long joining a cluster may take: Ray itself retries an address nobody answers on forever."""


def connect_timeout() -> float:
    """:data:`CONNECT_TIMEOUT_S`, or the seconds in ``L2P_RAY_CONNECT_TIMEOUT`` (tests, slow networks)."""
    try:
        value = float(os.environ.get("L2P_RAY_CONNECT_TIMEOUT", CONNECT_TIMEOUT_S))
    except ValueError:
        value = CONNECT_TIMEOUT_S
    return value if 0 < value < 1e6 else CONNECT_TIMEOUT_S


def _connect(ray, address: str, timeout: float) -> None:
    """``ray.init(address)`` given up after ``timeout`` seconds with a one-line EvaluationError. A
    ``host:port`` that refuses a TCP connection is said at once; one that accepts but never answers as Ray
    does (or ``auto`` naming a cluster that is gone) is given up when the timeout ends: ``ray.init`` runs in
    a daemon thread, left behind blocked (nothing of it is used) when the command exits."""
    hostport = address.removeprefix("ray://")
    host, sep, port = hostport.rpartition(":")
    if sep and host and port.isdigit():
        try:
            socket.create_connection((host.strip("[]"), int(port)), timeout=min(timeout, 10.0)).close()
        except OSError as e:
            raise EvaluationError(f'cannot reach Ray at "{address}": {e.strerror or type(e).__name__}; is a Ray '
                                  "cluster running there (ray start --head)?") from None
    outcome: dict = {}

    def init() -> None:
        try:
            ray.init(address=address, log_to_driver=False, configure_logging=False, logging_level="ERROR")
            outcome["ok"] = True
        except BaseException as e:  # handed to the caller's thread
            outcome["error"] = e

    thread = threading.Thread(target=init, daemon=True, name="ray-connect")
    thread.start()
    thread.join(timeout)
    if "error" in outcome:
        raise outcome["error"]
    if "ok" not in outcome:
        raise EvaluationError(f'Ray at "{address}" did not answer within {timeout:g} s; check the address '
                              "(ray status on the cluster) or set L2P_RAY_CONNECT_TIMEOUT")


def run_ray(tasks: Iterable[Task], address: str, workers: int, on_row: Callable[[dict], None]) -> None:
    """Run ``tasks`` on Ray (see the module docstring); ``on_row`` gets every row as it arrives."""
    ray = _import_ray()
    pending = list(tasks)
    if not pending:
        return
    started = False
    try:
        if not ray.is_initialized():
            if address == "local":
                ray.init(num_cpus=max(1, workers), include_dashboard=False, log_to_driver=False,
                         configure_logging=False, logging_level="ERROR")
            else:
                _connect(ray, address, connect_timeout())
            started = True
    except EvaluationError:
        raise
    except Exception as e:  # ConnectionError, ValueError... from Ray: the user's address is wrong
        raise EvaluationError(f'cannot start or reach Ray at "{address}": {type(e).__name__}: {e}') from None
    try:
        n = workers if workers > 0 else max(1, int(ray.cluster_resources().get("CPU", 1)))
        actor_cls = ray.remote(num_cpus=1, max_restarts=0)(_Actor)
        actors = [actor_cls.remote() for _ in range(min(n, len(pending)))]
        queue = list(reversed(pending))
        in_flight: dict = {}

        def submit(actor) -> None:
            task = queue.pop()
            in_flight[actor.run.remote(task.to_dict())] = (actor, task)

        for actor in actors:
            if queue:
                submit(actor)
        while in_flight:
            done, _ = ray.wait(list(in_flight), num_returns=1)
            ref = done[0]
            actor, task = in_flight.pop(ref)
            try:
                row = ray.get(ref)
            except (ray.exceptions.RayActorError, ray.exceptions.WorkerCrashedError,
                    ray.exceptions.ObjectLostError) as e:
                row = error_row(task, "WorkerDied", f"the Ray worker died while running this task: {type(e).__name__}")
                actor = actor_cls.remote()
            on_row(row)
            if queue:
                submit(actor)
    finally:
        if started:
            ray.shutdown()
