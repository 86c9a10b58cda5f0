"""The held-out sentence corpus (corpus.tsv) and how a resolution is compared with what it must be.

Each sentence is resolved as ``perform`` resolves it (every clause against the scene, before anything
moves) and written in the corpus's notation; a refusal is any of the project's one-line errors. A
sentence is *right* when the notation matches, *refused* when the toolkit said no, *wrong* when it
resolved to something else: a refusal beats a wrong block.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from dataclasses import dataclass
from pathlib import Path

from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.core.scene import load_scene
from l2p_bullet.errors import L2PError
from l2p_bullet.plugins import registry

HERE = Path(__file__).parent
REFUSE = "REFUSE"


@dataclass(frozen=True)
class Case:
    category: str
    sentence: str
    expect: str


def cases(name: str = "corpus.tsv") -> list[Case]:
    out = []
    for line in (HERE / name).read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            cat, sentence, expect = line.split("\t")
            out.append(Case(cat, sentence, expect))
    return out


def scene(name: str = "corpus.tsv"):
    """The scene a corpus is written against: ``<stem>_scene.json`` beside it where there is one (a corpus
    written for another table), else ``corpus_scene.json``."""
    own = HERE / f"{Path(name).stem}_scene.json"
    return load_scene(own if own.exists() else HERE / "corpus_scene.json")


def read(sentence: str, plugins, name: str = "corpus.tsv") -> str:
    """``sentence`` resolved against corpus ``name``'s table, in the corpus's notation (a refusal raises)."""
    return notation(resolve_clauses(sentence, scene(name), plugins))


def notation(clauses: list) -> str:
    """The clauses in the corpus's notation: a composite's steps as one ``row`` item."""
    items: list[str] = []
    last_group = None
    for c in clauses:
        group = getattr(c, "group", None)
        if group is not None:
            if group is not last_group:
                items.append(f"{group.action} {','.join(group.objects)}")
            last_group = group
            continue
        last_group = None
        cmd = c.command
        text = f"{cmd.manner}:{cmd.action} {cmd.mover} {','.join(cmd.anchors)}"
        for field in ("pace", "extent"):
            value = getattr(cmd, field, None)
            if value:
                text += f" {field}={value}"
        items.append(text)
    return " ; ".join(items)


def resolve(sentence: str, the_scene, plugins) -> str:
    try:
        return notation(resolve_clauses(sentence, the_scene, plugins))
    except L2PError:
        return REFUSE


def score(plugins=None, name: str = "corpus.tsv") -> tuple[dict[str, Counter], list[tuple[Case, str]]]:
    """Per category, how many are right / refused / wrong; and every case that is not right."""
    plugins = registry.discover() if plugins is None else plugins
    the_scene = scene(name)
    table: dict[str, Counter] = defaultdict(Counter)
    misses = []
    for case in cases(name):
        got = resolve(case.sentence, the_scene, plugins)
        if got == case.expect:
            table[case.category]["right"] += 1
        elif got == REFUSE:
            table[case.category]["refused"] += 1
            misses.append((case, got))
        else:
            table[case.category]["wrong"] += 1
            misses.append((case, got))
    return table, misses


if __name__ == "__main__":  # python tests/language/corpus.py [heldout.tsv]: the table per category, the misses
    import sys

    t, m = score(name=sys.argv[1] if len(sys.argv) > 1 else "corpus.tsv")
    total = Counter()
    print("| category | sentences | right | refused | wrong | rate |\n|---|---:|---:|---:|---:|---:|")
    for cat, c in t.items():
        n = sum(c.values())
        total.update(c)
        print(f"| {cat} | {n} | {c['right']} | {c['refused']} | {c['wrong']} | {100 * c['right'] / n:.1f} % |")
    n = sum(total.values())
    print(
        f"| all | {n} | {total['right']} | {total['refused']} | {total['wrong']} | {100 * total['right'] / n:.1f} % |"
    )
    for case, got in m:
        print(f"{case.category}: {case.sentence!r}\n   expect {case.expect}\n   got    {got}")
