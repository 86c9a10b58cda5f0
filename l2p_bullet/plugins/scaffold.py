"""``l2p-bullet new-action``: write a ready-to-install action plugin package.

The package is the smallest thing that makes a new preposition work end to end: a pyproject that
declares the entry point in ``l2p_bullet.actions``, a package whose folder will hold the bundle and whose
module declares what else the action is (``ACTION``, an ``ActionSpec`` as each built-in declares),
a manifest template carrying the phrases (so the parser learns them as soon as the package is
installed and trained) and a README that walks an author through demonstrations, training and
installation. Everything is plain text written from templates: no network, no build step.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from .. import __version__
from ..core.folders import check_writable
from ..core.frames import parse_anchors, parse_frame
from ..core.vocabulary import PLUGIN_ACTION, normalize_name, normalize_phrase
from ..errors import BundleError, PluginError, UnknownActionError
from ..judge.rules import RULES, TWO_ANCHOR_RULES


@dataclass(frozen=True)
class Scaffold:
    """What :func:`scaffold` wrote: the project folder, the package folder (the bundle goes there)."""

    root: Path
    package_dir: Path
    module: str
    dist_name: str
    files: list[Path]


def _example(phrase: str, anchors: int, kind: str = "action") -> str:
    """A sentence for the README and the ActionSpec: "move A <phrase> B" (and C); a composite's phrase
    takes the list of objects: "<phrase> A, B and C"."""
    if kind == "composite":
        return f"{phrase} A, B and C"
    return f"move A {phrase} B" + (" and C" if anchors == 2 else "")


_KIND = {"left-of": "left-of", "right-of": "right-of", "in-front-of": "in-front-of", "behind": "behind",
         "between": "between"}
"""Action names whose generated example demonstrations exist (``l2p_bullet.learning.synthetic``)."""


def _viewer_arg(frame: str) -> str:
    """The example script's ``viewer_xy`` argument for a viewer-frame action ("" for a relative one): the
    viewpoint in the tracks' frame (the table's centre at the origin, 0.15 m blocks), without which
    training refuses the files."""
    from ..data.demos import DEMO_BLOCK_SIZE

    xy = parse_frame(frame).viewpoint_xy()
    if xy is None:
        return ")"
    x, y = (float(v) for v in xy / 0.05 * DEMO_BLOCK_SIZE)  # scene metres -> blocks of 5 cm -> 0.15 m blocks
    return (f',\n             viewer_xy=np.array([{x:.2f}, {y:.2f}]))  # frame = "{frame}": where the viewer '
            "stood, in the tracks' frame")


def check_name(name: str) -> str:
    if not PLUGIN_ACTION.match(name):
        raise PluginError(
            f'"{name}" is not a valid action name: use lower-case words joined by hyphens, e.g. "left-of"'
        )
    return name


def scaffold(name: str, phrases: list[str], out: str | Path | None = None, *,
             installed: dict[str, str] | None = None, description: str = "", frame: str = "relative",
             anchors: int = 1, judge: str | None = None, kind: str = "action",
             installed_names: Iterable[str] = ()) -> Scaffold:
    """Write the plugin project for action ``name`` (claiming ``phrases``) into ``out``.

    ``installed`` maps phrases already claimed to their action: a new plugin that reuses one would make
    every sentence ambiguous once installed, so that is refused here rather than after ``pip install``.
    ``installed_names`` are the installed actions' names (built-in and plugins): a plugin named like one
    would be refused as a conflict once installed, so the name is refused here too.
    ``frame`` and ``anchors`` are the manifest's declarations (:mod:`l2p_bullet.core.frames`), ``judge``
    the name of a rule judge (``judge/rules.py``) for its ``[judge]`` section (default: none, the action's
    own progress model judges). ``kind`` "composite" makes a composite action's plugin (a phrase over a
    list of objects, taught on the teach page: l2p_bullet/composite). Never overwrites: an existing ``out``
    is an error.
    """
    if kind not in ("action", "composite"):
        raise PluginError(f'the kind of a plugin is "action" or "composite" (got {kind!r})')
    check_name(name)
    if name in {normalize_name(n) for n in installed_names}:
        raise PluginError(f'an action named "{name}" is already installed (l2p-bullet actions lists them); '
                          "choose another name for the new action")
    try:
        frame, anchors = parse_frame(frame).name, parse_anchors(anchors)
    except BundleError as e:
        raise PluginError(str(e)) from None
    if judge is not None:
        if judge not in RULES:
            raise UnknownActionError(judge, RULES, "(no rule judge has that name)")
        if (judge in TWO_ANCHOR_RULES) != (anchors == 2):
            raise PluginError(f'the rules "{judge}" read {2 if judge in TWO_ANCHOR_RULES else 1} reference object(s); '
                              f"this action takes {anchors} (--anchors)")
    clean = [normalize_phrase(p) for p in phrases if p.strip()]
    if not clean:
        raise PluginError('give at least one phrase, e.g. --phrase "to the left of"')
    if len(set(clean)) != len(clean):
        raise PluginError(
            "the same phrase is given twice: " + ", ".join(sorted({p for p in clean if clean.count(p) > 1}))
        )
    for p in clean:
        if not re.fullmatch(r"[a-z][a-z' ]*", p):
            raise PluginError(f'phrase "{p}" must be words made of letters (no digits or punctuation)')
        owner = (installed or {}).get(p)
        if owner is not None and owner != name:
            raise PluginError(f'the phrase "{p}" already belongs to the installed action "{owner}"; '
                              "choose another phrase (two plugins may not claim the same one)")
    module = "l2p_" + name.replace("-", "_")
    dist_name = "l2p-" + name
    root = Path(out) if out is not None else Path(dist_name)
    if root.exists() or root.is_symlink():
        raise PluginError(f"{root} already exists; choose another --out (new-action never overwrites)")
    check_writable(root, "--out", PluginError)
    pkg = root / module
    pkg.mkdir(parents=True)
    (root / "demos").mkdir()
    texts = {
        root / "pyproject.toml": _PYPROJECT.format(
            name=name,
            module=module,
            dist=dist_name,
            version=__version__,
            data=', "*.json"' if kind == "composite" else "",
        ),
        pkg / "__init__.py": _INIT.format(name=name),
        pkg / "manifest.toml": (_COMPOSITE_HEADER if kind == "composite" else _HEADER).format(name=name)
        + _MANIFEST.format(
            name=name,
            phrases=", ".join(f'"{p}"' for p in clean),
            version=__version__,
            # a TOML basic string, escaped as JSON escapes it: a quote, a backslash or a newline in the author's
            # description broke the manifest
            description=json.dumps(
                description
                or (
                    f"Put the blocks named in a row ({clean[0]} A, B and C)."
                    if kind == "composite"
                    else f"Slide a block {clean[0]} another block" + (" and a third" if anchors == 2 else "") + "."
                ),
                ensure_ascii=False,
            ),
            frame=frame,
            anchors=anchors,
        )
        + (_JUDGE.format(rules=judge) if judge else "")
        + (_COMPOSITE if kind == "composite" else ""),
        root / "README.md": (_COMPOSITE_README if kind == "composite" else _README).format(
            name=name,
            module=module,
            dist=dist_name,
            phrase=clean[0],
            root=root.name,
            phrases=", ".join(f'"{p}"' for p in clean),
            example=_example(clean[0], anchors, kind),
            kind=_KIND.get(name, "left-of" if anchors == 1 else "between"),
            viewer=_viewer_arg(frame),
        ),
        root / "demos" / ".gitkeep": "",
    }
    # what else the action is, declared as the built-ins declare theirs (registry.action_spec reads it)
    texts[pkg / "__init__.py"] += _ACTION.format(name=name, sentence=_example(clean[0], anchors, kind),
                                                 rules=f'"{judge}"' if judge else "None")
    for path, text in texts.items():
        path.write_text(text, encoding="utf-8")
    return Scaffold(root, pkg, module, dist_name, sorted(texts))


_PYPROJECT = """\
[build-system]
requires = ["setuptools>=68", "wheel"]
build-backend = "setuptools.build_meta"

