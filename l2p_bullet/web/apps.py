"""What the review app and the teach page share as web apps: loopback-only hosts, JSON errors, the page.

Every error a page can get is JSON ``{"error": message}`` with a 4xx status (a malformed request: 422; an
answer that cannot be taken: the app's own status), never a traceback; a bug is a 500 with the
exception's type only, its traceback in the server's log.
"""

from __future__ import annotations

import ipaddress
import logging
import re
from collections.abc import Callable
from importlib import resources
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from starlette.exceptions import HTTPException as StarletteHTTPException

from .. import __version__

LOOPBACK = ("127.0.0.1", "localhost", "::1")
"""Hosts a server binds to by default; bound there, it answers only requests addressed to them."""

MAX_BODY_BYTES = 4 * 2**20
"""The largest request body either app reads (413 past it, counted as it arrives, chunked or not): the
largest legitimate one, a teach recording of 20,000 samples, is about 2 MB."""
STATE_CHANGING = ("POST", "PUT", "PATCH", "DELETE")
SECURITY_HEADERS = (
    (b"x-frame-options", b"DENY"),
    (b"content-security-policy", b"default-src 'self'; img-src 'self' data: blob:; media-src 'self' blob:; "
                                 b"frame-ancestors 'none'; base-uri 'none'; form-action 'self'; object-src 'none'"),
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
)
"""On every response: no page of another site may frame ours (clickjacking), and ours loads nothing
from elsewhere."""


def is_loopback(host: str) -> bool:
    """``localhost`` or any loopback address (127.0.0.0/8, ::1): only this machine can connect."""
    if host.strip("[]").lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False

UserError = Callable[[Exception], tuple[int, dict]]
"""An app's own errors -> (status, extra JSON fields)."""


def new_app(title: str, host: str, extra_hosts: tuple[str, ...] = ()) -> FastAPI:
    """A FastAPI app without the API docs pages; bound to loopback, it refuses other Host headers so
    a web page elsewhere cannot reach it through a rebound DNS name (in :class:`RequestGuard`, so the
    refusal is JSON and carries the security headers like every other answer)."""
    app = FastAPI(title=title, version=__version__, docs_url=None, redoc_url=None)
    hosts = None
    if is_loopback(host):
        bound = f"[{host.strip('[]')}]" if ":" in host else host
        hosts = tuple(dict.fromkeys(h.lower() for h in ["127.0.0.1", "localhost", "[::1]", bound, *extra_hosts]))
    app.add_middleware(RequestGuard, allowed_hosts=hosts)
    return app


_HOST_RE = re.compile(
    r"^(?P<host>[a-z0-9._~%!$&'()*+,;=-]+|\[(?:(?P<ipv6>[a-f0-9]*:[a-f0-9.:]+)|"
    r"(?-i:v)[a-f0-9]+\.[a-z0-9._~!$&'()*+,;=:-]+)\])(?::(?P<port>[0-9]+))?$",
    re.IGNORECASE,
)
"""Starlette's own Host rule (``starlette._utils.parse_host_header``, private, so copied exactly from
Starlette 1.10): a reg-name, or an IP literal in brackets, then an optional numeric port; nothing else."""


def host_name(header: str | None) -> str | None:
    """The host of a Host header, lower case and without its port (``[::1]:8765`` -> ``[::1]``), or None
    when the header is missing or not a host[:port] by Starlette's rule: ``[::1]evil.com``,
    ``localhost:80@evil.com`` and ``127.0.0.1:abc`` are refused as TrustedHostMiddleware refused them, not
    read as a loopback host."""
    match = None if header is None else _HOST_RE.fullmatch(header)
    if match is None:
        return None
    if match["ipv6"] is not None:
        try:
            ipaddress.IPv6Address(match["ipv6"])
        except ipaddress.AddressValueError:
            return None
    return match["host"].lower()


