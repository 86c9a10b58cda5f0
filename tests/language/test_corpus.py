"""The sentence corpus (corpus.tsv): what people type resolves to the right blocks, or is refused.

The goal is the issue's: at least 95 % resolved right and not one wrong resolution (a refusal beats a
wrong block), per category reported by ``python tests/language/corpus.py``.
"""

from __future__ import annotations

import pytest
from corpus import REFUSE, cases, read, resolve, scene, score

from l2p_bullet.errors import L2PError
from l2p_bullet.language import parse
from l2p_bullet.pipeline import resolve as resolve_one
from l2p_bullet.plugins import registry


def assert_read(plugins, name: str, floor: int, excused=lambda sentence, got: False) -> None:
    """No line of corpus ``name`` read as another object or action than its author wrote, but where ``excused``
    (an author who disagrees with most, an open reading kept visible), and at least ``floor`` lines read right."""
    table, misses = score(plugins, name)
    wrong = [(case.sentence, got) for case, got in misses if got != REFUSE and not excused(case.sentence, got)]
    assert not wrong, f"wrong resolutions: {wrong}"
    right = sum(c["right"] for c in table.values())
    assert right >= floor, f"{right}/160 right; misses: {[(c.sentence, g) for c, g in misses]}"


def test_the_corpus_is_large_and_varied():
    all_cases = cases()
    assert len(all_cases) >= 300
    assert len({c.category for c in all_cases}) >= 8
    assert len({c.sentence for c in all_cases}) == len(all_cases), "a sentence is listed twice"


def test_corpus_resolves_right_and_never_wrong(plugins):
    table, misses = score(plugins)
    right = sum(c["right"] for c in table.values())
    total = sum(sum(c.values()) for c in table.values())
    wrong = [(case.sentence, got) for case, got in misses if got != REFUSE]
    assert not wrong, f"wrong resolutions (a refusal beats a wrong block): {wrong}"
    assert right / total >= 0.95, f"{right}/{total} right; misses: {[(c.sentence, g) for c, g in misses]}"


def test_the_second_authors_corpus_is_never_resolved_wrong(plugins):
    """heldout.tsv: 147 sentences another author wrote without seeing the grammar (docs/language.md). It was
    read once before the grammar saw it (68.0 % right, 2 wrong) and has guided changes since, so it guards
    against regressions: no wrong resolution, and what was reached stays reached. Its author reads "bring" as
    a carry, the four later authors as a slide, and the toolkit follows the four (:data:`BRING`)."""
    table, misses = score(plugins, "heldout.tsv")
    wrong = [(case.sentence, got) for case, got in misses if got != REFUSE and BRING not in case.sentence.lower()]
    assert not wrong, f"wrong resolutions: {wrong}"
    right = sum(c["right"] for c in table.values())
    assert right >= 140, f"{right}/147 right; misses: {[(c.sentence, g) for c, g in misses]}"


def test_the_third_authors_corpus_is_never_resolved_wrong(plugins):
    """heldout3.tsv: 190 sentences a third author wrote from the scene and the notation alone, never reading the
    grammar or the other corpora. Read once before any change (80.5 % right, 5 wrong: docs/language.md); the
    general rules it prompted since make it a development figure now, kept here against regressions."""
    table, misses = score(plugins, "heldout3.tsv")
    wrong = [(case.sentence, got) for case, got in misses if got != REFUSE]
    assert not wrong, f"wrong resolutions: {wrong}"
    right = sum(c["right"] for c in table.values())
    assert right >= 188, f"{right}/190 right; misses: {[(c.sentence, g) for c, g in misses]}"


BRING = "bring"
"""The one word the authors disagree on: heldout.tsv's author reads "bring" as a carry (5 sentences), the fourth
to seventh authors (heldout4-7) as a slide; the toolkit reads it as a slide, as most people did
(docs/language.md), so heldout.tsv's five read otherwise."""


@pytest.mark.parametrize("name, floor", [("heldout4.tsv", 159), ("heldout5.tsv", 159), ("heldout6.tsv", 156),
                                         ("heldout7.tsv", 158), ("heldout8.tsv", 156), ("heldout9.tsv", 157)])
def test_the_fourth_to_ninth_authors_corpora_are_never_resolved_wrong(plugins, name, floor):
    """heldout4.tsv (the corpus table), heldout5.tsv (its own table: two red cubes, a white cube and a white
    mug, a can), heldout6.tsv (two blue cubes, a teddy, a stone, a long white box), heldout7.tsv (cubes P Q R,
    a bottle, a bunny, a flat box), heldout8.tsv (two red cubes, a ball, a duck, a cup, a brown box) and
    heldout9.tsv (cubes U V W, a plank, a jar, a mug, a stone): 160 sentences each, written cold, read once
    (71.2 % right / 4 wrong, 51.9 % / 3, 59.4 % / 4, 68.8 % / 2, 63.8 % / 1, 67.5 % / 6: docs/language.md);
    development figures since, kept here against regressions."""
    assert_read(plugins, name, floor)


