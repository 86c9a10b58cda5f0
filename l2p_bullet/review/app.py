"""The review web app: FastAPI over a :class:`~l2p_bullet.review.session.ReviewSession`.

FastAPI because requests are validated from type declarations (a bad payload is a 422 that says which
field is wrong, never a 500), and the OpenAPI schema (``/openapi.json``) documents the API the tests
use; uvicorn is the standard ASGI server for it. The page is plain HTML, JavaScript and CSS shipped in
``review/static`` (no build step). The interactive API docs are off: they load scripts from a CDN, and
nothing here may reach outside the machine.

Errors are JSON ``{"error": message}``: 400 a request that makes no sense here, 404 an unknown run,
409 a conflict (the run changed on disk, or the answer was changed in another window), 410 a run folder
that disappeared, 422 a malformed payload, 503 a database moved away or made read-only while serving;
anything unexpected is a 500 with a one-line message (the
traceback goes to the server's log, not to the browser).
"""

from __future__ import annotations

import logging
import time
from typing import Annotated, Literal

from fastapi import FastAPI, Query, Request
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from .. import __version__
from ..errors import ReviewError
from .runs import motion_for_browser
from .session import Item, NotFound, ReviewSession
from .store import AnswerConflict, DatabaseUnavailable, GradeRow
from .web import json_errors, new_app, static_pages

log = logging.getLogger("l2p_bullet.review")

Reviewer = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1, max_length=40)]
Key = Annotated[str, StringConstraints(pattern=r"^[0-9a-f]{16}$")]
View = Literal["3d", "2d"]


class AnswerIn(BaseModel):
    """One answer. ``replaces``: the ``updated_at`` of the answer being changed (None for a first one)."""

    model_config = ConfigDict(extra="forbid")
    reviewer: Reviewer
    key: Key
    view: View
    grade: Annotated[int, Field(ge=0, le=10, strict=True)] | None = None
    label: Annotated[str, StringConstraints(max_length=60)] | None = None
    comment: Annotated[str, StringConstraints(max_length=2000)] = ""
    replaces: Annotated[str, StringConstraints(max_length=40)] | None = None


class SkipIn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    reviewer: Reviewer
    key: Key
    view: View


def create_app(session: ReviewSession, host: str = "127.0.0.1") -> FastAPI:
    app = new_app("l2p-bullet review", host)
    json_errors(app, log, ReviewError, _status)

    @app.middleware("http")
    async def server_timing(request: Request, call_next):
        t0 = time.perf_counter()
        response = await call_next(request)
        response.headers["Server-Timing"] = f"app;dur={(time.perf_counter() - t0) * 1000:.2f}"
        return response

    static_pages(app, "l2p_bullet.review")

    @app.get("/api/config")
    def config() -> dict:
        return {"mode": session.mode, "view": session.view, "version": __version__,
                "labels": _label_keys(session), "items": len(session.items),
                "problems": [{"run": rid, "problem": p} for rid, p in sorted(session.problems.items())]}

    @app.get("/api/next")
    def next_item(reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        it = session.next_item(reviewer)
        return {"item": None if it is None else _item(session, it, reviewer), "progress": session.progress(reviewer)}

    @app.get("/api/item/{key}")
    def item(key: Key, view: View, reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        return {"item": _item(session, session.item(key, view), reviewer), "progress": session.progress(reviewer)}

    @app.get("/api/history")
    def history(reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        by_id = {r.run_id: r for r in session.runs.values()}
        return {"answers": [_answer(g) | {"key": by_id[g.run_id].key} for g in session.history_rows(reviewer)],
                "progress": session.progress(reviewer)}

    @app.post("/api/answer")
    def answer(body: AnswerIn) -> dict:
        g = session.answer(body.reviewer, body.key, body.view, body.grade, body.label, body.comment, body.replaces)
        return {"answer": _answer(g) | {"key": body.key}, "progress": session.progress(body.reviewer)}

    @app.post("/api/skip")
    def skip(body: SkipIn) -> dict:
        session.skip(body.reviewer, body.key, body.view)
        return {"skipped": body.key}

    @app.get("/api/media/{key}/motion")
    def motion(key: Key) -> dict:
        return motion_for_browser(_run(session, key), blind=session.mode == "blind")

    @app.get("/api/media/{key}/video")
    def video(key: Key) -> FileResponse:
        run = _run(session, key)
        if session.mode == "blind" or run.video is None:  # the video's caption names the action
            raise NotFound("no video for this run here")
        return FileResponse(run.video, media_type="video/mp4" if run.video.suffix == ".mp4" else "image/gif")

    @app.get("/api/media/{key}/frames/{index}")
    def frame(key: Key, index: int) -> FileResponse:
        run = _run(session, key)
        if not 0 <= index < run.frames:
            raise NotFound(f"run has {run.frames} frames, not {index}")
        return FileResponse(run.path / "frames" / f"{index:04d}.png", media_type="image/png",
                            headers={"Cache-Control": "max-age=3600"})

    return app


def _label_keys(session: ReviewSession) -> list[dict]:
    from .session import label_keys

    return label_keys(session.labels) if session.mode == "blind" else []


def _run(session: ReviewSession, key: str):
    run = session.runs.get(key)
    if run is None:
        raise NotFound(f'no run "{key}" is served here')
    if session.check(run) == "missing":
        raise AnswerConflict(f"the run folder {run.path} disappeared", "missing")
    return run


def _item(session: ReviewSession, it: Item, reviewer: str) -> dict:
    run, blind = it.run, session.mode == "blind"
    use_video = it.view == "3d" and not blind and run.video is not None
    mine = session.answer_of(reviewer, it)
    return {
        "key": run.key, "view": it.view, "duration": run.duration_s,
        "sentence": None if blind else run.sentence,
        "video": f"/api/media/{run.key}/video" if use_video else None,
        "frames": run.frames if (it.view == "3d" and not use_video) else 0,
        "frame_fps": run.render_fps,
        "motion": f"/api/media/{run.key}/motion",
        "answer": None if mine is None else _answer(mine),
    }


def _answer(g: GradeRow) -> dict:
    return {"view": g.view, "grade": g.grade, "label": g.label, "comment": g.comment,
            "created_at": g.created_at, "updated_at": g.updated_at}


def _status(exc: Exception) -> tuple[int, dict]:
    """A ReviewError's status: 404 for an unknown run, 410/409 for an answer to a run that disappeared or
    changed, 400 otherwise."""
    if isinstance(exc, NotFound):
        return 404, {}
    if isinstance(exc, DatabaseUnavailable):
        return 503, {"reason": "database"}
    if isinstance(exc, AnswerConflict):
        return (410 if exc.reason == "missing" else 409), {"reason": exc.reason}
    return 400, {}
