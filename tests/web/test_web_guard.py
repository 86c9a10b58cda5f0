"""Both web apps (review, teach) against a hostile web page and a hostile client (issue 27.3, 27.5, 27.7):
cross-site state-changing requests are refused, bodies are bounded before they are read (chunked ones
too), every page carries anti-framing headers, and any loopback --host keeps the Host check."""

from __future__ import annotations

import socket
import time
from pathlib import Path

import http_client
import pytest
from teach_fixtures import live  # noqa: F401 - fixture

from l2p_bullet.web.apps import MAX_BODY_BYTES, is_loopback

EVIL = {"Origin": "http://evil.example"}


@pytest.fixture
def review(tmp_path):
    """The review app over no runs (what is tested here is in front of every route)."""
    from l2p_bullet.review.app import create_app
    from l2p_bullet.review.queue import ReviewQueue
    from l2p_bullet.review.store import Store
    from l2p_bullet.web.server import start

    server = start(create_app(ReviewQueue(Store(tmp_path / "r.sqlite"), [], labels=["past"])))
    yield server.url
    server.stop()


ANSWER = {"reviewer": "ann", "key": "0123456789abcdef", "view": "3d", "grade": 3}


def test_cross_site_requests_to_the_teach_page_are_refused(live):  # noqa: F811
    """A page elsewhere posting ``text/plain`` to /api/train used to get 200 and retrain the plugin."""
    s = live()
    weights = sorted(p.name for p in Path(s.action.bundle_dir).iterdir())
    for headers in ({**EVIL, "Content-Type": "text/plain"}, EVIL, {"Content-Type": "text/plain"},
                    {"Sec-Fetch-Site": "cross-site"}, {"Origin": "null"}):
        status, r = http_client.call(s.url, "POST", "/api/train", raw=b"", headers=headers)
        assert status in (403, 415) and r["error"], (headers, status, r)
        status, r = http_client.call(s.url, "POST", "/api/demos", raw=b"{}", headers=headers)
        assert status in (403, 415), (headers, status, r)
    assert sorted(p.name for p in Path(s.action.bundle_dir).iterdir()) == weights
    assert s.lesson.config()["count"] == 0
    # the page itself (same origin, JSON) is served as before
    origin = {"Origin": s.url.rstrip("/"), "Sec-Fetch-Site": "same-origin"}
    status, r = http_client.call(s.url, "POST", "/api/train", raw=b"", headers=origin)
    assert status == 400 and "no demonstrations" in r["error"]


def test_cross_site_requests_to_the_review_app_are_refused(review):
    for path in ("/api/answer", "/api/skip"):
        for headers in (EVIL, {**EVIL, "Content-Type": "text/plain"}, {"Content-Type": "text/plain"}):
            status, r = http_client.call(review, "POST", path, ANSWER, headers=headers)
            assert status in (403, 415) and r["error"], (path, headers, status, r)
    status, r = http_client.call(review, "POST", "/api/answer", ANSWER, headers={"Origin": review.rstrip("/")})
    assert status == 404, r  # reaches the app: an unknown key


def test_the_production_host_allow_list_has_no_testserver(review, live):  # noqa: F811
    for url in (review, live().url):
        status, _ = http_client.call(url, "GET", "/api/config", headers={"Host": "testserver"})
        assert status == 400


def _raw(url: str, head: str, chunks, limit_s: float = 20) -> tuple[int, int]:
    """Send ``head`` then ``chunks`` (bytes) on a socket until the server answers; (status, bytes sent)."""
    host, port = url.split("//")[1].rstrip("/").rsplit(":", 1)
    sent = 0
    with socket.create_connection((host, int(port)), timeout=limit_s) as sock:
        sock.sendall(head.encode())
        sock.setblocking(False)
        deadline = time.monotonic() + limit_s
        reply = b""
        for chunk in chunks:
            try:
                reply += sock.recv(4096)
            except BlockingIOError:
                pass
            except OSError:
                break
            if reply or time.monotonic() > deadline:
                break
            try:
                sock.setblocking(True)
                sock.sendall(chunk)
                sent += len(chunk)
                sock.setblocking(False)
            except OSError:  # the server answered and closed: it read no further
                break
        sock.setblocking(True)
        while b"\r\n" not in reply:
            more = sock.recv(4096)
            if not more:
                break
            reply += more
    return int(reply.split()[1]), sent