DISAGREED = {
    "heldout10.tsv": {"Move the small cube away from the teddy."},
    "heldout11.tsv": {"leftmost thing away from the ball", "the rightmost thing, push it toward the bottle"},
    "heldout13.tsv": {"Move the biggest thing next to the jar."},
    "heldout17.tsv": {"Could you move the leftmost object closer to the rabbit?"},
    "heldout20.tsv": {"There are two green cubes - move the small one toward the duck and the other one away from it."},
    "heldout22.tsv": {"Put the teddy bear next to the blue cube.",
                      "Put the toy bear right next to the bigger cube, the blue one.",
                      "Would you kindly place the teddy bear next to the plank? Thank you.",
                      "Put the domino right next to the plank.",
                      "Please place the teddy directly beside the domino, with no gap.",
                      "Lift the plank. Carry it past the mug. Then put it next to the domino."},
    "heldout23.tsv": {"Arrange the three cubes in a row - yellow, small green, big green - then slide the milk carton "
                      "next to the big green one."},
    "heldout24.tsv": {"Move the small cube next to the big cube."},
    "heldout25.tsv": {"Move the biggest thing on the table next to the green cube."},
    "heldout42.tsv": {"Make it so the bowl's up against the green cube"},
    "heldout43.tsv": {"bump the short box closer to the tall one"},
    "heldout44.tsv": {"grab the soup and stick it next to the jello",
                      "grab the soda can and the soup can and put them both next to the box"},
    "heldout45.tsv": {"the biggest thing, move it next to the ball"},
    "heldout46.tsv": {"3307 up against tote"},
    "heldout47.tsv": {"shift the sugar bowl up against the butter dish",
                      "grab the salt and pepper and put them both next to the butter"},
    "heldout51.tsv": {"move rex to the pond and then put the other one by the barn"},
    "heldout52.tsv": {"grab the mouse, put it next to the phone",
                      "grab the thing in the middle, put it next to the mouse",
                      "shove the computer mouse up against the gray cylinder"},
    "heldout58.tsv": {"Final frame: lemon by the banana, lime away from it."},
    "heldout63.tsv": {"AirPods right up against the Post-it, asap.",
                      "Move the biggest thing on the desk next to the iPhone."},
    "heldout65.tsv": {"what I want is the board over by the kettle, and then the mug up against the board"},
    "heldout67.tsv": {"Remote go far from bowl please", "Small thing, put next to book."},
    "heldout68.tsv": {"move the gun next to the tote"},
    "heldout74.tsv": {"move the long thin flat thing next to the soap", "the biggest one next to the comb"},
    "heldout75.tsv": {"Carry the cadmium red around the water pot; afterwards set it down right against the sketchpad.",
                      "grab the eraser, put it next to the brush, then push the brush away from it"},
    "heldout76.tsv": {"pen 1 up against the thing you staple with"},
    "heldout79.tsv": {"the spanner by the claw, then the Makita up against the tape",
                      "grab the one nearest the Makita and stick it by the claw, then shift the tape past the screws"},
    "heldout81.tsv": {"put glue stick to ruler", "little round pot, put to purple stick",
                      "take scissor away from glue stick, then put it to crayon box"},
    "heldout85.tsv": {"Move the biggest thing next to the smallest thing.", "Move the skinny one next to the map."},
    "heldout86.tsv": {"Pin cushion - move it up against the tape.", "put the round one on the right beside the tape"},
}
"""Lines where the tenth and eleventh authors read otherwise than most authors before them (docs/language.md):
"the small cube" among 3, 4, 4 and 6 cm cubes is the 3 cm one for the others ("small" picks the clearly
smallest); "leftmost" / "rightmost" 3 cm apart is clear for the corpus table's author, a question for others;
"the biggest thing" is the object of the greatest bulk (the mug, against a long thin beam and a jar);
"away from it" after "move the small one toward the duck and the other one" is the one moved before (most authors),
the duck for one; a bare "put" or "place" is a slide for every other author and a carry for the twenty-second (and
"then put it" after a carry); "the big green one" after a row that named the big green cube is that cube for its
author, where the toolkit reads the big green object of the table (a 16 cm bottle); "the big cube" among 3, 4 and 5 cm
cubes is the 5 cm one, as "the small cube" is the clearly smallest; "the biggest thing" is the greatest bulk; a bare
"against" is a plain next-to for the twenty-sixth author, a tight one ("up against", "snug against") for the others.
"up against" outside a line about extents is a plain next-to for the forty-second author (and heldout40's and
heldout41's), a tight one for most; "the tall one" after "the short box" is the tallest thing for the forty-third, the
taller box as most authors' sized twins read; "grab X and put it ..." is a carry for six authors, a slide for two
and the forty-fourth; "the biggest thing" between a 9 x 6 x 4 cm box and a 6 x 10 cm can is the can (bulk) as
for most, a question for the forty-fifth. "it" in "lemon by the banana, lime away from it" is the banana for the
fifty-eighth author, where the toolkit reads "it" after a clause as the block that clause moved, as most authors do;
"asap" asks for no pace for the sixty-third (a hurry for the toolkit), and "the biggest thing" of a cup 12 cm tall and
a notebook of a larger footprint is a question for that author, the cup (bulk) for the toolkit as for most. "up
against" is plain for the sixty-fifth author too; "go far from" is a plain "away" for the sixty-seventh (far, as every
other author wrote "far from"), and "small thing" among three small and three big things is asked by that author, the
clearly smallest for the toolkit as "the small one" is for most; "the gun" is the tape gun by its name for the
toolkit, as "the cup" is the cup beside a mug, and asked by the sixty-eighth author, who calls the scanner a barcode
gun. For the seventy-fourth author "the long thin flat thing" is the toothbrush or the comb (the comb, 1 cm thick, is
the flat one for the toolkit) and "the biggest one" a question (the shampoo, twice any other's bulk, for the toolkit);
for the seventy-fifth "set it down" after a carry and "grab X, put it ..." are slides (carries for the toolkit, as for
six earlier authors); "up against" is plain for the seventy-sixth, and for the seventy-ninth, for whom "grab X and
stick it ..." is a slide too. "put X to Y" is "next to" for the eighty-first author, who was told so of one voice
(the notation and every other author: closer). For the eighty-fifth "the biggest thing" between a lantern of 1,020
cm3 and a bottle of 850 cm3 is a question (the lantern, the greater bulk, for the toolkit) and so is "the skinny
one" (the bottle, 7 cm across and 22 cm tall, for the toolkit); for the eighty-sixth "up against" is plain, and "the
round one on the right" 3 cm further right than the other is a near tie (clear for the toolkit at 3 cm)."""


