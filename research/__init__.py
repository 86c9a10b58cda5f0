"""Experiments on the learning stage that did not ship, kept runnable: their benchmarks and tests import them.

Nothing in ``l2p_bullet`` imports this package (tests/test_layout.py checks it); docs/learning.md says what
each module measured and where its write-up is.
"""