@pytest.mark.parametrize("app", ["review", "teach"])
def test_request_bodies_are_bounded_before_they_are_read(review, live, app):  # noqa: F811
    """A 300 MB POST used to take the review server from 65 MB to 651 MB, never released."""
    url = review if app == "review" else live().url
    path = "/api/answer" if app == "review" else "/api/demos"
    hostport = url.split("//")[1].rstrip("/")
    # declared too large: refused before a byte of the body is read
    head = (f"POST {path} HTTP/1.1\r\nHost: {hostport}\r\nContent-Type: application/json\r\n"
            f"Content-Length: {300 * 2**20}\r\n\r\n")
    status, sent = _raw(url, head, (b"x" * 65536 for _ in range(4800)))
    assert status == 413 and sent < 64 * 2**20
    # chunked, no length: counted as it arrives, refused soon after the limit
    head = (f"POST {path} HTTP/1.1\r\nHost: {hostport}\r\nContent-Type: application/json\r\n"
            "Transfer-Encoding: chunked\r\n\r\n")
    piece = b"%x\r\n%s\r\n" % (65536, b" " * 65536)
    status, sent = _raw(url, head, (piece for _ in range(9600)))
    assert status == 413 and sent < 64 * 2**20
    # a body under the limit still reaches the app (a 422 from validation, not a 413)
    status, r = http_client.call(url, "POST", path, raw=b" " * (MAX_BODY_BYTES - 10) + b"{}")
    assert status == 422, r


