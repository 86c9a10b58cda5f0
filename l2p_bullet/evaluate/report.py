"""``evaluate --report``: success per action, the two confusion matrices as text, and as PNG files.

The PNGs are drawn with matplotlib's Agg backend (no display needed), imported only here.
"""

from __future__ import annotations

import json
import statistics
from pathlib import Path

import numpy as np

from ..actions import BUILTIN
from .confusion import Confusion, _ordered, confusion, touching_finding

TOUCHING = {name: spec.touching for name, spec in BUILTIN.items() if spec.touching is not None}
"""The actions whose report adds a touching finding (``ActionSpec.touching``), by name."""


def success_table(rows: list[dict], order: list[str] | None = None) -> list[dict]:
    """Per action: runs, success rate, errors, mean final progress, mean dev and max anchor shift, mean time."""
    out = []
    for a in _ordered({r["action"] for r in rows}, order):
        rs = [r for r in rows if r["action"] == a]
        ok = [r for r in rs if r.get("error") is None]

        def mean(key: str, rows_: list[dict] = ok) -> float:
            vals = [r[key] for r in rows_ if r.get(key) is not None]
            return statistics.fmean(vals) if vals else float("nan")

        out.append({
            "action": a, "runs": len(rs), "success": sum(bool(r.get("success")) for r in rs) / max(len(rs), 1),
            "errors": len(rs) - len(ok), "final_progress": mean("final_progress"),
            "max_deviation_mm": 1000 * mean("max_deviation_m"),
            "anchor_moved_mm": 1000 * max((r["anchor_displacement_m"] for r in ok
                                           if r.get("anchor_displacement_m") is not None), default=float("nan")),
            "plan_s": mean("plan_s"), "total_s": mean("total_s"),
        })
    return out


def _matrix_text(title: str, names_r: list[str], names_c: list[str], m: np.ndarray, fmt: str) -> str:
    w = max(8, *(len(n) for n in names_c))
    corner = "asked \\ recognised"
    lines = [title, f"{corner:<20}" + "".join(f"{n:>{w + 1}}" for n in names_c)]
    for i, r in enumerate(names_r):
        lines.append(f"{r:<20}" + "".join(f"{_cell(v, fmt):>{w + 1}}" for v in m[i]))
    return "\n".join(lines)


def _cell(v: float, fmt: str) -> str:
    """A number, or blank where no run informs it (NaN: all runs errors, or an action that cannot judge them)."""
    return "" if v != v else format(v, fmt)


def error_reasons(rows: list[dict], width: int = 160) -> list[str]:
    """Per action, each distinct error of its runs with how many runs ended in it, most frequent first."""
    by: dict[tuple[str, str], int] = {}
    for r in rows:
        if r.get("error") is not None:
            key = (r["action"], str(r["error"]).splitlines()[0][:width])
            by[key] = by.get(key, 0) + 1
    return [f"  {a}: {n} x {msg}" for (a, msg), n in sorted(by.items(), key=lambda kv: (kv[0][0], -kv[1]))]