@pytest.mark.parametrize("name, floor", [("heldout10.tsv", 156), ("heldout11.tsv", 155)])
def test_the_tenth_and_eleventh_authors_corpora(plugins, name, floor):
    """heldout10.tsv (cubes P Q R S, a tray, a can, a teddy) and heldout11.tsv (cubes E F G, a brick, a lid, a
    bottle, a ball): written cold, read once (78.8 % right / 4 wrong and 67.5 % / 4 on the grammar as it was; 81.9 %
    / 4 and 75.0 % / 5 with the lenient reading written before either was read: docs/language.md); development
    figures since. Wrong only where the author disagrees with most authors (:data:`DISAGREED`)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED[name])


@pytest.mark.parametrize("name, floor", [("heldout12.tsv", 157), ("heldout13.tsv", 158), ("heldout14.tsv", 157),
                                         ("heldout15.tsv", 157), ("heldout16.tsv", 155), ("heldout17.tsv", 152),
                                         ("heldout18.tsv", 156), ("heldout19.tsv", 153), ("heldout20.tsv", 155),
                                         ("heldout21.tsv", 150), ("heldout22.tsv", 143), ("heldout23.tsv", 153),
                                         ("heldout24.tsv", 156), ("heldout25.tsv", 156), ("heldout26.tsv", 148),
                                         ("heldout27.tsv", 149), ("heldout28.tsv", 144), ("heldout29.tsv", 145)])
def test_the_twelfth_to_seventeenth_authors_corpora(plugins, name, floor):
    """heldout12.tsv (cubes H J K, a slab, a tube, a duck) and heldout13.tsv (cubes M N T, a mug, a jar, a beam, a
    ball): written cold at the end of a session, read once on its grammar: 83.8 % / 3 wrong and 70.6 % / 2 wrong
    (75.6 % / 2 and 66.2 % / 3 on the grammar of the session's start); heldout14.tsv (cubes X Y Z, a domino, a bunny,
    a pot, a duck) and heldout15.tsv (cubes A B C, a plate, a bottle, a teddy, a stone): written cold, read once in the
    middle of the next session: 92.5 % / 2 and 89.4 % / 1 (90.6 % / 2 and 88.1 % / 1 on its start); heldout16.tsv (cubes
    R S T, a wedge, a cup, a tin, a bear) and heldout17.tsv (cubes K L M, a rod, a ball, a vase, a bunny): written cold,
    read once near that session's end: 86.9 % / 5 and 88.8 % / 1 (82.5 % / 4 and 86.2 % / 1 on its start;
    docs/language.md); heldout18.tsv to heldout21.tsv (a torus, a lego brick, a cone, a soccer ball, a prism, a tile,
    soap, a bunny on four new tables): written cold, read once at the next session's start: 81.9 % / 2, 80.6 % / 1,
    87.5 % / 2 and 73.8 % / 2; heldout22.tsv to heldout25.tsv (a domino, a teddy and a mug; a milk carton, a cereal
    box, a bread roll and a bottle as a model package ships them; objects named obj1 ... obj7 with a cup and a lemon;
    seven plain blocks): written cold, read once at the following session's start: 80.6 % / 8, 73.1 % / 4, 85.6 % / 5
    and 88.1 % / 2; heldout26.tsv to heldout29.tsv (LIBERO's groceries named as a user's file names them, Roboschool's
    household models, MyoSuite's and Genesis's hardware, three identical red cubes in a line): written cold, read once
    at the next session's start: 48.1 % / 2, 61.9 % / 1 (and one traceback), 58.8 % / 1 and 56.2 % / 2; development
    figures since. Wrong only where the author disagrees with most authors (:data:`DISAGREED`)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ()))


