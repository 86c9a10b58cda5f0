"""Composite actions over a list of objects ("make a row of A, B, C and D"), learned from demonstrations.

recipe.py learns what the demonstrations share (each drag recognised as an installed action); bundle.py
stores the recipe with its demonstrations; row.py turns a sentence into a chain of the learned single
action with a slot per clause (docs/learning.md, "Composite actions").
"""
