"""Judges: did a motion do what the sentence asked? One interface, :class:`Judge`, for all of them.

- :class:`~l2p_bullet.judge.rules.RuleJudge`: rules written from the meaning of the words (the five
  built-in actions ship theirs, ``judge/rules.py``); independent of the learned model the planner
  maximises, which is why the project reports them.
- :class:`~l2p_bullet.judge.learned.LearnedJudge`: the action's own progress model, the fallback
  for an action that ships no rules (its verdicts say so).
- a plugin's own judge, named in its manifest.

A bundle picks its judge in its manifest's ``[judge]`` section::

    [judge]
    rules = "next-to"                       # one of the rule sets in judge/rules.py ("between", "left-of", ...)
    # or
    entry = "l2p_between.judge:make_judge"  # a callable (bundle) -> Judge in the plugin's package
    # or nothing: the progress-model judge, optionally with  threshold = 0.6

``perform``, ``plan``, the benchmarks and the review report all get their judge from :func:`judge_for`.
"""

from __future__ import annotations

import importlib
from typing import Any

from ..errors import FailedToLoadPlugin, L2PError
from .base import Judge, Verdict, judge_context, plan_verdict
from .learned import THRESHOLD, LearnedJudge
from .rules import RULES, TWO_ANCHOR_RULES, RuleJudge, rule_verdict

__all__ = ["Judge", "Verdict", "RuleJudge", "LearnedJudge", "RULES", "rule_verdict", "judge_for", "judge_context",
           "plan_verdict"]


def judge_for(bundle: Any) -> Judge:
    """The judge a bundle's manifest names (see the module docstring); errors name the plugin."""
    spec = bundle.manifest.get("judge", {})
    if not isinstance(spec, dict):
        raise FailedToLoadPlugin(bundle.name, str(bundle.path), "[judge] must be a table")
    try:
        if "rules" in spec:
            judge = RuleJudge(str(spec["rules"]))
            wants = 2 if judge.rules in TWO_ANCHOR_RULES else 1
            if wants != int(bundle.manifest.get("anchors", 1)):
                raise ValueError(f'the rules "{judge.rules}" read {wants} reference object(s), the action declares '
                                 f'anchors = {bundle.manifest.get("anchors", 1)}')
            return judge
        if "entry" in spec:
            return _entry_judge(bundle, str(spec["entry"]))
        return LearnedJudge(bundle.name, bundle.progress_model(), float(spec.get("threshold", THRESHOLD)))
    except FailedToLoadPlugin:
        raise
    except (L2PError, TypeError, ValueError) as e:
        raise FailedToLoadPlugin(bundle.name, str(bundle.path), f"its [judge] cannot be used: {e}") from None


def _entry_judge(bundle: Any, entry: str) -> Judge:
    module, _, attr = entry.partition(":")
    if not module or not attr:
        raise ValueError(f'entry "{entry}" must read "package.module:callable"')
    try:
        factory = getattr(importlib.import_module(module), attr)
        judge = factory(bundle)
    except Exception as e:  # the plugin's own code: report it, never crash the caller
        raise FailedToLoadPlugin(bundle.name, str(bundle.path),
                                 f"its judge {entry} failed to load: {type(e).__name__}: {e}") from None
    if not isinstance(judge, Judge):
        raise FailedToLoadPlugin(bundle.name, str(bundle.path), f"{entry} did not return a judge "
                                 "(an object with .name and .judge(mover, anchor, size, final_progress=None), "
                                 "see l2p_bullet/judge/base.py)")
    return judge