OPEN = {
    "heldout31.tsv": {
        # "the back one" after "the front green cube": the back green cube (block2), read as the backmost object
        "the front green cube and the back one, put them both next to the red cube":
            "slide:next-to block1 block3 ; slide:next-to block5 block3"},
    "heldout33.tsv": {
        # a clause without a verb after a push: a slide for the author, read as the push again
        "Push the ball to the mug. After, the same ball around the triangle.":
            "push:closer soccerball mug ; push:around soccerball prism"},
    "heldout41.tsv": {
        # "up against" without "right": a plain next-to for this author (and two of heldout40's lines), a tight one
        # for two earlier authors; read as tight
        "um put the little blue box up against the cup": "slide:next-to blue cup extent=right"},
    "heldout66.tsv": {
        # "the front left" of a cup 12 cm in front and 9 cm left and a lamp 6 cm in front and 20 cm left: both for the
        # author, the cup (farther toward the nearer of the corner's two sides) for the toolkit
        "the one in the front left \u27a1\ufe0f next to the keys": "slide:next-to cup keys"},
    "heldout67.tsv": {
        # "vaso" is Spanish for a glass, and one letter from "vase": asked by the author, read as the slip of "vase"
        "the vaso put it near to the book": "slide:closer vase book"},
    "heldout77.tsv": {
        # "glued to": touching for the author; read past as a word the grammar does not know, and "to" as closer
        "put the big blue glued to the white piece": "slide:closer D F"},
    "heldout78.tsv": {
        # "the apple by the lime, around the lemon": "by the lime" tells which apple for the author (and two apples as
        # near the plate are asked); read as two commands, the first a "next to"
        "The apple by the lime, around the lemon.": "slide:next-to apple lime ; slide:around apple lemon",
        "The apple by the plate, round the lemon.": "slide:next-to apple plate ; slide:around apple lemon"},
    "heldout80.tsv": {
        # "the can near the front right, sorry I mean the one at the back right": the blue can meant; the correction is
        # read as of "the front right", the place, and the red can moved
        "move the can near the front right, sorry I mean the one at the back right, around the cube in the front left":
            "slide:around red_can red_cube"},
    "heldout83.tsv": {
        # a clause without a verb after a push: a slide for the author (as for heldout33's), read as the push again
        "push green toward blue. the one I just moved, now away from the deck":
            "push:closer green_pawn blue_pawn ; push:away green_pawn card_deck"},
    "heldout88.tsv": {
        # "closest to the robot": the burner and the goggles 2 cm apart in x for the author (asked); nearest the robot's
        # base for the toolkit (the burner)
        "Move whatever's closest to the robot away from the flask - it's probably hot.": "slide:away burner flask"},
    # heldout90-108: the thirty-fourth session's cold batches, read once and not yet examined line by line (the
    # gardener's "the feed" mended as the seed tray's "seed" by a slip one keystroke away, seven times; "small
    # shovel" as the gloves); kept as they read now
    "heldout90.tsv": {
        "would you mind sliding the larger pot beside the feed? cheers":
            "slide:next-to pot_large seed_tray",
        "please be so kind to move small shovel closer to big pot":
            "push:closer gloves pot_large",
        "result must be: fertilizer near small shovel":
            "push:closer fertilizer gloves",
        "bring the hand trowel slightly closer to the feed":
            "slide:closer trowel seed_tray extent=little",
        "the feed, put it right up against the can":
            "slide:next-to seed_tray watering_can extent=right",
        "slowly slide the hand trowel past the feed":
            "slide:past trowel seed_tray pace=slow",
        "slide the hand trowel beside the feed, then push it a little toward the module tray":
            "slide:next-to trowel seed_tray ; push:closer trowel seed_tray extent=little",
        "nudge the feed closer to the gloves, then pick the gloves up and carry them past it":
            "push:closer seed_tray gloves ; carry:past gloves seed_tray",
        "line up the glovs the seed tray thingy and the big pot pls":
            "row seed_tray,pot_large",
        "move the biggest thing next to the glovs":
            "slide:next-to pot_large gloves",
    },
    "heldout91.tsv": {
        "Please kindly move the shorter green bottle past the soap bar.":
            "slide:past shampoo soap",
        "the short green bottle go past the cup":
            "slide:past shampoo toothbrush_cup",
        "Take the small green bottle, the short one, and put it next to the cotton":
            "slide:next-to shampoo cotton_pads",
        "Please move the green bottle to near of the cup.":
            "slide:closer shampoo toothbrush_cup",
    },
    "heldout92.tsv": {
        "Translate car_1 slightly toward the garage at reduced velocity.":
            "slide:closer car_1 garage extent=little",
        "canny noo, move the green block next tae the lorry":
            "slide:next-to block_green truck",
        "make the fire engine go round the garage":
            "slide:around truck garage",
    },
    "heldout94.tsv": {
        "get that bin WAY away from the bolt lmao 🚀":
            "slide:away Bin_Parts Bolt_M8 pace=fast extent=far",
        "slide the bolt next to the gear then the other one goes over toward the bin k? 👍":
            "slide:next-to Bolt_M8 Gear_40T ; slide:closer Nut_M8 Bin_Parts",
        "Deliverable: the threaded fastener, the long one, placed beside the drive gear.":
            "slide:next-to Bracket_L Gear_40T",
    },
    "heldout96.tsv": {
        "move the fluffy rolling thing next to the black tray":
            "slide:next-to tape_roll paint_tray",
        "sorry im new to this, can you put the fluffy rolling thing beside the paint can please":
            "slide:next-to tape_roll paint_can",
        "move the rolla uh right next to the paint tray":
            "slide:next-to tape_roll paint_tray extent=right",
        "um push the rolla slowly uh past the the wide brush":
            "push:past tape_roll brush_wide pace=slow",
        "um move the rolla next to the paint can and then uh move it past the rag":
            "slide:next-to tape_roll paint_can ; slide:past tape_roll rag",
        "the thing on the far left, move it closer to the fluffy rolling thing":
            "slide:closer paint_tray tape_roll",
        "move the smallest thing past the fluffy rolling thing":
            "slide:past brush_thin tape_roll",
        "move the one on the far right uh closer to the rolla":
            "slide:closer rag tape_roll",
        "um line up the paint can the rolla and the the rag":
            "row paint_can,tape_roll,rag",
    },
    "heldout101.tsv": {
        "smartly now, shift the shears clear of the tape measure":
            "slide:away scissors tape_measure",
    },
    "heldout102.tsv": {
        "green cube. closer to the yellow cylinder. we want green close to yellow.":
            "slide:closer cube_green cyl_yellow ; slide:closer cube_green cyl_yellow",
    },
    "heldout103.tsv": {
        "move the thing on the right over by the black thing":
            "slide:next-to clipboard stethoscope",
    },
    "heldout104.tsv": {
        "Move the dinosaur on the left toward the bucket.":
            "slide:closer ball bucket",
    },
    "heldout107.tsv": {
        "get the pad away from the popcorn bowl":
            "slide:away napkin popcorn_bowl",
        "shift the popcorn along til its sat next to the pad":
            "slide:next-to popcorn_bowl napkin",
    },
    "heldout109.tsv": {
        "grab the rocks, lift it over by the mat, then bottle past it":
            "carry:next-to rocks_glass bar_mat ; carry:past bottle rocks_glass",
        "put the bottle away from the lime then line up the jogger shaker and rocks glass":
            "slide:away bottle lime ; row shaker,rocks_glass",
        "move the cup next to the lime":
            "slide:next-to rocks_glass lime",
    },
    "heldout110.tsv": {
        "Move the bobber slightly away from the reel, just enough to give yourself finger room.":
            "push:away bobber reel extent=little",
    },
    "heldout111.tsv": {
        "ok chat step one blue die next to timer, step two push that one toward the pawn":
            "push:closer die_blue pawn",
    },
    "heldout112.tsv": {
        "cable next to tin, go. now the tin, away from it. go":
            "slide:next-to cable pick_tin ; slide:away cable pick_tin",
        "get the clip-on tuner away from my picks":
            "carry:away tuner pick_tin",
        "take the smalest thing and put it by the cabel":
            "slide:next-to capo cable",
    },
    "heldout113.tsv": {
        # "the Blumentopf, the small one": the small pot, read as the smallest object (the seed packet)
        "Shift the gloves near to the Blumentopf, the small one.":
            "slide:closer gloves seed_packet",
    },
    "heldout114.tsv": {
        # "Fastly": the pace, read past
        "Fastly take the syringe box around the blister pack.":
            "slide:around syringe_box blister_pack",
    },
    "heldout117.tsv": {
        # "the box" among a soap bar, a toothpaste tube and a razor, all box-shaped: asked, the author says; the
        # boxiest (the soap bar), as "the box" is read beside long thin ones
        "Move the box next to cup": "slide:next-to soap_bar toothbrush_cup",
    },
    "heldout119.tsv": {
        # "the largest box", "the biggest box": the book, the largest box-shaped thing; read among what is called a box
        # (the chalk box; reading both and asking where they differ turned 11 right lines of other corpora to
        # refusals)
        "Put the largest box beside the smallest object.": "slide:next-to chalk_box eraser",
        "move the biggest box next to the globe": "slide:next-to chalk_box globe",
    },
    "heldout120.tsv": {
        # "real quick" said of when, not how fast, the author says
        "diaper pack away from the cream real quick its in the way": "slide:away diaper_pack cream_tube pace=fast",
        # "shaky" read past as an unknown adjective, "toy" then the teddy
        "get the baby's shaky toy closer to the diapers": "slide:closer teddy diaper_pack",
        # "what is next the wipes" ("next" without "to"): read as "what is next:", then the wipes
        "move what is next the wipes closer to bottle": "slide:closer wipes baby_bottle",
    },
    "heldout121.tsv": {
        # "grab ... and put them": a carry by the manners' verbs, as four authors wrote it; six wrote a slide
        "grab the vase n the tape and put them both next to the card box":
            "carry:next-to vase card_box ; carry:next-to tape_roll card_box",
        # "the reel": the ribbon spool, the author says; read as the tape roll, whose "roll" it sounds like
        "the watering thing next to the reel": "slide:next-to watering_can tape_roll",
    },
    "heldout125.tsv": {
        # a verbless sentence after a push's: pushed as well, as the sentence before asked; a slide, the author says
        "Shove the oil bottle away from the tray. Now the tweezers up against it.":
            "push:away oil_bottle parts_tray ; push:next-to tweezers oil_bottle extent=right",
    },
    "heldout126.tsv": {
        # "it" is what was just moved, as the notation says; the author would ask (the rack or the beaker)
        "Bring the rack closer to the beaker, and then move the Bunsen burner away from it.":
            "slide:closer tube_rack beaker ; slide:away burner tube_rack",
    },
    "heldout128.tsv": {
        # "just past" is a little past in every other corpus that says it (19 lines); no extent, this author says
        "Let the stamp finish up just past the envelopes.": "slide:past stamp envelopes extent=little",
        # "next to it too": the same anchor, as three other authors wrote it; the ink pad, as two (this one) did
        "put the ink pad next to the envelopes, then move the stamp next to it too":
            "slide:next-to ink_pad envelopes ; slide:next-to stamp envelopes",
        # "the scales" said for the one scale: "them" read as both objects of the clause before (the sentence is read
        # with the plural mended to the name before the pronoun is read)
        "Move the scales a bit nearer the parcel and then nudge them round the envelopes.":
            "slide:closer scale parcel extent=little ; push:around scale envelopes ; push:around parcel envelopes",
    },
    "heldout130.tsv": {
        # "the metal one": the steel kettle, "metal" read as its grey; the author would ask (the tea tin is metal too)
        "move the metal one next to the mug": "slide:next-to kettle mug",
    },
    "heldout131.tsv": {
        # "up against" read as a tight gap, as the other authors wrote it (102 of 116 lines); this one wrote a plain one
        "pick up t'seed packet, carry it to t'gloves, then push t'twine up against it":
            "carry:closer seed_packet gloves ; push:next-to twine seed_packet extent=right",
    },
    "heldout132.tsv": {
        # "the biggest thing": the deck of cards (9 x 6.5 x 2.5 cm) by its outline, longer and wider than the bag of
        # tokens (6 x 6 x 4 cm) of all but the same bulk; the author would ask which
        "biggest thing away from the blue pawn": "slide:away card_deck pawn_blue",
    },
    "heldout133.tsv": {
        # a description said as a verbless move ("X, by the green box,") before the clause that moves it as "it"
        "That little white bottle at the back, by the green box, could you bring it toward the thermometer?":
            "slide:next-to pills_b syringe_box ; slide:closer pills_b thermometer",
    },
    "heldout134.tsv": {
        # "them both" after two moves to two anchors: the last clause's mover and anchor, where the author meant the two
        # moved
        "put the 85 by the blower and the 50 by the battery, then slide them both closer to the camera":
            "slide:next-to lens_85mm blower ; slide:next-to lens_50mm battery_1 ; slide:closer lens_50mm camera_body ; "
            "slide:closer battery_1 camera_body",
    },
}
"""Wrong readings found by a cold corpus read once on a session's last code and not mended since: kept visible here
(and in docs/language.md) rather than tuned away unseen; each is asserted as it is now, so mending it fails the
check below until the entry is removed."""


