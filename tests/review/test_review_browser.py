"""The review app in a real browser (headless Debian Chromium via Playwright), keyboard only.

Set L2P_DOCS_SCREENSHOT=1 to refresh docs/img/review_app.png from the graded-mode test.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from review_fixtures import live, open_page, run_folder  # noqa: F401 - fixtures (chromium: conftest.py)

pytestmark = pytest.mark.slow
DOCS_IMG = Path(__file__).resolve().parents[2] / "docs" / "img" / "review_app.png"


def _page(browser, url: str):
    return open_page(browser, url, 1000, 660)


def _login(page, name: str) -> str:
    page.wait_for_selector("#name")
    page.fill("#name", name)
    page.press("#name", "Enter")
    return _shown(page)


def _shown(page, previous: str | None = None) -> str:
    """Wait until a run other than ``previous`` is shown; its key:view."""
    page.wait_for_function("(prev) => document.body.dataset.state === 'review' && document.body.dataset.key "
                           "&& document.body.dataset.key !== prev", arg=previous or "")
    return page.get_attribute("body", "data-key")


def _keys(page, *keys: str) -> None:
    for k in keys:
        page.keyboard.press(k)


def test_grade_with_the_keyboard_reload_and_change_it(live, chromium, tmp_path):  # noqa: F811
    s = live()
    page, errors = _page(chromium, s.url)
    first = _login(page, "ann")
    sentence = page.inner_text("#sentence")
    assert sentence.startswith("“move A")
    _keys(page, "7")
    assert page.inner_text("#grades button.selected") == "77"  # the key hint and the grade
    _keys(page, "Enter")
    second = _shown(page, first)
    (g,) = s.store.grades()
    assert (g.reviewer, g.grade, g.mode, f"{s.queue.runs[first.split(':')[0]].key}:{g.view}") == (
        "ann", 7, "graded", first)

    page.reload()  # the name is remembered, the grade is in the database
    assert _shown(page) == second
    assert "1 / 4 answered" in page.inner_text("#count")
    _keys(page, "ArrowLeft")
    assert _shown(page, second) == first
    assert page.inner_text("#sentence") == sentence
    assert page.inner_text("#grades button.selected") == "77"
    _keys(page, "t", "Enter")  # change it to 10
    assert _shown(page, first) == second
    (g,) = s.store.grades()
    assert g.grade == 10
    _keys(page, "s")  # skip the second run: a third one comes
    third = _shown(page, second)
    assert third not in (first, second)
    _screenshot(page, tmp_path / "review_app.png")
    assert not errors


def _screenshot(page, path: Path) -> None:
    """The picture in docs/review.md: a rendered run (skip to one), a grade picked, the video playing."""
    shown = page.get_attribute("body", "data-key")
    while page.is_hidden("#video"):
        _keys(page, "s")
        shown = _shown(page, shown)
    _keys(page, "8")
    page.wait_for_timeout(2000)  # the video and the progress curve play on a little
    page.screenshot(path=str(path))
    if os.environ.get("L2P_DOCS_SCREENSHOT"):
        shutil.copy(path, DOCS_IMG)


def test_blind_mode_label_then_grade(live, chromium):  # noqa: F811
    s = live(mode="blind")
    page, errors = _page(chromium, s.url)
    first = _login(page, "bob")
    help_line = page.inner_text("#label-keys-help")  # the page shows its keys (issue 26)
    for hint in ("c: closer", "a: away", "n: next-to", "p: past", "r: around", "x: none of these"):
        assert hint in help_line, help_line
    assert page.inner_text("#sentence") == ""
    assert "move A" not in page.content()
    _keys(page, "5", "Enter")  # no label yet: refused on the page, nothing sent
    assert "pick the action" in page.inner_text("#status")
    _keys(page, "p")  # picking it answers the red line: it goes (issue 26: it stayed)
    assert page.inner_text("#status") == "" and page.get_attribute("#status", "class") == ""
    _keys(page, "Enter")
    _shown(page, first)
    (g,) = s.store.grades()
    assert (g.mode, g.label, g.grade) == ("blind", "past", 5)
    # the views have accessible names (a screen reader said "video", "canvas"), and none names an action
    names = {i: page.get_attribute(f"#{i}", "aria-label") for i in ("video", "flip", "top", "progress")}
    assert all(names.values()), names
    assert not any(a in n.lower() for n in names.values() for a in ("closer", "away", "next", "past", "around"))
    assert not errors


def test_a_plugin_named_like_html_is_shown_as_text(live, chromium):  # noqa: F811
    """Blind mode's labels are installed plugins' entry-point names, any text: the page put them in with
    innerHTML, so a plugin named ``<img src=x>`` added an element to the page."""
    from l2p_bullet.review.queue import blind_labels

    s = live(mode="blind")
    s.queue.labels = blind_labels(["<img src=x id=planted>", *s.queue.labels])
    page, errors = _page(chromium, s.url)
    _login(page, "eve")
    assert page.query_selector("#planted") is None
    assert "<img src=x id=planted>" in page.inner_text("#label-buttons")
    assert "<img src=x id=planted>" in page.inner_text("#label-keys-help")
    assert not errors


def test_two_reviewers_at_once(live, chromium):  # noqa: F811
    s = live()
    (a, ea), (b, eb) = _page(chromium, s.url), _page(chromium, s.url)
    ka, kb = _login(a, "ann"), _login(b, "bob")
    for _ in range(2):
        _keys(a, "3", "Enter")
        _keys(b, "8", "Enter")
        ka, kb = _shown(a, ka), _shown(b, kb)
    grades = s.store.grades()
    assert sorted((g.reviewer, g.grade) for g in grades) == [("ann", 3), ("ann", 3), ("bob", 8), ("bob", 8)]
    assert len({g.run_id for g in grades if g.reviewer == "ann"}) == 2
    assert not ea and not eb


def test_the_same_reviewer_in_two_windows_never_overwrites_silently(live, chromium):  # noqa: F811
    s = live()
    context = chromium.new_context(viewport={"width": 1000, "height": 660})
    a, b = context.new_page(), context.new_page()
    a.goto(s.url)
    first = _login(a, "ann")
    b.goto(s.url)  # same browser profile: the name is remembered, the same run is shown
    assert _shown(b) == first
    _keys(a, "4", "Enter")
    _shown(a, first)
    _keys(b, "6", "Enter")  # refused: b shows ann's stored answer instead
    b.wait_for_function("() => document.getElementById('status').textContent.includes('the stored answer now')")
    assert b.inner_text("#grades button.selected") == "44"
    (g,) = s.store.grades()
    assert g.grade == 4
    _keys(b, "6", "Enter")  # now it is a change of the stored answer
    _shown(b, first)
    (g,) = s.store.grades()
    assert g.grade == 6 and [e["grade"] for e in s.store.log()] == [4, 6]
    context.close()


def test_a_phone_wide_page_shows_the_whole_grading_panel(live, chromium, tmp_path):  # noqa: F811
    """Issue 26: at 390 px wide the grading panel was cut off (two columns of at least 300 and 280 px)."""
    s = live(mode="blind")
    page, errors = open_page(chromium, s.url, 390, 844)
    _login(page, "cy")
    page.wait_for_timeout(500)
    widths = page.evaluate("""() => ({page: document.documentElement.scrollWidth,
        panel: document.getElementById('panel').getBoundingClientRect().right,
        submit: document.getElementById('submit').getBoundingClientRect().right,
        grade10: document.querySelector('#grades button[data-grade="10"]').getBoundingClientRect().right,
        none: document.querySelector('#label-buttons button[data-label="none"]').getBoundingClientRect().right,
        media: document.getElementById('media').getBoundingClientRect().right})""")
    assert all(v <= 390 for v in widths.values()), widths  # nothing beyond the screen's right edge
    path = tmp_path / "review_390.png"
    page.screenshot(path=str(path), full_page=True)
    if os.environ.get("L2P_SCREENSHOT_DIR"):  # to look at it
        shutil.copy(path, Path(os.environ["L2P_SCREENSHOT_DIR"]) / path.name)
    _keys(page, "5", "p", "Enter")  # and it still grades
    page.wait_for_function("() => document.getElementById('status').textContent === 'saved'")
    assert [(g.label, g.grade) for g in s.store.grades()] == [("past", 5)]
    assert not errors


def test_the_default_video_plays_to_its_end_and_the_page_says_where_the_viewer_stands(chromium, tmp_path):  # noqa: F811
    """A run filmed with the default video (640x480 at 15 fps, lit, from behind the robot) plays to its
    end in Chromium, at its size, and the page says on which side of the table the viewer stands."""
    from review_fixtures import Live

    from l2p_bullet.core.scene import default_scene
    from l2p_bullet.embodiment.sim.camera import RenderSettings
    from l2p_bullet.pipeline import perform

    runs = tmp_path / "runs"
    perform("move A closer to B", default_scene(), out_dir=runs / "run0", render_settings=RenderSettings())
    s = Live(tmp_path / "reviews.sqlite", runs)
    try:
        page, errors = _page(chromium, s.url)
        _login(page, "vic")
        assert not page.is_hidden("#video")
        assert "you stand behind the robot" in page.inner_text("#viewname")
        assert "its left is your left" in page.inner_text("#viewname")
        page.wait_for_function("() => document.querySelector('#video').ended && document.body.dataset.ended === '1'",
                               timeout=60_000)
        size = page.evaluate(
            "[document.querySelector('#video').videoWidth, document.querySelector('#video').videoHeight]"
        )
        assert size[0] == 640 and size[1] > 480  # the frame and the caption strip under it
        assert not errors
    finally:
        s.stop()


def test_buttons_reached_with_tab_do_what_they_say_and_are_named_by_their_grade(live, chromium):  # noqa: F811
    """A keyboard user who tabs to a button and presses Enter or Space gets that button: Enter on a focused
    "skip" submitted the grade picked instead (Space replayed the run). A screen reader heard "77" for the
    grade 7 (the key hint in the name) and never which grade was picked. Enter still submits after a grade
    picked with the mouse (the clicked button gives its focus back)."""
    s = live()
    page, errors = _page(chromium, s.url)
    first = _login(page, "ann")
    seven = page.get_by_role("button", name="7", exact=True)
    assert page.get_by_role("button", name="10", exact=True).count() == 1
    _keys(page, "7")
    assert seven.get_attribute("aria-pressed") == "true"
    assert page.get_by_role("button", name="6", exact=True).get_attribute("aria-pressed") == "false"
    page.focus("#skip")
    _keys(page, "Enter")  # skips: the grade 7 is not sent
    second = _shown(page, first)
    page.focus("#skip")
    _keys(page, " ")
    third = _shown(page, second)
    assert s.store.grades() == []
    page.get_by_role("button", name="4", exact=True).click()
    _keys(page, "Enter")
    _shown(page, third)
    assert [g.grade for g in s.store.grades()] == [4]
    assert not errors


def _graded_with_a_comment(chromium, url: str):
    """(page, errors, the run shown): "ann" logged in, grade 7 picked and "it hesitated" typed, nothing sent."""
    page, errors = _page(chromium, url)
    first = _login(page, "ann")
    _keys(page, "7", "/")
    page.wait_for_function("() => document.activeElement.id === 'comment'")
    page.keyboard.type("it hesitated")
    _keys(page, "Escape")
    return page, errors, first


def test_a_server_that_does_not_answer_is_said_and_the_answer_stays_to_send_again(live, chromium):  # noqa: F811
    """The server stopped (or the network dropped) mid-session: the page said "not saved: Failed to fetch".
    It says the server does not answer and keeps the grade and the comment, sent with Enter once it is back."""
    s = live()
    page, errors, first = _graded_with_a_comment(chromium, s.url)
    # The network taken away by the browser's own offline switch: an aborted ``page.route`` now and then leaves
    # Chromium's fetch hanging instead of failing (microsoft/playwright#41802), which timed this test out.
    page.context.set_offline(True)
    _keys(page, "Enter")
    page.wait_for_function("() => document.getElementById('status').textContent.startsWith('not saved')", polling=100)
    text = page.inner_text("#status")
    assert "server does not answer" in text and "stays on this page" in text, text
    assert page.get_attribute("#status", "class") == "error"
    assert page.input_value("#comment") == "it hesitated" and page.inner_text("#grades button.selected") == "77"
    page.context.set_offline(False)
    _keys(page, "Enter")
    _shown(page, first)
    assert [(g.grade, g.comment) for g in s.store.grades()] == [(7, "it hesitated")]
    assert not errors


def test_a_reload_mid_answer_keeps_the_grade_and_the_comment_not_yet_sent(live, chromium):  # noqa: F811
    """A reload (F5, a slip of the finger) threw away the grade and the comment typed but not yet sent; they
    come back, said to be unsaved, and Enter sends them. Another run shown drops them, as before."""
    s = live()
    page, errors, first = _graded_with_a_comment(chromium, s.url)
    page.reload()
    assert _shown(page) == first
    assert page.inner_text("#grades button.selected") == "77" and page.input_value("#comment") == "it hesitated"
    assert "not saved yet" in page.inner_text("#status")
    _keys(page, "Enter")
    second = _shown(page, first)
    assert [(g.grade, g.comment) for g in s.store.grades()] == [(7, "it hesitated")]
    _keys(page, "3", "s")  # a grade picked, then skipped: gone after a reload
    third = _shown(page, second)
    page.reload()
    assert _shown(page) == third and page.query_selector("#grades button.selected") is None
    assert page.input_value("#comment") == ""
    assert not errors