[project]
name = "{dist}"
version = "0.1.0"
description = "l2p-bullet action plugin: {name}"
requires-python = ">=3.11"
dependencies = ["l2p-bullet>={version}"]

# This line is the whole plugin mechanism: l2p-bullet finds actions in this entry-point group. The value
# is the package whose folder holds the bundle (manifest.toml + weights); it is located without being
# imported, so listing actions stays fast.
[project.entry-points."l2p_bullet.actions"]
{name} = "{module}"

[tool.setuptools]
packages = ["{module}"]

[tool.setuptools.package-data]
"{module}" = ["*.toml", "*.safetensors", "*.md"{data}]
"""

_INIT = '''"""Action plugin "{name}" for l2p-bullet: this folder holds the bundle (manifest.toml and weights).

What else the action is, ``ACTION``, is declared here the way the built-in actions declare theirs
(l2p_bullet/actions/<name>/__init__.py): its example sentence, the rule set that judges it, and how its
training set differs from the defaults (``Training``: which actions' demonstrations are its negatives,
stretched or twisted copies, ...; see l2p_bullet/actions/spec.py). `l2p-bullet train` reads it.
"""
'''

_ACTION = '''
from l2p_bullet.actions.spec import ActionSpec, Training

ACTION = ActionSpec(
    name="{name}",
    source_name="{name}",
    sentence="{sentence}",
    rules={rules},
    training=Training(),
)
'''

_HEADER = """\
# Bundle manifest of the action "{name}".
# "phrases" are the prepositions this action answers to in sentences ("move A <phrase> B").
# `l2p-bullet train {name} ... --out <this folder>` fills in the model, training and metrics sections and
# writes progress.safetensors next to this file; until then the action is listed as "not trained".
"""

_COMPOSITE_HEADER = """\
# Bundle manifest of the composite action "{name}".
# "phrases" take a list of objects in sentences ("<phrase> A, B and C").
# `l2p-bullet teach {name}` records rows into demos.json next to this file and learns recipe.json from them
# (both listed under [weights] below); until then the action is listed as broken ("no trained weights").
"""

_MANIFEST = """\
schema = 1
name = "{name}"
version = "0.1.0"
requires = ">={version}"
phrases = [{phrases}]
description = {description}
# Where the relation is seen from: "relative" (it means the same whichever way the table is turned:
# around, past, closer to), "viewer" (left of, in front of, ... as seen from the robot's base) or
# "viewer:camera" (as seen from across the table, where the `--camera robot` video is filmed).
frame = "{frame}"
# How many reference objects a sentence names: 1 ("move A <phrase> B") or 2 ("move A between B and C").
anchors = {anchors}
"""

_COMPOSITE = """
# A composite action: its phrase takes a list of objects ("make a row of A, B, C and D"). It has no
# weights: `l2p-bullet teach` records whole rows and learns recipe.json from them (demos.json keeps them).
kind = "composite"
"""

_JUDGE = """
# Who decides whether a run succeeded: a rule judge of l2p_bullet/judge/rules.py (independent of the
# learned model the planner maximises). Without this section the action's own progress model judges.
[judge]
rules = "{rules}"
"""

_README = """\
# {dist}: the "{name}" action for l2p-bullet

