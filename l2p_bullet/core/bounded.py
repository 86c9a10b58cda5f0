"""Reading files a user hands us in bounded memory and bounded recursion.

A size check on ``stat()`` only holds for regular files: ``/dev/zero``, a FIFO or ``/proc`` files report
0 bytes and never end. :func:`read_bounded` reads at most ``limit + 1`` bytes from whatever the path is,
so "too large" is found by reading, not by asking. :func:`loads_toml` bounds a TOML text's size and
nesting *before* :mod:`tomllib` sees it: its parser recurses once per nested array or inline table, so
500 ``[`` in a 1 KB manifest used to be a 3,000-line ``RecursionError`` in every command.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from ..errors import L2PError

MAX_TOML_BYTES = 256 * 1024
"""A manifest is a few KB (the built-ins are 3.3 KB); 256 KiB leaves room for long notes."""
MAX_TOML_DEPTH = 16
"""Nesting of arrays, inline tables and dotted keys in a manifest (the built-ins use 3)."""


def read_bounded(path: str | Path, limit: int, error: type[L2PError], label: str = "") -> bytes:
    """The bytes of ``path``, or ``error`` when it holds more than ``limit`` (a device or pipe included)."""
    label = label or str(path)
    try:
        with open(path, "rb") as f:
            data = f.read(limit + 1)
    except IsADirectoryError:
        raise error(f"{label} is a folder, not a file") from None
    except OSError as e:
        raise error(f"cannot read {label}: {e.strerror or e}") from None
    if len(data) > limit:
        raise error(f"{label} is larger than {_size(limit)}, the limit for this file (or never ends)")
    return data


def _size(n: int) -> str:
    return f"{n / 2**20:g} MiB" if n >= 2**20 else f"{n / 2**10:g} KiB"


def toml_nesting(text: str) -> int:
    """The deepest nesting of ``[``/``{`` outside strings and comments (an upper bound of what tomllib
    will recurse into); a linear scan, no recursion."""
    depth = deepest = 0
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if c in "\"'":
            quote = c * 3 if text.startswith(c * 3, i) else c
            i += len(quote)
            while i < n and not text.startswith(quote, i):
                if c == '"' and text[i] == "\\":
                    i += 1
                elif len(quote) == 1 and text[i] == "\n":
                    break
                i += 1
            i += len(quote)
            continue
        if c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth = max(0, depth - 1)
        i += 1
    return deepest


def value_depth(value: object) -> int:
    """How deeply dicts and lists nest in ``value`` (iteratively: a deep value must not recurse here)."""
    deepest, stack = 0, [(value, 0)]
    while stack:
        v, d = stack.pop()
        deepest = max(deepest, d)
        if isinstance(v, dict):
            stack += [(x, d + 1) for x in v.values()]
        elif isinstance(v, list):
            stack += [(x, d + 1) for x in v]
    return deepest


def loads_toml(raw: bytes, error: type[L2PError], label: str, *, max_bytes: int = MAX_TOML_BYTES,
               max_depth: int = MAX_TOML_DEPTH) -> dict:
    """Parse TOML from a user's file with its size and nesting bounded; every failure a one-line ``error``."""
    if len(raw) > max_bytes:
        raise error(f"{label} is {len(raw)} bytes; a manifest may hold at most {_size(max_bytes)}")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise error(f"{label} is not UTF-8 text (byte {e.start})") from None
    if toml_nesting(text) > max_depth:
        raise error(f"{label} nests arrays or tables more than {max_depth} deep; a manifest never needs that")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise error(f"{label} is not valid TOML ({e})") from None
    except (RecursionError, MemoryError, ValueError) as e:
        raise error(f"{label} cannot be read as TOML ({type(e).__name__})") from None
    if value_depth(data) > max_depth:
        raise error(f"{label} nests tables more than {max_depth} deep; a manifest never needs that")
    return data