def report_text(rows: list[dict], c: Confusion | None = None) -> str:
    """The whole report as text (what ``evaluate --report`` prints)."""
    c = c or confusion(rows)
    modes = {r.get("mode") for r in rows}
    what = "the plan (--plan-only)" if modes == {"plan"} else "the executed trajectory"
    lines = [f"success per action (the action's own judge on {what})",
             f"{'action':<12}{'runs':>6}{'success':>9}{'errors':>8}{'progress':>10}{'dev mm':>8}{'anchor mm':>10}"
             f"{'plan s':>8}{'total s':>9}"]
    for s in success_table(rows):
        lines.append(f"{s['action']:<12}{s['runs']:>6}{100 * s['success']:>8.0f}%{s['errors']:>8}"
                     f"{_cell(s['final_progress'], '.2f'):>10}{_cell(s['max_deviation_mm'], '.1f'):>8}"
                     f"{_cell(s['anchor_moved_mm'], '.2f'):>10}{_cell(s['plan_s'], '.2f'):>8}"
                     f"{_cell(s['total_s'], '.2f'):>9}")
    manners = sorted({r.get("manner") or "slide" for r in rows})
    if manners != ["slide"]:  # evaluate --manners: the same table per manner of motion
        lines += ["", "success per manner and action (the manner's physical signature checked too)",
                  f"{'manner':<8}{'action':<12}{'runs':>6}{'success':>9}{'errors':>8}{'dev mm':>8}{'anchor mm':>10}"]
        for m in manners:
            for s in success_table([r for r in rows if (r.get("manner") or "slide") == m]):
                lines.append(f"{m:<8}{s['action']:<12}{s['runs']:>6}{100 * s['success']:>8.0f}%{s['errors']:>8}"
                             f"{_cell(s['max_deviation_mm'], '.1f'):>8}{_cell(s['anchor_moved_mm'], '.2f'):>10}")
    reasons = error_reasons(rows)
    if reasons:
        lines += ["", "errors (runs x reason; the whole message is in results.sqlite):", *reasons]
    lines += ["", _matrix_text("judge-based confusion: share of runs each action's judge accepts",
                               c.asked, c.recognised, 100 * c.judges, ".0f"),
              "", _matrix_text("model-based confusion: mean final learned progress of each action's model",
                               c.asked, c.recognised, c.models, ".2f"),
              "", _matrix_text("model-based, recognised as the highest-scoring model: share of runs",
                               c.asked, c.recognised, 100 * c.argmax, ".0f")]
    for name, t in TOUCHING.items():
        f = touching_finding(rows, name, t.also) if name in c.asked else {"runs": 0}
        if f["runs"]:
            w, n = f["share_within"], f["runs"]
            lines += ["", f'"{name}" runs: final gap to the anchor within 0.2 / 0.3 / 0.5 block: '
                          f'{100 * w["0.2"]:.0f} / {100 * w["0.3"]:.0f} / {100 * w["0.5"]:.0f} % of {n} '
                          f'(median {f["median_gap_blocks"]:.2f} block); read as "{t.also_words}" by its '
                          f'judge: {f["read_as_also"]} of {n}. {t.note}']
    return "\n".join(lines)


def save_plots(c: Confusion, out_dir: str | Path) -> dict[str, Path]:
    """confusion_judges.png and confusion_models.png in ``out_dir``."""
    # lazy: matplotlib takes about a second to import; only when a figure is drawn
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out_dir)
    files = {}
    for key, m, title, fmt in (("judges", c.judges, "accepted by the judge of (share of runs)", "{:.0%}"),
                               ("models", c.models, "mean final learned progress of the model of", "{:.2f}")):
        fig, ax = plt.subplots(figsize=(1.3 * len(c.recognised) + 2.5, 1.0 * len(c.asked) + 2))
        cmap = matplotlib.colormaps["viridis"].with_extremes(bad="white")  # NaN: no run informs the cell
        im = ax.imshow(np.ma.masked_invalid(m), vmin=0, vmax=1, cmap=cmap)
        ax.set_xticks(range(len(c.recognised)), c.recognised, rotation=30, ha="right")
        ax.set_yticks(range(len(c.asked)), [f"{a} ({n})" for a, n in zip(c.asked, c.counts, strict=True)])
        ax.set_xlabel("recognised as")
        ax.set_ylabel("asked (runs)")
        ax.set_title(title, fontsize=10)
        for i in range(len(c.asked)):
            for j in range(len(c.recognised)):
                if m[i, j] != m[i, j]:
                    continue  # left blank, not 0 %
                ax.text(j, i, fmt.format(m[i, j]), ha="center", va="center",
                        color="black" if m[i, j] > 0.6 else "white", fontsize=9)
        fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04)
        fig.tight_layout()
        files[key] = out / f"confusion_{key}.png"
        fig.savefig(files[key], dpi=110)
        plt.close(fig)
    return files


def write_report(rows: list[dict], out_dir: str | Path) -> tuple[str, dict[str, Path]]:
    """Print-ready text; also saves the PNGs and ``report.json`` (the numbers) in ``out_dir``."""
    c = confusion(rows)
    files = save_plots(c, out_dir) if c.asked and c.recognised else {}
    data = {"success": [{k: (None if v != v else v) for k, v in s.items()} for s in success_table(rows)],
            "errors": error_reasons(rows), "confusion": c.to_dict(),
            **{f"{name}_touching": touching_finding(rows, name, t.also) if name in c.asked else None
               for name, t in TOUCHING.items()}}
    files["json"] = Path(out_dir) / "report.json"
    files["json"].write_text(json.dumps(data, indent=1, default=float) + "\n")
    return report_text(rows, c), files
