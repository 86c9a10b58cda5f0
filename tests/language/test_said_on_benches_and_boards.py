"""Sentences as a Northern English gardener, a board-game table and learners type them: "t'" for "the", a kind the
scene file says with "of", a board game's men and figures, an object said by what it holds, a plural object's end
state, and the words that must never be read into another object. The sentences are the tests' own, not the cold
corpora's lines (heldout131.tsv, heldout132.tsv), which are measured, never tuned on."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

BENCH = "heldout131.tsv"  # trowel, pot_small, pot_big (two flower pots), seed_tray, twine ("ball of twine"), gloves
BOARD = "heldout132.tsv"  # die, pawn_red, pawn_blue, card_deck, hourglass ("sand timer"), score_pad, token_bag
HOME = "heldout100.tsv"  # pill_organizer, glasses_case, tea_cup, remote, hearing_aid_box, crossword_book


@pytest.mark.parametrize("sentence, expect", [
    ("shift t'seed packet past t'trowel", "slide:past seed_packet trowel"),
    ("tek t'trowel past t'twine an' then past t'seed tray", "slide:past trowel twine ; slide:past trowel seed_tray"),
    ("move them gloves closer to t'big un", "slide:closer gloves pot_big"),
    ("put t'trowel by t'ball o' twine, ta very much", "slide:next-to trowel twine"),
    ("be a good lad and move the trowel away from the seed tray", "slide:away trowel seed_tray"),
])
def test_northern_english_as_typed(plugins, sentence, expect):
    assert read(sentence, plugins, BENCH) == expect


@pytest.mark.parametrize("name, sentence, expect", [
    (BENCH, "move the ball of twine away from the gloves", "slide:away twine gloves"),
    (BOARD, "put the little blue man next to the die", "slide:next-to pawn_blue die"),
    (BOARD, "move the blue figure past the cards", "slide:past pawn_blue card_deck"),
    (BOARD, "move the pawn that stands more at the back next to the die", "slide:next-to pawn_blue die"),
    (BOARD, "move the cards most at the back next to the die", "slide:next-to card_deck die"),
    (BOARD, "move the bag with the tokens in it past the die", "slide:past token_bag die"),
    (BOARD, "put the sand clock by the die", "slide:next-to hourglass die"),
    (BOARD, "make sure the cards are beside the die", "slide:next-to card_deck die"),
    (BOARD, "move the red pawn next to the die. other pawn next to the cards",
     "slide:next-to pawn_red die ; slide:next-to pawn_blue card_deck"),
    (BOARD, "pick up the die. drop it next to the cards", "carry:next-to die card_deck"),
    (BOARD, "take up the die and carry it past the cards", "carry:past die card_deck"),
    (BENCH, "move the twine beside the pot more big", "slide:next-to twine pot_big"),
    (BENCH, "move the little pot of brown colour next to the twine", "slide:next-to pot_small twine"),
    (BENCH, "move the big terracotta pot away from the twine", "slide:away pot_big twine"),
    (BENCH, "lift the trowel and put it by the twine, with attention", "carry:next-to trowel twine pace=careful"),
    (BENCH, "move the seed tray away from the trowel, as far as you can", "slide:away seed_tray trowel extent=far"),
])
def test_said_on_a_bench_and_a_board(plugins, name, sentence, expect):
    assert read(sentence, plugins, name) == expect


@pytest.mark.parametrize("name, sentence", [
    (BENCH, "make a row of big pot small pot and the twine"),  # two pots run together: never one of them
    (BENCH, "move the big small pot next to the twine"),  # two sizes of one object
    (BOARD, "the cards are next to the die"),  # tells how the table is, asks for nothing
    (BOARD, "move the figure next to the die"),  # two pawns
    (HOME, "move the cup of tea next to the pastillero, with care"),  # "care" is no slip of the glasses case
    (BENCH, "lift the big pot and bring it near the trowel, with attention it is heavy"),  # never the pace dropped
])
def test_what_must_not_be_read_as_another_object_is_refused(plugins, name, sentence):
    with pytest.raises(L2PError):
        read(sentence, plugins, name)