class RequestGuard:
    """ASGI middleware for both apps: refuses cross-site state-changing requests and bodies over
    :data:`MAX_BODY_BYTES`, and adds :data:`SECURITY_HEADERS` to every response.

    With ``allowed_hosts`` (a server bound to loopback), a request whose Host header names another host,
    or is missing or malformed, is refused (400) first, and a websocket handshake closed (403): a rebound
    DNS name must not reach the app, over HTTP or a websocket.

    A web page elsewhere can make the browser send a "simple" request (``text/plain``, no preflight) to
    a server on this machine: ``POST /api/train`` would retrain a plugin. So every POST/PUT/PATCH/DELETE
    must be ``application/json`` (which a browser only sends cross-origin after a CORS preflight that
    these apps never grant) and, when the browser says where it comes from (``Origin``,
    ``Sec-Fetch-Site``), come from this very server. The body is read here, counting bytes as they
    arrive (a chunked body has no Content-Length to check), and handed to the app only when it is small.
    """

    def __init__(self, app, max_body: int = MAX_BODY_BYTES, allowed_hosts: tuple[str, ...] | None = None):
        self.app, self.max_body, self.allowed_hosts = app, max_body, allowed_hosts

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] == "websocket" and not self.host_allowed(scope):
            # before accepting: the server answers the handshake 403 (TrustedHostMiddleware refused here too)
            await send({"type": "websocket.close", "code": 1008, "reason": "invalid host header"})
            return
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        held: list = []  # a text/plain error's start and body so far, turned into JSON once whole

        async def send_with_headers(message) -> None:
            if message["type"] == "http.response.start":
                have = {k.lower() for k, _ in message.get("headers", [])}
                message["headers"] = [*message.get("headers", []), *(h for h in SECURITY_HEADERS if h[0] not in have)]
                if message["status"] >= 400 and dict(message["headers"]).get(b"content-type", b"").startswith(
                    b"text/plain"
                ):
                    held.append(message)  # starlette's own (a malformed Range header): JSON like ours
                    return
            elif held and message["type"] == "http.response.body":
                held.append(message)
                if message.get("more_body", False):
                    return
                await send_json_error(send, held)
                return
            await send(message)

        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])}
        host = first_host(scope)  # not headers["host"]: that dict keeps the last of repeated Host headers
        if not self.host_allowed(scope):
            refusal = 400, "invalid host header (this server answers only requests addressed to this machine)"
        else:
            refusal = _refusal(scope["method"], headers, host or "", self.max_body)
        if refusal is not None:
            await _reply(send_with_headers, *refusal)
            return
        body = bytearray()
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            body += message.get("body", b"")
            if len(body) > self.max_body:
                await _reply(send_with_headers, 413, f"the request body is larger than {self.max_body} bytes")
                return
            if not message.get("more_body", False):
                break
        given = False

        async def replay():
            nonlocal given
            if given:
                return await receive()
            given = True
            return {"type": "http.request", "body": bytes(body), "more_body": False}

        await self.app(scope, replay, send_with_headers)

    def host_allowed(self, scope) -> bool:
        """Whether the request (HTTP or websocket) may reach the app: any Host without ``allowed_hosts``,
        else a Host header that parses (:func:`host_name`) to one of them. Starlette reads the headers
        as latin-1 and its ``Headers.get`` returns the first of repeated ones; so does this."""
        if self.allowed_hosts is None:
            return True
        return host_name(first_host(scope)) in self.allowed_hosts


def first_host(scope) -> str | None:
    """The request's first Host header (latin-1), or None. Both the Host check and the Origin check use
    this one: with two Host headers, checking one and comparing the Origin with the other would let a
    foreign page pass the Origin check by adding a second Host that names itself."""
    return next((v.decode("latin-1") for k, v in scope.get("headers", []) if k.lower() == b"host"), None)