def test_two_host_headers_and_a_foreign_origin_are_refused(review):
    """The Host check read the first Host header and the Origin check the last: a page at evil.example
    whose request carried ``Host: 127.0.0.1`` then ``Host: evil.example`` passed both. Uvicorn's h11
    refuses a request with two Host headers (400) before the guard sees it, so the guard is tested on its
    own, as another ASGI server would call it; through this server, such a request is refused too."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from l2p_bullet.web.apps import RequestGuard

    reached = []

    async def app(scope, receive, send):
        reached.append(scope["path"])
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"{}"})

    guard = RequestGuard(app, allowed_hosts=("127.0.0.1", "localhost", "[::1]"))

    async def post(hosts: tuple[str, ...], origin: str) -> int:
        sent: list[dict] = []

        async def receive():
            return {"type": "http.request", "body": b"{}", "more_body": False}

        async def send(message):
            sent.append(message)

        headers = [*((b"host", h.encode()) for h in hosts), (b"origin", origin.encode()),
                   (b"content-type", b"application/json"), (b"content-length", b"2")]
        await guard({"type": "http", "method": "POST", "path": "/api/train", "headers": headers}, receive, send)
        return sent[0]["status"]

    def run(coro):  # in a thread of its own, as in the websocket test below
        with ThreadPoolExecutor(1) as pool:
            return pool.submit(asyncio.run, coro).result()

    assert run(post(("127.0.0.1:8765", "evil.example"), "http://evil.example")) == 403
    assert run(post(("evil.example", "127.0.0.1:8765"), "http://127.0.0.1:8765")) == 400
    assert reached == []
    assert run(post(("127.0.0.1:8765",), "http://127.0.0.1:8765")) == 200 and reached == ["/api/train"]
    hostport = review.split("//")[1].rstrip("/")
    head = (f"POST /api/answer HTTP/1.1\r\nHost: {hostport}\r\nHost: evil.example\r\n"
            "Origin: http://evil.example\r\nContent-Type: application/json\r\nContent-Length: 2\r\n\r\n{}")
    assert _raw(review, head, [])[0] in (400, 403)


def test_pages_cannot_be_framed(review, live):  # noqa: F811
    import urllib.request

    for url in (review, live().url):
        for path in ("", "api/config", "static/nothing.js"):
            try:
                r = urllib.request.urlopen(url + path, timeout=30)
            except urllib.error.HTTPError as e:
                r = e
            assert r.headers["X-Frame-Options"] == "DENY"
            assert "frame-ancestors 'none'" in r.headers["Content-Security-Policy"]


@pytest.mark.parametrize("host, loop", [("127.0.0.1", True), ("127.0.0.2", True), ("::1", True),
                                        ("localhost", True), ("0.0.0.0", False), ("192.168.1.4", False)])
def test_any_loopback_address_is_loopback(host, loop):
    assert is_loopback(host) == loop


def test_a_server_on_127_0_0_2_keeps_the_host_check(tmp_path):
    """``--host 127.0.0.2`` used to skip the Host check (and warn that anyone could reach it)."""
    from l2p_bullet.review.app import create_app
    from l2p_bullet.review.queue import ReviewQueue
    from l2p_bullet.review.store import Store
    from l2p_bullet.web.server import start

    try:
        server = start(create_app(ReviewQueue(Store(tmp_path / "r.sqlite"), []), host="127.0.0.2"),
                       host="127.0.0.2")
    except Exception as e:  # pragma: no cover - a system without 127.0.0.0/8 routed
        pytest.skip(f"cannot bind 127.0.0.2: {e}")
    try:
        assert http_client.call(server.url, "GET", "/api/config")[0] == 200
        assert http_client.call(server.url, "GET", "/api/config", headers={"Host": "rebound.evil.example"})[0] == 400
    finally:
        server.stop()


@pytest.mark.parametrize("host, warned", [("0.0.0.0", True), ("127.0.0.1", False)])
def test_teach_off_loopback_says_anyone_can_write_demonstrations(tmp_path, monkeypatch, host, warned):
    """Off loopback the teach page answers any Host (and so any machine that can reach it): it says so
    before serving, as review does. It used to print only the address to open."""
    from click.testing import CliRunner

    from l2p_bullet.cli import main
    from l2p_bullet.plugins.scaffold import scaffold
    from l2p_bullet.web import server

    root = scaffold("zorp-near", ["zorpily near"], tmp_path / "l2p-zorp-near").root
    monkeypatch.setattr(server, "serve", lambda app, sock, log_level="warning": sock.close())
    r = CliRunner().invoke(main, ["teach", "zorp-near", "--plugin", str(root), "--host", host, "--port", "0"])
    assert r.exit_code == 0, r.output
    assert (f"warning: listening on {host}: anyone who can reach this machine can write demonstrations"
            in r.stderr) == warned, r.stderr


def test_a_database_moved_away_while_serving_is_said_never_recreated(tmp_path):
    """Issue 27.7: the database moved away while serving gave a 500 and a new empty database in its place."""
    from l2p_bullet.review.app import create_app
    from l2p_bullet.review.queue import ReviewQueue
    from l2p_bullet.review.store import Store
    from l2p_bullet.web.server import start

    db = tmp_path / "r.sqlite"
    server = start(create_app(ReviewQueue(Store(db), [], labels=["past"])))
    try:
        assert http_client.call(server.url, "GET", "/api/next?reviewer=ann")[0] == 200
        db.rename(tmp_path / "elsewhere.sqlite")
        status, r = http_client.call(server.url, "GET", "/api/next?reviewer=ann")
        assert status == 503 and "moved or deleted" in r["error"], r
        assert not db.exists(), "a fresh empty database was created in its place"
        (tmp_path / "other.sqlite").write_bytes((tmp_path / "elsewhere.sqlite").read_bytes())
        (tmp_path / "other.sqlite").rename(db)  # another file under the same name is not ours either
        status, r = http_client.call(server.url, "GET", "/api/next?reviewer=ann")
        assert status == 503 and "replaced" in r["error"], r
    finally:
        server.stop()


def test_a_database_made_read_only_while_serving_is_said(tmp_path):
    import os

    from l2p_bullet.review.store import DatabaseUnavailable, Store

    if os.geteuid() == 0:
        pytest.skip("root writes to read-only files")
    store = Store(tmp_path / "r.sqlite")
    store.path.chmod(0o444)
    with pytest.raises(DatabaseUnavailable, match="read-only"), store.transaction() as conn:
        conn.execute("CREATE TABLE written_after_chmod (x)")


def _head(url: str, path: str, headers: dict | None = None) -> tuple[int, dict, bytes]:
    """(status, headers (lower-case names), body) of a raw request, whatever its content type."""
    import http.client

    host, port = url.split("//")[1].rstrip("/").rsplit(":", 1)
    method = "GET"
    if path.startswith("HEAD "):
        method, path = "HEAD", path[5:]
    conn = http.client.HTTPConnection(host, int(port), timeout=30)
    try:
        conn.request(method, path, headers=headers or {})
        r = conn.getresponse()
        return r.status, {k.lower(): v for k, v in r.getheaders()}, r.read()
    finally:
        conn.close()


def test_a_foreign_host_is_refused_in_json_with_the_security_headers(review, live):  # noqa: F811
    """The refusal was ``400 text/plain "Invalid host header"`` without the headers every response carries."""
    import json

    for url in (review, live().url):
        for path in ("/api/config", "/"):
            status, headers, body = _head(url, path, {"Host": "evil.example"})
            assert status == 400 and headers["content-type"] == "application/json", (url, path, headers)
            assert "host" in json.loads(body)["error"]
            assert headers["x-frame-options"] == "DENY" and "frame-ancestors" in headers["content-security-policy"]
        assert _head(url, "/api/config", {"Host": "localhost:1"})[0] == 200


@pytest.mark.parametrize(
    "raw",
    [b'{"reviewer": "m\xff"}', b"[" * 100_000 + b"]" * 100_000, b'{"grade": ' + b"9" * 5000 + b"}"],
    ids=["invalid-utf8", "deep-nesting", "5000-digit-int"],
)
def test_bodies_json_cannot_parse_are_the_documented_422(review, live, raw):  # noqa: F811
    """They were ``400 "There was an error parsing the body"``."""
    teach = live().url
    for url, path in ((review, "/api/answer"), (teach, "/api/demos"), (teach, "/api/rows"), (teach, "/api/train")):
        status, r = http_client.call(url, "POST", path, raw=raw)
        assert status == 422 and r == {"error": "the request body is not valid JSON"}, (path, status, r)


def test_head_is_answered_where_get_is(review):
    status, headers, body = _head(review, "HEAD /")
    assert status == 200 and body == b"" and headers["content-type"].startswith("text/html")
    assert headers["x-frame-options"] == "DENY"


@pytest.mark.parametrize("host", ["[::1]evil.com", "localhost:80@evil.com", "127.0.0.1:abc", "localhost.", ""])
def test_a_host_header_starlette_cannot_parse_is_refused(review, host):
    """The guard that replaced TrustedHostMiddleware read ``[::1]evil.com`` as ``[::1]``, ``localhost:80@evil.com``
    and ``127.0.0.1:abc`` as loopback hosts; Starlette's own rule refuses them (and an empty Host)."""
    import json

    status, headers, body = _head(review, "/api/config", {"Host": host})
    assert status == 400 and "host" in json.loads(body)["error"], (host, status, body)
    assert headers["x-frame-options"] == "DENY"
    for good in ("127.0.0.1", "LOCALHOST:1", "[::1]:8765"):
        assert _head(review, "/api/config", {"Host": good})[0] == 200, good


