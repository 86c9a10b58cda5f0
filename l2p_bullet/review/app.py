"""The review web app: FastAPI over a :class:`~l2p_bullet.review.queue.ReviewQueue`.

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
from pathlib import Path
from typing import Annotated, Literal

from fastapi import FastAPI, Query, Request
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from .. import __version__
from ..errors import ReviewError
from ..web.apps import json_errors, new_app, static_pages
from .queue import Item, NotFound, ReviewQueue, label_keys
from .runs import motion_for_browser
from .store import AnswerConflict, DatabaseUnavailable, GradeRow

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


def create_app(queue: ReviewQueue, host: str = "127.0.0.1") -> FastAPI:
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
        return {"mode": queue.mode, "view": queue.view, "version": __version__,
                "labels": _label_keys(queue), "items": len(queue.items),
                "problems": [{"run": rid, "problem": p} for rid, p in sorted(queue.problems.items())]}

    @app.get("/api/next")
    def next_item(reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        it = queue.next_item(reviewer)
        return {"item": None if it is None else _item(queue, it, reviewer), "progress": queue.progress(reviewer)}

    @app.get("/api/item/{key}")
    def item(key: Key, view: View, reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        return {"item": _item(queue, queue.item(key, view), reviewer), "progress": queue.progress(reviewer)}

    @app.get("/api/history")
    def history(reviewer: Annotated[str, Query(max_length=200)]) -> dict:
        by_id = {r.run_id: r for r in queue.runs.values()}
        return {"answers": [_answer(g) | {"key": by_id[g.run_id].key} for g in queue.history_rows(reviewer)],
                "progress": queue.progress(reviewer)}

    @app.post("/api/answer")
    def answer(body: AnswerIn) -> dict:
        g = queue.answer(body.reviewer, body.key, body.view, body.grade, body.label, body.comment, body.replaces)
        return {"answer": _answer(g) | {"key": body.key}, "progress": queue.progress(body.reviewer)}

    @app.post("/api/skip")
    def skip(body: SkipIn) -> dict:
        queue.skip(body.reviewer, body.key, body.view)
        return {"skipped": body.key}

    @app.get("/api/media/{key}/motion")
    def motion(key: Key) -> dict:
        return motion_for_browser(_run(queue, key), blind=queue.mode == "blind")

    @app.api_route("/api/media/{key}/video", methods=["GET", "HEAD"])
    def video(key: Key) -> FileResponse:
        run = _run(queue, key)
        if queue.mode == "blind" or run.video is None:  # the video's caption names the action
            raise NotFound("no video for this run here")
        return FileResponse(
            _present(run.video, "video", run.path),
            media_type="video/mp4" if run.video.suffix == ".mp4" else "image/gif",
        )

    @app.get("/api/media/{key}/frames/{index}")
    def frame(key: Key, index: int) -> FileResponse:
        run = _run(queue, key)
        if not 0 <= index < run.frames:
            raise NotFound(f"run has {run.frames} frames, not {index}")
        return FileResponse(_present(run.path / "frames" / f"{index:04d}.png", f"frame {index}", run.path),
                            media_type="image/png",
                            headers={"Cache-Control": "max-age=3600"})

    return app


def _label_keys(queue: ReviewQueue) -> list[dict]:
    return label_keys(queue.labels) if queue.mode == "blind" else []


def _run(queue: ReviewQueue, key: str):
    run = queue.runs.get(key)
    if run is None:
        raise NotFound(f'no run "{key}" is served here')
    if queue.problem_of(run) == "missing":
        raise AnswerConflict(f"the run folder {run.path} disappeared", "missing")
    return run


def _present(path: Path, what: str, run_dir: Path) -> Path:
    """``path`` if it is still a file of the run folder ``run_dir``: one removed while the server runs is a 410
    (the run folder is there, this file of it no longer is), not a 500 from FileResponse. One that leads out
    of the folder (a link in a run folder from elsewhere, say to a key file) is not served: with ``--host``
    off loopback, anyone who reaches the page could read it."""
    if not path.is_file():
        raise AnswerConflict(f"the run's {what} ({path.name}) is missing from {path.parent}", "missing")
    if not path.resolve().is_relative_to(run_dir.resolve()):
        raise NotFound(f"the run's {what} ({path.name}) links outside its run folder: not served")
    return path


def _item(queue: ReviewQueue, it: Item, reviewer: str) -> dict:
    run, blind = it.run, queue.mode == "blind"
    use_video = it.view == "3d" and not blind and run.video is not None
    mine = queue.answer_of(reviewer, it)
    return {
        "key": run.key, "view": it.view, "duration": run.duration_s,
        "sentence": None if blind else run.sentence,
        "video": f"/api/media/{run.key}/video" if use_video else None,
        "frames": run.frames if (it.view == "3d" and not use_video) else 0,
        "frame_fps": run.render_fps,
        "viewpoint": viewpoint(it.view, run.camera),
        "motion": f"/api/media/{run.key}/motion",
        "answer": None if mine is None else _answer(mine),
    }


def viewpoint(view: str, camera: str | None) -> str:
    """Where the person watching stands, said on the page: the 2-D view and the default video share the
    robot's side, so left and right are the words' left and right in both."""
    from ..embodiment.sim.camera import VIEWER_SIDE

    if view == "2d":
        return VIEWER_SIDE["top"]
    return VIEWER_SIDE.get(camera or "", "where the run's own camera stands (summary.json: render.camera)")


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
