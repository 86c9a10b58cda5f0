"""What asking the person for their own words gives (``perform --ask``, l2p_bullet/commands/asking.py), on the
sentence corpora of tests/language.

    .venv/bin/python benchmarks/bench_asked.py                       # every corpus, 2 processes (about 3 minutes)
    .venv/bin/python benchmarks/bench_asked.py --corpora heldout109.tsv,heldout110.tsv --workers 0

Each line is read as typed (as ``perform`` reads it). Where the reader refuses it for a word no object has that
``perform`` would ask about, the word is answered as the line's author meant: with each object of the line's own
answer in turn, and again for the next word asked (at most as many as ``perform`` asks). A line is *right* where
some answer reads it as its author wrote; *wrong* where every answer reads it as something else (a second word
read wrong that the refusal hid: why ``perform`` shows the reading before it moves anything); else refused. The
author's answer stands in for the person at the terminal, who names the object they meant; a person would not
answer a question about a word that is no object ("carefully"), which this count does answer, so its wrong column
is an upper bound.

Printed: per group of corpora (``--held-out``, by default the four newest authors, and the rest), the lines, right
as typed and with the words answered, lines asked about, wrong as typed and with every asked reading performed.
"""

from __future__ import annotations

import argparse
import itertools
import os
import sys
from multiprocessing import Pool
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CORPORA = ROOT / "tests" / "language"
HELD_OUT = tuple(f"heldout{i}.tsv" for i in range(109, 113))
"""The newest four authors' corpora (written and read once before the asking was built)."""
REFUSE = "REFUSE"


def _meant(expect: str, names: list[str]) -> list[str]:
    """The objects a line's answer names (movers, anchors, a row's objects), in order."""
    if expect == REFUSE:
        return []
    said = (n for item in expect.split(" ; ") for part in item.split()[1:3] for n in part.split(","))
    return list(dict.fromkeys(n for n in said if n in names))


def _answered(scene, error, meant: list[str], read, to_ask, with_word) -> list[str]:
    """Every reading of a refused line with each word asked about answered with each object ``meant``, word after
    word (``read(scene)``: the line read on a scene; ``to_ask(error, scene, taught)``: the word perform asks about
    then, "" for none)."""
    ends: list[str] = []
    todo = [(scene, to_ask(error, scene, {}), {})]
    while todo:
        the_scene, word, taught = todo.pop()
        for name in meant:
            told = with_word(the_scene, name, word)
            reading, next_error = read(told)
            now = {**taught, word: name}
            next_word = to_ask(next_error, told, now) if reading == REFUSE else ""
            if next_word:
                todo.append((told, next_word, now))
            else:
                ends.append(reading)
    return ends


def read_corpus(name: str, longest: int | None = None) -> tuple[str, list[tuple[str, str, str, int]]]:
    """(corpus, [(expected, as typed, with the words answered, words asked)]) for every line of ``name``; a
    description of more than ``longest`` words is not asked about (default: as perform asks)."""
    sys.path[:0] = [str(ROOT), str(CORPORA)]
    import corpus

    from l2p_bullet.commands.asking import MAX_DESCRIPTION, with_word, word_to_ask
    from l2p_bullet.errors import L2PError, UnknownObjectError
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    scene = corpus.scene(name)
    longest = MAX_DESCRIPTION if longest is None else longest

    def read(the_scene, sentence: str) -> tuple[str, L2PError | None]:
        try:
            return corpus.notation(corpus.resolve_clauses(sentence, the_scene, plugins)), None
        except L2PError as e:
            return REFUSE, e

    def to_ask(e: L2PError | None, the_scene, taught: dict[str, str]) -> str:
        return word_to_ask(e, the_scene, taught, longest) if isinstance(e, UnknownObjectError) else ""

    rows = []
    for case in corpus.cases(name):
        got, error = read(scene, case.sentence)
        if got != REFUSE or not to_ask(error, scene, {}):
            rows.append((case.expect, got, got, 0))
            continue
        ends = _answered(scene, error, _meant(case.expect, scene.names), lambda sc, s=case.sentence: read(sc, s),
                         to_ask, with_word)
        answered = case.expect if case.expect in ends else REFUSE if REFUSE in ends or not ends else ends[0]
        rows.append((case.expect, got, answered, 1))
    return name, rows


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--corpora", default="", help="comma-separated corpus files (default: every one)")
    ap.add_argument("--held-out", default=",".join(HELD_OUT), help="the corpora reported apart")
    ap.add_argument("--workers", type=int, default=2, help="processes (0: this one)")
    ap.add_argument("--longest", type=int, default=None,
                    help="ask about descriptions of at most this many words (default: as perform asks)")
    args = ap.parse_args(argv)
    names = [n for n in args.corpora.split(",") if n] or sorted(p.name for p in CORPORA.glob("*.tsv"))
    missing = [n for n in names if not (CORPORA / n).is_file()]
    if missing:
        ap.error(f"no corpus {', '.join(missing)} in {CORPORA}")
    jobs = [(n, args.longest) for n in names]
    if args.workers > 0:
        with Pool(args.workers) as pool:
            results = dict(pool.starmap(read_corpus, jobs, chunksize=1))
    else:
        results = dict(itertools.starmap(read_corpus, jobs))
    held = set(args.held_out.split(","))
    print("| corpora | lines | right as typed | right with the words answered | lines asked | wrong as typed | "
          "wrong with every asked reading performed |\n|---|---:|---:|---:|---:|---:|---:|")
    groups = (("held out", [n for n in names if n in held]), ("the others", [n for n in names if n not in held]))
    for label, group in groups:
        rows = [r for n in group for r in results[n]]
        if not rows:
            continue
        lines = len(rows)
        right = sum(exp == got for exp, got, _, _ in rows)
        answered = sum(exp == ans for exp, _, ans, _ in rows)
        wrong = sum(got not in (exp, REFUSE) for exp, got, _, _ in rows)
        wrong_answered = sum(ans not in (exp, REFUSE) for exp, _, ans, _ in rows)
        print(f"| {label} ({len(group)}) | {lines} | {right} ({100 * right / lines:.1f} %) | {answered} "
              f"({100 * answered / lines:.1f} %) | {sum(a for *_, a in rows)} | {wrong} | {wrong_answered} |")


if __name__ == "__main__":
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    main()
