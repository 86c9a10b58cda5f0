"""Chains of instructions: "move A next to B, then slide C past A and then move D around B" as one run.

The front door of ``perform`` and ``plan`` for every sentence: a single sentence is a chain of one clause
(performed and written as one-clause runs are). clause.py is the clause record, splitting.py cuts the sentence
into its clauses' texts, clauses.py resolves them (composite.py makes a composite's clauses), forecast.py plans
the whole chain in 2-D up front, run.py executes it clause by clause in one PyBullet episode, files.py writes the
run folder (docs/perform.md, "Chains").
"""

from .clause import MAX_CLAUSES, Clause
from .clauses import is_chain, resolve_clauses
from .run import ChainResult, ClauseResult, perform_chain
from .splitting import split_clauses

__all__ = ["MAX_CLAUSES", "ChainResult", "Clause", "ClauseResult", "is_chain", "perform_chain", "resolve_clauses",
           "split_clauses"]