def test_a_websocket_to_a_foreign_host_is_closed_before_the_app_sees_it():
    """Websocket scopes went past the Host check; TrustedHostMiddleware refused them too."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from l2p_bullet.web.apps import RequestGuard

    reached = []

    async def app(scope, receive, send):
        reached.append(scope["type"])

    guard = RequestGuard(app, allowed_hosts=("127.0.0.1", "localhost", "[::1]"))

    async def handshake(host: str | None) -> list[dict]:
        sent: list[dict] = []

        async def receive():
            return {"type": "websocket.connect"}

        async def send(message):
            sent.append(message)

        headers = [] if host is None else [(b"host", host.encode("latin-1"))]
        await guard({"type": "websocket", "path": "/ws", "headers": headers}, receive, send)
        return sent

    def run(coro):  # in a thread of its own: a browser test before this one may leave this thread's loop running
        with ThreadPoolExecutor(1) as pool:
            return pool.submit(asyncio.run, coro).result()

    for host in ("evil.example", "[::1]evil.com", "localhost:80@evil.com", "127.0.0.1:abc", None):
        sent = run(handshake(host))
        assert [m["type"] for m in sent] == ["websocket.close"] and not reached, (host, sent)
    assert run(handshake("localhost:8765")) == [] and reached == ["websocket"]
