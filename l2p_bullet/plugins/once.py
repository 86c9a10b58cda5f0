"""The installed plugins read once while one sentence is read.

Discovery reads every installed distribution's entry points and every action's manifest anew each time it is
asked (7 ms), so that a plugin installed, broken or mended between two sentences counts at the next one. Reading
one sentence asks several times (each clause and each reading the clause reader tries asks for the composites), and
nothing is installed while one sentence is read: inside :func:`read_once` (entered by
``chain/clauses.resolve_clauses``) what was read first is kept until the sentence is read, and each asker gets a
copy of its own. Outside it every question is read anew. The scope is a context variable: a thread or task of its
own never sees another's.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any, TypeVar

T = TypeVar("T")

_KEPT: ContextVar[dict[str, Any] | None] = ContextVar("l2p_plugins_read_once", default=None)


@contextmanager
def read_once() -> Iterator[None]:
    """Inside, :func:`kept` reads each question once; nested scopes share the outermost one."""
    if _KEPT.get() is not None:
        yield
        return
    token = _KEPT.set({})
    try:
        yield
    finally:
        _KEPT.reset(token)


def kept(question: str, read: Callable[[], T], copy: Callable[[T], T]) -> T:
    """``read()``, read once per :func:`read_once` scope and handed out as ``copy`` of it; read each time outside
    one. A failure is never kept."""
    answers = _KEPT.get()
    if answers is None:
        return read()
    if question not in answers:
        answers[question] = read()
    return copy(answers[question])
