"""On tables whose scene files write shades (a jeweller's counter: a navy ring box, a gold watch case, a clear polish
jar, a burgundy tray, a silver bracelet box beside a grey gift box; a kitchen counter: a steel kettle, a clear jam jar,
a beige bread bin, a teal mug): a box-shaped thing is "the gold box" where nothing named a box is gold, the clear one is
"see-through" and "transparent" too (but "the magnifying glass" is no glass-clear thing), "past of" and "beyond of"
are "past", and "would you lift X, put it ..." is a carry as "lift X, put it ..." is. Checked on sentences of each
kind (not the corpora's own lines)."""

from __future__ import annotations

import pytest
from corpus import read

from l2p_bullet.errors import L2PError

JEWELLER = "heldout129.tsv"
KITCHEN = "heldout130.tsv"


@pytest.mark.parametrize("sentence, expect, table", [
    ("move the gold box next to the loupe", "slide:next-to watch_case loupe", JEWELLER),
    ("slide the golden box away from the jar", "slide:away watch_case polish_jar", JEWELLER),
    ("put the yellow box past the black one", "slide:past watch_case loupe", JEWELLER),
    ("move the navy box closer to the grey box", "slide:closer ring_box gift_box", JEWELLER),
    ("move the silver box around the loupe", "slide:around bracelet_box loupe", JEWELLER),
    ("move the see-through jar next to the mug", "slide:next-to jam_jar mug", KITCHEN),
    ("push the transparent one toward the kettle", "push:closer jam_jar kettle", KITCHEN),
    ("move the glass jar past the teal mug", "slide:past jam_jar mug", KITCHEN),
    ("move the cream pot next to the light yellow dish", "slide:next-to sugar_pot butter_dish", KITCHEN),
    ("move the mug past of the kettle", "slide:past mug kettle", KITCHEN),
    ("slide the tea tin a little beyond of the bread bin", "slide:past tea_tin bread_bin extent=little", KITCHEN),
    ("could you lift the mug, put it beside the kettle", "carry:next-to mug kettle", KITCHEN),
    ("please pick up the jam jar, set it near the bread bin", "carry:closer jam_jar bread_bin", KITCHEN),
])
def test_read_on_tables_of_shades(sentence, expect, table, plugins):
    assert read(sentence, plugins, table) == expect


def test_the_magnifying_glass_is_no_glass_clear_thing(plugins):
    with pytest.raises(L2PError, match='"the magnifying glass"') as e:
        read("slide the magnifying glass away from the ring box", plugins, JEWELLER)
    assert "white" not in str(e.value)