def _refusal(method: str, headers: dict[str, str], host: str, max_body: int) -> tuple[int, str] | None:
    """(status, why) for a request refused before its body is read, else None. ``host`` is
    :func:`first_host`, the one the Host check passed, not ``headers["host"]`` (the last one)."""
    length = headers.get("content-length")
    if length is not None and (not length.strip().isdigit() or int(length) > max_body):
        return 413, f"the request body is larger than {max_body} bytes"
    if method.upper() not in STATE_CHANGING:
        return None
    origin = headers.get("origin")
    if origin is not None and origin.rstrip("/") not in (f"http://{host}", f"https://{host}"):
        return 403, f"cross-origin request refused (Origin {origin[:100]} is not this server)"
    if headers.get("sec-fetch-site", "same-origin") not in ("same-origin", "none"):
        return 403, "cross-site request refused (Sec-Fetch-Site)"
    if headers.get("content-type", "").split(";")[0].strip().lower() != "application/json":
        return 415, "state-changing requests must be Content-Type: application/json"
    return None


async def _reply(send, status: int, error: str, headers: tuple = ()) -> None:
    import json

    body = json.dumps({"error": error}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [*headers, (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())],
        }
    )
    await send({"type": "http.response.body", "body": body})


async def send_json_error(send, held: list) -> None:
    """Send a held text/plain error response (start, body messages) as ``{"error": text}``, its status
    and other headers kept (a 416's Content-Range)."""
    from http import HTTPStatus

    start = held[0]
    text = b"".join(m.get("body", b"") for m in held[1:]).decode("utf-8", "replace").strip()
    if not text:
        try:
            text = HTTPStatus(start["status"]).phrase.lower()
        except ValueError:
            text = "error"
    keep = tuple((k, v) for k, v in start["headers"] if k.lower() not in (b"content-type", b"content-length"))
    await _reply(send, start["status"], text, keep)



def static_pages(app: FastAPI, package: str) -> None:
    """Serve ``package``'s ``static/`` folder under /static and its index.html at / (not cached, so a
    page reloaded after an upgrade is the new one)."""
    folder = Path(str(resources.files(package) / "static"))
    app.mount("/static", StaticFiles(directory=folder), name="static")

    @app.api_route("/", methods=["GET", "HEAD"], response_class=HTMLResponse, include_in_schema=False)
    def index() -> HTMLResponse:
        return HTMLResponse((folder / "index.html").read_text(encoding="utf-8"), headers={"Cache-Control": "no-store"})


def json_errors(app: FastAPI, log: logging.Logger, error_type: type[Exception], user_error: UserError) -> None:
    """Install the handlers: validation (422 naming the field), HTTP errors, ``error_type`` (``user_error``
    decides the status), and anything else (500, logged with its traceback)."""

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        parts = []
        for e in exc.errors():
            if e.get("type") == "json_invalid":
                parts.append("the request body is not valid JSON")
                continue
            where = ".".join(str(p) for p in e.get("loc", ()) if p not in ("body", "query", "path"))
            parts.append(f"{where or 'request'}: {e.get('msg', 'invalid')}")
        return JSONResponse({"error": "; ".join(parts) or "invalid request"}, status_code=422)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        if exc.status_code == 400 and isinstance(exc.__cause__, (ValueError, RecursionError)):
            # FastAPI's "There was an error parsing the body": a JSON body its decoder could not take
            # (invalid UTF-8, nesting past the recursion limit, an integer of thousands of digits)
            return JSONResponse({"error": "the request body is not valid JSON"}, status_code=422)
        return JSONResponse({"error": str(exc.detail)}, status_code=exc.status_code)

    @app.exception_handler(error_type)
    async def user(request: Request, exc: Exception) -> JSONResponse:
        status, extra = user_error(exc)
        return JSONResponse({"error": str(exc), **extra}, status_code=status)

    @app.exception_handler(Exception)
    async def bug(request: Request, exc: Exception) -> JSONResponse:
        log.exception("%s: unexpected error on %s %s", app.title, request.method, request.url.path)
        return JSONResponse({"error": f"internal error ({type(exc).__name__}); see the server's log"}, status_code=500)
