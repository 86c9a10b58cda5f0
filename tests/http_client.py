"""A JSON client for the live servers the web tests start (the review app, the teach page)."""

from __future__ import annotations

import json
import urllib.error
import urllib.request


def call(url: str, method: str, path: str, body=None, raw: bytes | None = None, headers: dict | None = None,
         timeout: float = 60) -> tuple[int, object]:
    """(status, JSON body) of one request to ``url + path``; a body that is not JSON comes back as bytes."""
    data = raw if raw is not None else (None if body is None else json.dumps(body).encode())
    req = urllib.request.Request(url.rstrip("/") + path, data=data, method=method,
                                 headers={"Content-Type": "application/json", **(headers or {})})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            payload, status = r.read(), r.status
    except urllib.error.HTTPError as e:
        payload, status = e.read(), e.code
    try:
        return status, json.loads(payload)
    except ValueError:
        return status, payload
