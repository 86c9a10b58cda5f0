"""Benchmark the review app: grade 20 runs with the keyboard alone, in a real browser, and time it.

    .venv/bin/python benchmarks/bench_review.py                     # 20 runs (4 per action), default render
    .venv/bin/python benchmarks/bench_review.py --runs-dir /tmp/rv  # reuse run folders made before
    .venv/bin/python benchmarks/bench_review.py --no-watch          # grade as soon as a run is shown

It performs the runs (``pipeline.perform`` with the default 320x240, 10 fps rendering, seeded random
scenes), starts the app on 127.0.0.1 with a fresh database, and drives headless Debian Chromium
(Playwright) like a reviewer who uses the keyboard only: type a name and Enter once, then for every
run wait until its video has played to the end at the page's default speed (2x), press a digit and
Enter. It prints the keystrokes, the server's time to store an answer (its Server-Timing header: the
transaction, the check of the run's file and the JSON, not the network), the time from Enter to the
next run on the page, and the grading's wall time. A person adds their own decision time; the
table says how much of the 5-minute goal (issue 11) is left for it.
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from review_fixtures import CHROMIUM, CHROMIUM_FLAGS, LABELS  # noqa: E402

SENTENCES = ["move A closer to B", "move A away from B", "move A next to B", "move A past B", "move A around B"]
GOAL_S = 300.0


def make_runs(root: Path, n: int) -> Path:
    from l2p_bullet.core.scene import random_scene
    from l2p_bullet.pipeline import perform

    for i in range(n):
        t = time.perf_counter()
        perform(SENTENCES[i % len(SENTENCES)], random_scene(500 + i), out_dir=root / f"run{i:02d}")
        print(f"  run {i + 1}/{n}: {SENTENCES[i % len(SENTENCES)]} ({time.perf_counter() - t:.1f} s)", file=sys.stderr)
    return root


def grade_by_keyboard(url: str, n: int, watch: bool) -> dict:
    from playwright.sync_api import sync_playwright

    server_ms: list[float] = []
    enter_to_next: list[float] = []
    keys = {"name": 0, "answers": 0}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS, headless=True)
        page = browser.new_page(viewport={"width": 1000, "height": 660})

        def on_response(r) -> None:
            if r.url.endswith("/api/answer") and r.request.method == "POST":
                m = re.search(r"dur=([0-9.]+)", r.headers.get("server-timing", ""))
                if m:
                    server_ms.append(float(m.group(1)))

        page.on("response", on_response)
        page.goto(url)
        page.wait_for_selector("#name")
        t0 = time.perf_counter()
        page.keyboard.type("bench")
        page.keyboard.press("Enter")
        keys["name"] = len("bench") + 1
        shown = None
        for i in range(n):
            page.wait_for_function("(prev) => document.body.dataset.state === 'review' && document.body.dataset.key "
                                   "&& document.body.dataset.key !== prev", arg=shown or "")
            shown = page.get_attribute("body", "data-key")
            if watch:
                page.wait_for_selector("body[data-ended='1']", timeout=120_000)
            page.keyboard.press(str(i % 10))
            t = time.perf_counter()
            page.keyboard.press("Enter")
            keys["answers"] += 2
            page.wait_for_function("(prev) => document.body.dataset.key !== prev", arg=shown)
            enter_to_next.append((time.perf_counter() - t) * 1000)
        page.wait_for_selector("body[data-state='done']")
        wall = time.perf_counter() - t0
        browser.close()
    return {"wall_s": wall, "server_ms": server_ms, "enter_to_next_ms": enter_to_next, "keys": keys}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--runs-dir", type=Path, default=None, help="Use (or fill) this folder of run folders.")
    ap.add_argument("--no-watch", action="store_true", help="Do not wait for each video to end.")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()

    from l2p_bullet.review.app import create_app
    from l2p_bullet.review.queue import ReviewQueue
    from l2p_bullet.review.runs import find_runs
    from l2p_bullet.review.store import Store
    from l2p_bullet.web.server import start

    with tempfile.TemporaryDirectory() as tmp:
        root = args.runs_dir or Path(tmp) / "runs"
        if not (root.exists() and len(list(root.glob("*/trajectory.json"))) >= args.runs):
            print(f"performing {args.runs} runs into {root} ...", file=sys.stderr)
            make_runs(root, args.runs)
        runs = find_runs([root])[: args.runs]
        store = Store(Path(tmp) / "reviews.sqlite")
        store.register_runs(runs)
        server = start(create_app(ReviewQueue(store, runs, "graded", "3d", LABELS)))
        try:
            r = grade_by_keyboard(server.url, len(runs), watch=not args.no_watch)
        finally:
            server.stop()
        grades = store.grades()
        assert len(grades) == len(runs) and {g.reviewer for g in grades} == {"bench"}, "answers missing"
        durations = [run.duration_s for run in runs]

    n = len(runs)
    watch = sum(durations) / 2.0
    rows = [
        ("runs graded", f"{n}"),
        ("keystrokes per answer", f"{r['keys']['answers'] / n:.0f} (a digit, Enter)"),
        ("keystrokes in all", f"{r['keys']['answers'] + r['keys']['name']} (name and Enter once: {r['keys']['name']})"),
        ("server time to store an answer, ms (median / max)",
         f"{statistics.median(r['server_ms']):.1f} / {max(r['server_ms']):.1f}"),
        ("Enter to the next run on the page, ms (median / max)",
         f"{statistics.median(r['enter_to_next_ms']):.0f} / {max(r['enter_to_next_ms']):.0f}"),
        ("video length per run, s (mean / max, 1x)", f"{statistics.mean(durations):.1f} / {max(durations):.1f}"),
        ("watching every video to its end at 2x, s", f"{watch:.0f}" if not args.no_watch else "not waited for"),
        ("grading wall time, keyboard only, s", f"{r['wall_s']:.0f}"),
        ("left of the 5 minutes for a person's decisions, s per run", f"{(GOAL_S - r['wall_s']) / n:.1f}"),
    ]
    width = max(len(k) for k, _ in rows)
    print(f"\n| {'measure':<{width}} | value |\n|{'-' * (width + 2)}|---|")
    for k, v in rows:
        print(f"| {k:<{width}} | {v} |")
    if args.json:
        args.json.write_text(json.dumps({"runs": n, "durations_s": durations, **r}, indent=1))


if __name__ == "__main__":
    main()
