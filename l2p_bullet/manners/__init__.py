"""Manners of motion (slide, carry, push): declarations and their entry-point registry (docs/manners.md)."""

from .registry import DEFAULT, discover, get, verb_table
from .spec import MannerSpec

__all__ = ["DEFAULT", "MannerSpec", "discover", "get", "verb_table"]
