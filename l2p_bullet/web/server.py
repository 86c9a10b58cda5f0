"""Running the review app (and the teach page, ``l2p_bullet.teach``) with uvicorn: on a socket bound here
(so the port is known, 0 picks a free one), in the foreground for ``l2p-bullet review`` / ``teach`` or in
a thread for tests and benchmarks."""

from __future__ import annotations

import errno
import socket
import threading
import time
from dataclasses import dataclass

from ..errors import ReviewError


def bind(host: str, port: int) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as e:
        sock.close()
        if e.errno == errno.EADDRINUSE:
            raise ReviewError(
                f"port {port} on {host} is in use; pass another --port (or --port 0 for a free one)"
            ) from None
        raise ReviewError(f"cannot listen on {host}:{port}: {e.strerror or e}") from None
    sock.listen(128)
    return sock


def url_of(sock: socket.socket) -> str:
    host, port = sock.getsockname()[:2]
    return f"http://{f'[{host}]' if ':' in host else host}:{port}/"


def _server(app, log_level: str):
    # lazy: the web stack only when a server runs
    import uvicorn

    return uvicorn.Server(uvicorn.Config(app, log_level=log_level, access_log=False, lifespan="off"))


def serve(app, sock: socket.socket, log_level: str = "warning") -> None:
    """Serve until Ctrl+C (uvicorn handles the signal and finishes the requests under way)."""
    _server(app, log_level).run(sockets=[sock])


@dataclass
class RunningServer:
    url: str
    server: object
    thread: threading.Thread

    def stop(self) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=10)


def start(app, host: str = "127.0.0.1", port: int = 0, log_level: str = "warning",
          name: str = "review-server") -> RunningServer:
    """Serve ``app`` in a daemon thread; returns once it accepts connections."""
    sock = bind(host, port)
    server = _server(app, log_level)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True, name=name)
    thread.start()
    deadline = time.monotonic() + 20
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise ReviewError(f"the server ({name}) did not start")
        time.sleep(0.02)
    return RunningServer(url_of(sock), server, thread)
