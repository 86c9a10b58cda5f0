"""The teach web app: FastAPI over a :class:`~l2p_bullet.teach.lesson.Lesson`.

The same stack and conventions as the review app (``l2p_bullet/review/app.py``; served by its runner,
``web/server.py``): requests validated from type declarations (a bad
payload is a 422 naming the field), JSON errors ``{"error": message}`` (400 a recording that cannot be
saved (any L2PError), 404 an unknown run, 400 a demonstration to remove that is not there, 409 a training already under
way or a recording saved already, 500 a one-line message with the traceback
in the server's log), static HTML/JS without a build step, no interactive API docs (they load scripts
from a CDN; nothing here may reach outside the machine), bound to 127.0.0.1 unless told otherwise.
"""

from __future__ import annotations

import logging
from typing import Annotated, Any

import numpy as np
from fastapi import Body, FastAPI, Path, Query
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field
from starlette.exceptions import HTTPException as StarletteHTTPException

from ..errors import L2PError, TeachError
from ..web.apps import json_errors, new_app, static_pages
from .checks import MAX_SAMPLES, Duplicate
from .lesson import Lesson, Recording

log = logging.getLogger("l2p_bullet.teach")

Number = Annotated[float, Field(strict=True, allow_inf_nan=False)]
"""A JSON number, finite: "0" (a string) is refused, not read as 0; NaN / Infinity are "not a finite number"."""
Sample = Annotated[list[Number], Field(min_length=4, max_length=4)]


class RecordingIn(BaseModel):
    """One demonstration as the page sampled it: ``samples`` rows ``[t, x, y, yaw]`` (seconds, scene frame)."""

    model_config = ConfigDict(extra="forbid")
    scene: Annotated[int, Field(ge=0, le=10**9)]
    samples: Annotated[list[Sample], Field(min_length=2, max_length=MAX_SAMPLES)]
    start: Number
    end: Number


Drag = Annotated[list[Sample], Field(min_length=2, max_length=MAX_SAMPLES)]


class DragIn(BaseModel):
    """One drag of a composite's demonstration: the block and its samples ``[t, x, y, yaw]``."""

    model_config = ConfigDict(extra="forbid")
    block: Annotated[str, Field(min_length=1, max_length=64)]
    samples: Drag


class RowIn(BaseModel):
    """A composite's demonstration: the scene's seed and the drags in the order they were made."""

    model_config = ConfigDict(extra="forbid")
    scene: Annotated[int, Field(ge=0, le=10**9)]
    segments: Annotated[list[DragIn], Field(min_length=1, max_length=8)]


class Busy(TeachError):
    """A training is already under way."""


def create_app(lesson: Lesson, host: str = "127.0.0.1") -> FastAPI:
    app = new_app("l2p-bullet teach", host)
    json_errors(app, log, L2PError, lambda exc: (409 if isinstance(exc, (Busy, Duplicate)) else 400, {}))
    static_pages(app, "l2p_bullet.teach")

    @app.get("/api/config")
    def config() -> dict:
        return lesson.config()

    @app.get("/api/scene")
    def scene(seed: Annotated[int, Query(ge=0, le=10**9)]) -> dict:
        return lesson.scene_json(seed)

    @app.post("/api/demos")
    def save(body: RecordingIn) -> dict:
        rec = Recording(body.scene, np.array(body.samples, float), body.start, body.end)
        return lesson.save(rec)

    @app.post("/api/rows")
    def save_row(body: RowIn) -> dict:
        if not hasattr(lesson, "save_row"):
            raise TeachError("this teach page records single actions: save with /api/demos")
        return lesson.save_row(body.scene, [d.model_dump() for d in body.segments])

    @app.delete("/api/demos/{k}")
    def remove(k: Annotated[int, Path(ge=1, le=10**6)]) -> dict:
        """Remove demonstration ``k`` (1 = the first saved): a mistaken one, or room under the limit."""
        return lesson.remove(k)

    @app.post("/api/train")
    def train(body: Annotated[dict[str, Any] | None, Body()] = None) -> dict:
        """Start training; the body is empty or a JSON object (anything else is a 422, not a training)."""
        if lesson.job.state in ("training", "performing"):
            raise Busy("training is already under way")
        return lesson.train()

    @app.get("/api/train")
    def status() -> dict:
        return lesson.status()

    @app.get("/api/runs/{k}/video")
    def video(k: int) -> FileResponse:
        try:
            path = lesson.video(k)
        except TeachError as e:
            raise StarletteHTTPException(404, str(e)) from None
        return FileResponse(path, media_type="video/mp4")

    return app