Teaches `l2p-bullet perform` the phrases {phrases}, as in `l2p-bullet perform "{example}"`.

    {root}/
      pyproject.toml        declares the entry point  [project.entry-points."l2p_bullet.actions"]  {name} = "{module}"
      {module}/manifest.toml  the phrases, the frame, the number of anchors; training adds the model and metrics
      {module}/progress.safetensors   written by training
      demos/                your demonstrations (.npz)

## 0. Declare what the words mean geometrically

`{module}/manifest.toml` says where the relation is seen from and how many reference objects it has:

- `frame = "relative"` when the words mean the same whichever way the table is turned (around, past,
  closer to, next to); `frame = "viewer"` when they depend on who looks (left of, right of, in front of,
  behind as seen from the robot's base; `"viewer:camera"`: as seen from across the table, where `--camera robot` films).
  A viewer-frame action is not trained on mirror images (they would turn left into right): the mirror
  images that end on the wrong side are its negatives;
- `anchors = 1` for "move A {phrase} B", `anchors = 2` for two reference objects ("move A between B and C").

Change them before training (training reads them; a bundle whose declaration differs from what its
model was trained with is refused).

## 1. Demonstrations

Any of three ways; all end as capture-session files in `demos/`:

- **record them in the browser**: `l2p-bullet teach {name}` (run next to this folder, or with
  `--plugin {root}`) opens a page with a top-down view of a random scene; drag the block with the mouse,
  mark start and end, and each demonstration is appended to `demos/{name}_taught.npz`;
- **generate examples** of a few simple prepositions (left-of, right-of, in-front-of, behind, between),
  enough to try the whole path:

      python -c "from l2p_bullet.learning.synthetic import write_sessions; write_sessions('demos', '{kind}')"

- **record them with any tracker** (motion capture, a phone video and a marker tracker, ...) or write
  them with a script, in the format below.

Training reads the capture-session format of the shipped human demonstrations (`l2p_bullet/data/README.md`).
One `.npz` file is one session: the 2-D tracks of the blocks over time, and the annotated events in which
one block performs the action relative to the others. Required arrays:

| array             | shape  | meaning                                                                  |
|-------------------|--------|--------------------------------------------------------------------------|
| `shell_pose`      | (T, 3) | block 0: `[x, y, theta]` of its centre per frame (metres, radians)         |
| `stella_pose`     | (T, 3) | block 1, same frames                                                      |
| `event_start_end` | (E, 2) | `[first, last]` frame of each event (inclusive)                           |
| `event_mover`     | (E,)   | which block moves in each event: 0 (shell) or 1 (stella); the other is the anchor |

Needed by some declarations:

| array             | shape     | meaning                                                                 |
|-------------------|-----------|-------------------------------------------------------------------------|
| `viewer_xy`       | (2,)      | `frame = "viewer"`: where the viewer stood, same frame as the tracks     |
| `more_poses`      | (K, T, 3) | `anchors = 2`: tracks of blocks 2, 3, ...                                |
| `event_anchors`   | (E, n)    | each event's reference blocks by index (0 shell, 1 stella, 2... `more_poses`); required with `more_poses` |

Optional: `frame` (T,), `shell_observed`/`stella_observed` (T,) bool, `table_points_2d` (K, 2).
Frames are about 30 per second; blocks are 0.15 m squares (only relative geometry matters, so any fixed
frame works). Leave some still frames before and after each event: the progress model learns that
progress is 0 outside the event and rises to 1 at its end. Files are loaded with `allow_pickle=False`,
so save plain numeric arrays; `l2p_bullet.data.demos.save_session` writes them and checks them.

A script that writes them, for a one-anchor action (vary start positions, speeds, curved and
straight paths, both blocks as mover):

```python
import numpy as np

rng = np.random.default_rng(0)
for session in range(2):
    shell, stella, events = [], [], []
    t = 0
    for _ in range(20):                                # 20 events per session
        anchor = rng.uniform(-0.5, 0.5, 2)
        start = anchor + rng.uniform(-0.8, 0.8, 2)
        goal = anchor + np.array([0.0, 0.25])          # <- where "{phrase}" ends, relative to the anchor
        n = int(rng.integers(40, 80))
        s = np.linspace(0, 1, n)[:, None] ** rng.uniform(0.8, 1.2)
        path = np.vstack([np.repeat([start], 15, 0), start + s * (goal - start), np.repeat([goal], 15, 0)])
        shell.append(np.column_stack([path, np.zeros(len(path))]))
        stella.append(np.tile([*anchor, 0.0], (len(path), 1)))
        events.append([t + 15, t + 15 + n - 1])
        t += len(path)
    np.savez(f"demos/{name}_Session{{session + 1}}.npz", shell_pose=np.vstack(shell),
             stella_pose=np.vstack(stella), event_start_end=np.array(events),
             event_mover=np.zeros(len(events), dtype=np.int8){viewer}
```

Check that they load: `python -c "from l2p_bullet.data.demos import load_session; load_session('demos/{name}_Session1.npz')"`.

## 2. Train

    l2p-bullet train {name} --demos demos --out {module}

`--demos` takes several files (the shell expands `demos/*.npz`) or a folder. This writes
`{module}/progress.safetensors` and completes `{module}/manifest.toml` in place (model, training data
digest, metrics); its comments, version, phrases and declaration stay. The shipped demonstrations of the
built-in actions serve as negatives. Optionally (relative one-anchor actions), train a REINFORCE move
policy against the new model (the default planner then also proposes the policy's moves; without one
it searches without it):

    l2p-bullet train-policy {name} --bundle {module}

## 3. Install and use

    <env>/bin/pip install .  # the pip of the environment l2p-bullet runs in (or: install -e .)
                             # always a path: `pip install {dist}` would fetch a stranger's package;
                             # a plain install copies the bundle: install again after re-training
    l2p-bullet actions       # "{name}" is listed with its phrases
    l2p-bullet perform "{example}"

To share the action, build a wheel (`pip wheel . --no-deps`) and publish it like any Python package.
"""

_COMPOSITE_README = """\
# {dist}: the composite action "{name}" for l2p-bullet

Teaches `l2p-bullet perform` the phrases {phrases}, followed by a list of blocks, as in
`l2p-bullet perform "{example}" --scene SCENE` (a scene file with blocks A, B and C; docs/perform.md).

    {root}/
      pyproject.toml        declares the entry point  [project.entry-points."l2p_bullet.actions"]  {name} = "{module}"
      {module}/manifest.toml  the phrases and `kind = "composite"`; teaching adds the digests of the files below
      {module}/demos.json     the rows you demonstrated (written by the teach page)
      {module}/recipe.json    what was learned from them (the single action each step is, the spacing, the axis)

A composite has no progress model of its own: `l2p-bullet train` does not make one. It is performed as a
chain of an installed single action ("move B next to A, then move C next to B, ..."), learned from rows you
drag on the teach page (docs/perform.md, "Composite actions").

## 1. Teach it

    l2p-bullet teach {name} --plugin {root}      # then open http://127.0.0.1:8766/ (Ctrl+C stops it)

The page shows scenes of 2 or 3 cubes and the sentence "{example}". Drag the named blocks one after
another (each drag is one step; Q / W turn the dragged block), Enter saves the row, T learns the recipe
from every saved row and performs a row of four on a new scene, with video.

## 2. Install and use

    <env>/bin/pip install ./{root}   # the pip of the environment l2p-bullet runs in (or: install -e ./{root})
                                     # always a path: `pip install {dist}` would fetch a stranger's package;
                                     # a plain install copies the recipe: install again after teaching more rows
    l2p-bullet actions               # "{name}" is listed as a composite with its phrases
    l2p-bullet perform "{phrase} A, B, C and D" --scene SCENE   # blocks A-D (an l2p-bullet checkout has
                                                                 # examples/four_blocks.json)

To share the action, build a wheel (`pip wheel ./{root} --no-deps`) and publish it like any Python package.
"""