@pytest.mark.parametrize("name, floor", [("heldout30.tsv", 140), ("heldout31.tsv", 133), ("heldout32.tsv", 160),
                                         ("heldout33.tsv", 150), ("heldout34.tsv", 155), ("heldout35.tsv", 145),
                                         ("heldout36.tsv", 136), ("heldout37.tsv", 140), ("heldout38.tsv", 137),
                                         ("heldout39.tsv", 131), ("heldout40.tsv", 109), ("heldout41.tsv", 139)])
def test_the_thirtieth_to_thirty_ninth_authors_corpora(plugins, name, floor):
    """heldout30.tsv (an apple, a beaker and a potion bottle from ManiSkill and Roboschool, cubes and a cylinder named
    as a simulator names them: Apple_01, Cube_02) and heldout31.tsv (six plain objects a user's software named block1
    ... block6): written cold at the end of the twenty-fifth session and read once on its last code, after every rule
    of that session: 65.6 % / 0 wrong and 37.5 % / 2 wrong (:data:`OPEN`). heldout32.tsv to heldout34.tsv (a
    CALVIN-style tabletop named block_red ... with a bowl and a coffee stirrer; pybullet's toy models named after
    their files: cube, cylinder, prism, mug, soccerball; seven blocks named "1" to "7"): written cold at the
    twenty-sixth session's start and read once on its start code: 63.1 % / 2, 63.8 % / 4 and 71.2 % / 1.
    heldout35.tsv (a game engine's camelCase names: redCube, smallBox, Meta-World's coffee cup, robosuite's lemon and
    soda can) and heldout36.tsv (eight objects A ... H in three rows): written cold during that session and read once
    on its last language code: 88.1 % / 0 wrong and 80.6 % / 1 wrong; on its start code 88.1 % / 0 and 81.2 % / 1
    (the line between, "the green stick" for an 8 x 4 cm bar, lost to the proportions' stick and mended after the
    reading). The wrong one ("the leftmost one in the middle row" read without "row", the middle row's middle object)
    is refused since: the lenient reading leaves no word of a row, a column, a corner or an edge over. heldout37.tsv
    to heldout39.tsv (a reinforcement-learning scene indexed cube_0 ... with a bowl and a flat goal marker, texted and
    dictated; LIBERO's grocery meshes named ketchup_1, butter_1, alphabet_soup_1 ...; block1 ... block5 and a box, a
    front row): written cold at the twenty-seventh session's start and read once on its start code: 73.1 % / 0,
    71.2 % / 1 and 71.9 % / 1 wrong. heldout40.tsv (a Gazebo world's unit_box, unit_box_0, unit_cylinder with a coke
    can, a beer bottle and a marker cube) and heldout41.tsv (cubes named after their colours, red ... yellow, a
    ping-pong ball and a cup): written cold during that session and read once on its last language code: 50.0 % / 0
    and 75.6 % / 1 wrong (:data:`OPEN`)."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout42.tsv", 129), ("heldout43.tsv", 149), ("heldout44.tsv", 141),
                                         ("heldout45.tsv", 133), ("heldout46.tsv", 93)])
def test_the_forty_second_to_forty_sixth_authors_corpora(plugins, name, floor):
    """heldout42.tsv (a cooking class's fruit, one of them named "orange", beside an orange cube named "block"; a
    chef, a German speaker, a phone's dictation and a child), heldout43.tsv (a task file's left_block and right_block
    standing where their names no longer say, boxes big_box and small_box, a goal disc and an obstacle post; Indian
    English, numbered test steps, a gamer) and heldout44.tsv (a clean-up scene's mug_1, mug_2, a soda can and a soup
    can, a gelatin box, two cubes; a polite elder, a parent, a French speaker, a QA tester): written cold at the
    twenty-eighth session's start and read once on its start code: 50.6 % / 21 wrong (the fruit named "orange" read
    for "the orange block"), 68.1 % / 2 and 63.1 % / 2. heldout45.tsv (a bilingual classroom's objects named in
    Spanish: caja, pelota, taza, lata, cubo_rojo, cubo_azul) and heldout46.tsv (a packing station's parcels named by
    SKU, a tote, a cone, a scanner; a dictating supervisor): written cold during that session and read once on its
    last language code: 73.1 % / 4 wrong and 40.0 % / 5 wrong. Wrong only where the author disagrees with most
    authors (:data:`DISAGREED`) or the reading is kept visible (:data:`OPEN`)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ())
                or OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout47.tsv", 149), ("heldout48.tsv", 159), ("heldout49.tsv", 142),
                                         ("heldout50.tsv", 144), ("heldout51.tsv", 142), ("heldout52.tsv", 131),
                                         ("heldout53.tsv", 147)])
