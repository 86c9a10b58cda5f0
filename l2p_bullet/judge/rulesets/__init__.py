"""The rule sets, one module each: a built-in action's rule lives in the module its ``ActionSpec.rules``
names (``closer``, ``away``, ``next_to``, ``past``, ``around``), next to the ones plugins pick by name in
their manifest (``between``, ``sides``). Each module exports ``RULES`` (rule-set name -> function);
``judge/rules.py`` gathers them and runs them.

A rule function reads the motion in the anchor's frame: ``rule(rel, d, mover, anchor, size, **context)``,
``rel`` (T,2) and ``d`` (T,) in blocks (``footprints.relative``), ``mover`` and ``anchor`` (T,3) in metres,
``context`` the keywords a rule may need (``anchors``, ``viewer``); it returns a
:class:`~l2p_bullet.judge.base.Verdict`. Its thresholds are the action's own (``ActionSpec.thresholds``).
"""
