"""What the review app and the teach page share as web apps: loopback-only hosts, JSON errors, the page.

Every error a page can get is JSON ``{"error": message}`` with a 4xx status (a malformed request: 422; an
answer that cannot be taken: the app's own status), never a traceback; a bug is a 500 with the
exception's type only, its traceback in the server's log.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from importlib import resources
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.middleware.trustedhost import TrustedHostMiddleware

from .. import __version__

LOOPBACK = ("127.0.0.1", "localhost", "::1")
"""Hosts a server binds to by default; bound there, it answers only requests addressed to them."""

UserError = Callable[[Exception], tuple[int, dict]]
"""An app's own errors -> (status, extra JSON fields)."""


def new_app(title: str, host: str, extra_hosts: tuple[str, ...] = ()) -> FastAPI:
    """A FastAPI app without the API docs pages; bound to loopback, it refuses other Host headers so
    a web page elsewhere cannot reach it through a rebound DNS name."""
    app = FastAPI(title=title, version=__version__, docs_url=None, redoc_url=None)
    if host in LOOPBACK:
        app.add_middleware(TrustedHostMiddleware, allowed_hosts=["127.0.0.1", "localhost", "[::1]", *extra_hosts])
    return app



def static_pages(app: FastAPI, package: str) -> None:
    """Serve ``package``'s ``static/`` folder under /static and its index.html at / (not cached, so a
    page reloaded after an upgrade is the new one)."""
    folder = Path(str(resources.files(package) / "static"))
    app.mount("/static", StaticFiles(directory=folder), name="static")

    @app.get("/", response_class=HTMLResponse, include_in_schema=False)
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
        return JSONResponse({"error": str(exc.detail)}, status_code=exc.status_code)

    @app.exception_handler(error_type)
    async def user(request: Request, exc: Exception) -> JSONResponse:
        status, extra = user_error(exc)
        return JSONResponse({"error": str(exc), **extra}, status_code=status)

    @app.exception_handler(Exception)
    async def bug(request: Request, exc: Exception) -> JSONResponse:
        log.exception("%s: unexpected error on %s %s", app.title, request.method, request.url.path)
        return JSONResponse({"error": f"internal error ({type(exc).__name__}); see the server's log"}, status_code=500)