def test_the_forty_seventh_to_fifty_third_authors_corpora(plugins, name, floor):
    """Written cold in the twenty-ninth session, on tables whose names are not single words: heldout47.tsv (a
    breakfast table named with two words, "salt shaker"), heldout48.tsv (alphabet blocks A, I, O, X) and heldout49.tsv
    (a lab bench's beaker_250 and beaker_500), read once on its start code: 80.6 % / 4 wrong, 70.0 % / 1, 66.2 % / 1;
    heldout50.tsv (the YCB set as its files name it, 002_master_chef_can ...) and heldout51.tsv (toys a child named
    Rex, Daisy, Max, Nemo; their kinds declared in the scene file after the reading), read once mid-session: 33.8 % / 0
    and 42.5 % / 4; heldout52.tsv (an office desk, Hinglish) and heldout53.tsv (bricks named as a parts list names
    them, brick_2x4_red), read once on the session's last language code but one: 68.1 % / 8 and 31.9 % / 1. Wrong
    only where the author disagrees with most authors (:data:`DISAGREED`: "grab X, put it" a slide, "up against" a
    plain next-to, "the other one" after "move rex to the pond" asked)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ()))


@pytest.mark.parametrize("name, floor", [("heldout54.tsv", 138), ("heldout55.tsv", 136), ("heldout56.tsv", 142),
                                         ("heldout57.tsv", 113), ("heldout58.tsv", 143), ("heldout59.tsv", 134),
                                         ("heldout60.tsv", 103), ("heldout61.tsv", 138), ("heldout62.tsv", 147),
                                         ("heldout63.tsv", 145), ("heldout64.tsv", 139)])
def test_the_fifty_fourth_to_sixty_fourth_authors_corpora(plugins, name, floor):
    """Written cold in the thirtieth session, on tables whose names are not plain English words: heldout54.tsv (a chess
    set, German and dictated piece names), heldout55.tsv (a game engine's default names, Cube, Cube (1), Cylinder),
    heldout56.tsv (a French kitchen, théière), heldout57.tsv (people correcting themselves), heldout58.tsv (fruit, a
    Granny Smith beside a red apple), heldout59.tsv (a workbench, wrench_10mm) and heldout60.tsv (Singlish, Nigerian,
    Filipino and Scottish English), read once on 8c0f880: 36.2 % / 1 wrong, 59.4 % / 10, 41.2 % / 3, 52.5 % / 3,
    61.9 % / 5, 23.8 % / 0, 46.9 % / 3; heldout61.tsv (a Japanese table, koppu, hako), heldout62.tsv (a shape sorter),
    heldout63.tsv (brands, Sharpie, Starbucks) and heldout64.tsv (a lab's sample tubes S-0412 ... and CENT-2), read
    once on b6d64bb: 44.4 % / 0, 68.8 % / 1, 36.2 % / 4, 60.0 % / 2. Wrong only where the author disagrees with most
    authors (:data:`DISAGREED`)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ()))


@pytest.mark.parametrize("name, floor", [("heldout65.tsv", 125), ("heldout66.tsv", 144), ("heldout67.tsv", 128),
                                         ("heldout68.tsv", 131), ("heldout69.tsv", 128), ("heldout70.tsv", 129),
                                         ("heldout71.tsv", 137), ("heldout72.tsv", 134)])
def test_the_sixty_fifth_to_seventy_second_authors_corpora(plugins, name, floor):
    """Written cold in the thirty-first session, on everyday tables as people type about them: heldout65.tsv (a kitchen,
    things said by their use: "the thing you boil water in"), heldout66.tsv (a bedside table, texting, typos, emoji),
    heldout67.tsv (a living room, English as Chinese, Spanish, Russian and Arabic speakers write it), heldout68.tsv (a
    packing station, SKU-4471 and SKU-4472 by their last digits), heldout69.tsv (six gray game tokens: a top hat, a
    boot, a thimble), heldout70.tsv (blocks and jars said by what they are not, and by order), heldout71.tsv (a
    child's toys, "him" and "her") and heldout72.tsv (a procedure tray, ward slang: "pickups", "the blade"), read once
    on the session's start code (adbdc06): 43.1 % / 4 wrong, 68.8 % / 2, 64.4 % / 3, 56.9 % / 4, 58.1 % / 1, 76.9 % /
    1, 66.9 % / 5, 56.2 % / 3. Wrong only where the author disagrees with most authors (:data:`DISAGREED`) or as
    :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ())
                or OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout73.tsv", 134), ("heldout74.tsv", 132), ("heldout75.tsv", 110),
                                         ("heldout76.tsv", 141)])
def test_the_seventy_third_to_seventy_sixth_authors_corpora(plugins, name, floor):
    """Written cold in the thirty-second session, on shelves and desks as people type about them: heldout73.tsv (a
    robotics lab's YCB objects by their dataset names: "003_cracker_box", "the 005", "ycb 25", "the Cheez-It box"),
    heldout74.tsv (a bathroom shelf: shaky typing, care notes, brands, dictation's "the come" and "the racer"),
    heldout75.tsv (an art desk: a painter's words, a child's, someone across the desk saying "my left", dictation's
    "the water char") and heldout76.tsv (three identical pens told apart by place, label and order: "pen 2", "p3",
    "the pen by the mug"), read once on the session's start code (dc207bc): 79.4 % / 1 wrong, 61.9 % / 3, 40.0 % / 0,
    82.5 % / 1. Wrong only where the author disagrees with most authors (:data:`DISAGREED`)."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ()))


@pytest.mark.parametrize("name, floor", [("heldout77.tsv", 120), ("heldout78.tsv", 128), ("heldout79.tsv", 137),
                                         ("heldout80.tsv", 140)])
def test_the_seventy_seventh_to_eightieth_authors_corpora(plugins, name, floor):
    """Written cold in the thirty-third session, by learners, in notes and dictated: heldout77.tsv (six lettered blocks
    said by Korean, Indian, Brazilian and Turkish writers of English: "block A to B near move", "put the A in the side
    of the B", "slıde C"), heldout78.tsv (fruit on a kitchen counter: a chef, a parent, a voice assistant, a texting
    teenager's emoji), heldout79.tsv (a workshop bench: trade words, "the Makita", a beginner, an engineer's notes:
    "scrwdrvr", "tape_meas", dictation's "the ranch") and heldout80.tsv (cubes and cans said in steps, corrected, done
    again: "Actually make that ...", "do the same with ..."), read once on the session's start code (ca2fec2): 51.9 % /
    7 wrong, 68.1 % / 7, 49.4 % / 2, 83.1 % / 2. Wrong only where the author disagrees with most authors
    (:data:`DISAGREED`) or as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ())
                or OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout81.tsv", 127), ("heldout82.tsv", 127), ("heldout83.tsv", 133),
                                         ("heldout84.tsv", 122)])
def test_the_eighty_first_to_eighty_fourth_authors_corpora(plugins, name, floor):
    """Written cold in the thirty-third session after the rules of the seventy-seventh to eightieth: heldout81.tsv (a
    classroom: a teacher, a child's words, a parent writing without articles, autocorrect's "paint pit"),
    heldout82.tsv (a bedside table with two alike pill bottles: "bottle B", "the pill bottle hey", a carer's notes,
    clock directions), heldout83.tsv (a board game: jargon, Spanish among English words, compass directions to refuse,
    "the one I just moved") and heldout84.tsv (a lab's generic names obj_0 ...: code calls, a formal reviewer, French-
    shaped English, negation), read once on aad7b98: 69.4 % / 3 wrong, 47.5 % / 1, 58.1 % / 2, 50.0 % / 0. Wrong only
    where the author disagrees with most authors (:data:`DISAGREED`) or as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ())
                or OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout85.tsv", 111), ("heldout86.tsv", 124), ("heldout87.tsv", 101),
                                         ("heldout88.tsv", 73)])
