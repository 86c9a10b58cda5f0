"""The code speaks in the present: comments and strings in ``l2p_bullet/`` say why, never when.

History (issue numbers, the sessions and stops that built the project, dates, rounds of an experiment) goes
to CHANGELOG.md and the appendices of docs/; a comment that cites it goes stale the day it is written. The
scan reads comments and string literals only (tokenize), so code is never flagged, and is precise about the
words the product itself uses: a capture *session* (``Session1``, ``load_session``), a *grading session* of
people in the review app, the *rounds* of ``l2p-bullet improve`` (``round 1``) and hex colours (``"#999"``)
are not history.
"""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

import l2p_bullet

PKG = Path(l2p_bullet.__file__).parent

_ORDINAL = (r"(?:first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|tenth|eleventh|twelfth|thirteenth|"
            r"fourteenth|fifteenth|sixteenth|seventeenth|eighteenth|nineteenth|twentieth|\d+(?:st|nd|rd|th))")
_MONTH = (r"(?:Jan(?:uary)?|Feb(?:ruary)?|Mar(?:ch)?|Apr(?:il)?|May|June?|July?|Aug(?:ust)?|Sep(?:t(?:ember)?)?|"
          r"Oct(?:ober)?|Nov(?:ember)?|Dec(?:ember)?)")

HISTORY = {
    "an issue number": re.compile(r"\bissues?[ -]?#?\d+", re.IGNORECASE),
    "an issue reference (#N)": re.compile(r"(?<![\w&\"'#/])#\d+\b(?![\"'\w])"),
    "a session or stop of the project's making": re.compile(
        rf"\b{_ORDINAL}[ -](?:session|stop)\b"
        r"|\bstops? \d+\b(?![.,]?\d*\s*(?:cm|mm|m|s|ms|blocks?|sides?|%|deg|degrees?|turns?)\b)|(?-i:\bsession \d+\b)"
        r"|\b(?:this|last|previous|earlier|next) session\b",
        re.IGNORECASE,
    ),
    "a round of an experiment": re.compile(rf"\b{_ORDINAL} round\b", re.IGNORECASE),
    "a date": re.compile(rf"\b20\d\d-\d\d-\d\d\b|\b{_MONTH}\.? (?:\d{{1,2}},? )?20\d\d\b"),
}
"""What history looks like in a comment, and what each pattern means in the failure message."""


def _texts(path: Path):
    """(first line, text) of every string literal and every block of comments on consecutive lines of a Python
    file, with line breaks and the comment marks between lines read as spaces (a phrase broken over two lines
    is still seen)."""
    src = path.read_text(encoding="utf-8")
    block: tuple[int, str] | None = None
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        if tok.type == tokenize.COMMENT:
            if block and block[0] + block[1].count("\n") + 1 == tok.start[0]:
                block = (block[0], block[1] + "\n" + tok.string)
            else:
                if block:
                    yield block
                block = (tok.start[0], tok.string)
        elif tok.type in (tokenize.STRING, getattr(tokenize, "FSTRING_MIDDLE", -1)):
            yield tok.start[0], tok.string
    if block:
        yield block


def _matches(text: str, pattern: re.Pattern):
    """(line offset, match) of ``pattern`` in ``text`` read as one line."""
    lines = [re.sub(r"^\s*#?\s*", "", line) for line in text.split("\n")]
    starts, flat = [], ""
    for line in lines:
        starts.append(len(flat))
        flat += line + " "
    for m in pattern.finditer(flat):
        yield sum(1 for st in starts[1:] if st <= m.start()), m


def history_in(path: Path) -> list[str]:
    name = path.relative_to(PKG.parent) if path.is_relative_to(PKG.parent) else path.name
    return [f"{name}:{line + offset}: {what} ({m.group(0)!r})"
            for line, text in _texts(path) for what, pattern in HISTORY.items()
            for offset, m in _matches(text, pattern)]


def test_no_history_in_the_package():
    files = sorted(PKG.rglob("*.py"))
    assert len(files) > 100, "the scan found too few modules to be looking at the package"
    found = [hit for f in files for hit in history_in(f)]
    assert not found, ("history in code (say why in the present tense; history goes to CHANGELOG.md or a doc's "
                       "appendix):\n  " + "\n  ".join(found))


@pytest.mark.parametrize("text", [
    "# issue 23: not a slide", "x = 1  # (issue 27.8)", '"""Moved here (2026-11-27, twelfth session)."""',
    "# measured in the CI, stop 29", "# see #42", "# the planning disk is larger since Nov 2026",
    "# the fifth round's table (docs/learning.md)", "# fixed in the last session",
    "# a traceback (CI, stop\n# 29) once", '"""Moved here in the\ntwelfth session."""',
])
def test_the_scan_sees_history(tmp_path, text):
    f = tmp_path / "probe.py"
    f.write_text(text + "\n")
    assert _hits(f), text


@pytest.mark.parametrize("text", [
    'color = "#999"', "# one capture session per person: Session1, Session2", "# a grading session of people",
    "# round 1's first run uses IMPROVE_SEEDS", "def load_session(path): ...", "# the mover stops part of the way",
    "# a stop sign", "# the 0.35 m disk", "# version 2026.1", "# the block stops 2 cm short",
    "# the search stops 3 blocks out",
])
def test_the_scan_leaves_the_products_words_alone(tmp_path, text):
    f = tmp_path / "probe.py"
    f.write_text(text + "\n")
    assert not _hits(f), text


def _hits(path: Path) -> list[str]:
    return history_in(path)