def test_the_eighty_fifth_to_eighty_eighth_authors_corpora(plugins, name, floor):
    """Written cold at the end of the thirty-third session and read once on its last language code (0258a09):
    heldout85.tsv (a camping table: Australian slang's "the billy", a scout leader, a smartwatch's dictation, sizes),
    heldout86.tsv (a sewing table: a dressmaker's "the bobbin", capitals without punctuation, Irish English's "the
    yoke", colours and shapes mixed up), heldout87.tsv (three brown boxes by size: warehouse shorthand, a safety
    officer, comparisons, dictation's "the barrow") and heldout88.tsv (a chemistry bench: lab jargon, a student's "the
    fire thing", safety asides, a German speaker's "the Becherglas"): 62.5 % / 6 wrong, 70.6 % / 12, 61.9 % / 1, 26.9 %
    / 3. Wrong only where the author disagrees with most authors (:data:`DISAGREED`) or as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: sentence in DISAGREED.get(name, ())
                or OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, sentence", [(n, s) for n, lines in OPEN.items() for s in lines])
def test_open_wrong_readings_are_still_as_recorded(plugins, name, sentence):
    """An entry of :data:`OPEN` is how the toolkit reads the line now; once mended, remove the entry."""
    assert read(sentence, plugins, name) == OPEN[name][sentence]


@pytest.mark.parametrize("sentence, said", [
    ("move the cube past A", ['"the cube" is ambiguous', "A, B, C"]),
    ("move the block next to B", ["ambiguous", "A, B, C, D, E"]),
    ("move it next to B", ['"it"', "no", "earlier clause"]),
    ("move that same cube next to B", ['"that same cube"', "earlier clause"]),
    ("move A around B slowly and quickly", ["different paces"]),
    ("move A far around B", ['"far around"', "does not have"]),
    ("move the shortest one next to B", ["ambiguous", "A, B, C, D"]),
    ("move the one left of the duck next to B", ["nothing in the scene is left of duck"]),
])
def test_refusals_say_why_and_list_the_candidates(plugins, sentence, said):
    with pytest.raises(L2PError) as e:
        resolve_one(sentence, scene(), plugins)
    for s in said:
        assert s in str(e.value), str(e.value)


def test_a_word_that_names_an_object_is_never_dropped(plugins):
    """An object called "now" (a polite word) or "slowly" (a pace) is still the object."""
    from l2p_bullet.core.scene import Scene, SceneObject

    s = Scene((SceneObject("now", "red", 0.04, (0.1, 0.0)), SceneObject("slowly", "green", 0.04, (0.0, 0.1))))
    cmd = parse("move now next to slowly", s, registry.phrase_table(plugins))
    assert (cmd.mover, cmd.anchor, cmd.pace) == ("now", "slowly", None)


def test_pace_and_extent_are_recorded_on_the_command(plugins):
    cmd = resolve_one("could you gently slide the red block a bit closer to the green one?", scene(), plugins)
    assert (cmd.mover, cmd.anchor, cmd.action, cmd.pace, cmd.extent) == ("A", "B", "closer", "gentle", "little")
    plain = resolve_one("move A closer to B", scene(), plugins)
    assert (plain.pace, plain.extent) == (None, None)


def test_pronouns_follow_the_previous_clause(plugins):
    got = resolve("move A next to B, then move the other one around C, then move it past D", scene(), plugins)
    assert got == "slide:next-to A B ; slide:around B C ; slide:past B D"


@pytest.mark.parametrize("name, floor", [("heldout89.tsv", 85), ("heldout90.tsv", 89), ("heldout91.tsv", 107),
                                         ("heldout92.tsv", 113), ("heldout93.tsv", 89), ("heldout94.tsv", 96),
                                         ("heldout95.tsv", 109), ("heldout96.tsv", 68), ("heldout97.tsv", 114),
                                         ("heldout98.tsv", 51), ("heldout99.tsv", 77), ("heldout100.tsv", 88),
                                         ("heldout101.tsv", 96), ("heldout102.tsv", 56), ("heldout103.tsv", 47),
                                         ("heldout104.tsv", 100),
                                         ("heldout105.tsv", 65), ("heldout106.tsv", 107), ("heldout107.tsv", 39),
                                         ("heldout108.tsv", 85)])
def test_the_eighty_ninth_to_hundred_and_eighth_authors_corpora(plugins, name, floor):
    """Written cold in the thirty-fourth session in five batches, from the notation and a scene file alone, and
    read once each before the changes they were to measure (docs/language.md): heldout89-92 (an office desk, a
    potting bench, a bathroom shelf, a toy table: 377 of 640 on the session's start, 17 wrong), heldout93-96 (a tea
    tray, a CAD parts bench, six lettered blocks, a decorator's table: 344, 14 wrong; 350 with the WordNet look-up)
    heldout97-100 (a student's desk, a chopping area, test pieces, an elderly person's side table: 298, 5 wrong;
    316 with the look-up and the remarks) and heldout101-104 (a knitting basket, colour sorting, a clinic trolley, a
    sandpit: 284, 5 wrong; 297 with both, and with "next to" inside descriptions) and heldout105-108 (a camera kit,
    coded blocks, a snack table, a carpenter's bench: 286, 2 wrong; 296 with all of them and adjectives read past).
    Wrong only as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout109.tsv", 84), ("heldout110.tsv", 76), ("heldout111.tsv", 93),
                                         ("heldout112.tsv", 78)])
def test_the_hundred_and_ninth_to_hundred_and_twelfth_authors_corpora(plugins, name, floor):
    """Written cold at the thirty-fifth session's start, from the notation and a scene file alone, and read once on
    that start (bdeaa3b) before any change they were to measure (docs/language.md): a bar counter, a fishing tackle
    table, board-game pieces and a music studio desk: 330 of 640, 13 wrong; 332 and 10 wrong on that session's last
    code, where three of its wrong readings were examined and mended. Wrong only as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout113.tsv", 120), ("heldout114.tsv", 88), ("heldout115.tsv", 120),
                                         ("heldout116.tsv", 95)])
def test_the_hundred_and_thirteenth_to_hundred_and_sixteenth_authors_corpora(plugins, name, floor):
    """Written cold at the thirty-sixth session, from the notation and a scene file alone, and read once on that
    session's last reader code before anything was changed for them (docs/language.md): a potting bench, a pharmacy
    counter, a children's craft table and a picnic: 423 of 640, 3 wrong (the same on the session's start). Wrong only
    as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout117.tsv", 134), ("heldout118.tsv", 129), ("heldout119.tsv", 128),
                                         ("heldout120.tsv", 128)])
def test_the_hundred_and_seventeenth_to_hundred_and_twentieth_authors_corpora(plugins, name, floor):
    """Written cold at the thirty-seventh session, from the notation and a scene file alone, and read once on that
    session's reader code (13c72da) before anything was changed for them (docs/language.md): a bathroom counter, a
    baker's counter, a teacher's desk and a baby changing table: 502 of 640, 8 wrong; 519 and 6 wrong since (an end
    wished for and then ordered read as one move, an object said first by where it stands as the next clause's "it",
    "all the way" and "super far" as far, a package called by what it holds in other words). Wrong only as
    :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout121.tsv", 141), ("heldout122.tsv", 125), ("heldout123.tsv", 137),
                                         ("heldout124.tsv", 133)])
def test_the_hundred_and_twenty_first_to_hundred_and_twenty_fourth_authors_corpora(plugins, name, floor):
    """Written cold at the thirty-eighth session, from the notation and a scene file alone, and read once on the
    session's start (03fd356) before anything was changed for them (docs/language.md): a florist's table, a nail
    salon's table, a hotel reception desk and a model-railway table: 486 of 640, 8 wrong; 536 and 2 wrong since (an
    ordinal before "closest", "most on the left", every must / should / has to with every way of staying, "up" before a
    comparative, what was lifted and then moved a carry, a long name clipped, a kind's own synonyms in WordNet, rows
    said in more ways). Wrong only as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout125.tsv", 130), ("heldout126.tsv", 137), ("heldout127.tsv", 121),
                                         ("heldout128.tsv", 130)])
def test_the_hundred_and_twenty_fifth_to_hundred_and_twenty_eighth_authors_corpora(plugins, name, floor):
    """Written cold at the thirty-ninth session, from the notation and a scene file alone, and read once on the
    session's start (d7c8335) before anything was changed for them (docs/language.md): a watchmaker's bench, a school
    chemistry bench, a dog groomer's table and a post-office counter: 508 of 640, 9 wrong; 518 and 5 wrong since (a
    thing's own word no slip of another's, "glasses" as spectacles, "the soap for dogs" no dog brush, "the franking
    machine" no stamp, "up" before the phrase, "first" before the next clause, "all in a line", a statement after the
    command, "hold ... up"). Wrong only as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout129.tsv", 138), ("heldout130.tsv", 140)])
def test_the_hundred_and_twenty_ninth_and_thirtieth_authors_corpora(plugins, name, floor):
    """Written cold at the fortieth session on tables whose scene files write shades (a jeweller's counter: navy, gold,
    clear, burgundy, silver beside grey; a kitchen counter: steel, clear, beige, teal, cream, dark green, light yellow),
    and read once on bb42105, the shades' code, before anything was changed for them (docs/language.md): 132 and 137
    of 160, 0 and 2 wrong; since, "the gold box" for a box-shaped gold thing where no object named a box is gold,
    "see-through" and "transparent" for clear, "past of", and "would you lift X, put it ..." as a carry. Wrong only
    as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout131.tsv", 128), ("heldout132.tsv", 142)])
def test_the_hundred_and_thirty_first_and_second_authors_corpora(plugins, name, floor):
    """Written cold at the forty-first session (a gardener's potting bench whose scene file writes CSS shades, two
    brown flower pots; a board-game table whose scene file writes hex colours) and read once on 8ce3c87, before
    anything was changed for them (docs/language.md): 88 and 118 of 160, 2 and 2 wrong; since, Northern English ("t'",
    "an'", "o'", tek, reet, "them gloves"), a kind said with "of", an object by what it holds, a board game's men and
    figures, "more at the back", two sizes refused, "drop", "take up", a plural object's end state. Wrong only as
    :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)


@pytest.mark.parametrize("name, floor", [("heldout133.tsv", 125), ("heldout134.tsv", 119)])
def test_the_hundred_and_thirty_third_and_fourth_authors_corpora(plugins, name, floor):
    """Written cold at the forty-second session (a veterinary exam table with two alike pill bottles; a photographer's
    desk whose scene file writes hex colours, two lenses told apart by size) and read once on f7a802d, before anything
    was changed for them (docs/language.md): 120 and 106 of 160, 3 and 1 wrong; since, one shape's objects told apart
    by their height, "bring B back to it", "the card of memory", a doubt after the command, "shall", "row of ...",
    "line em up!! A, B, C", "with softness", "the leftmost box" among boxes. Wrong only as :data:`OPEN` records."""
    assert_read(plugins, name, floor, lambda sentence, got: OPEN.get(name, {}).get(sentence) == got)
