"""The report's plots (matplotlib, Agg: no display needed), one PNG per question."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _plt():
    # lazy: matplotlib takes about a second to import; only when a figure is drawn
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_all(rep: dict, folder: Path) -> list[Path]:
    files = []
    tables = [(k, rep["graded"][k]) for k in ("original", "app") if rep["graded"][k]]
    if tables:
        files += [_table1(tables, folder / "table1.png"), _agreement(tables, folder / "agreement.png")]
    if rep["blind"]:
        files.append(_confusion(rep["blind"], folder / "confusion.png"))
    if rep["views"]:
        files.append(_views(rep["views"], folder / "views.png"))
    return files


def _table1(tables, path: Path) -> Path:
    """Mean grade per action with the evaluator disparity as a bar beside it."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(tables), figsize=(5.5 * len(tables), 3.6), squeeze=False)
    for ax, (key, t) in zip(axes[0], tables, strict=True):
        x = np.arange(len(t))
        ax.bar(x - 0.2, [r["mean_grade"] or 0 for r in t], 0.4, label="mean grade")
        ax.bar(x + 0.2, [r["disparity"] or 0 for r in t], 0.4, label="disparity")
        ax.set_xticks(x, [r["group"].replace(" (", "\n(") for r in t], fontsize=7)
        ax.set_ylim(0, 10)
        ax.set_title("original study (2-D)" if key == "original" else "graded here")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _agreement(tables, path: Path) -> Path:
    """Each run's mean grade against the learned final progress, one panel per group."""
    plt = _plt()
    groups = [(key, r) for key, t in tables for r in t]
    cols = min(4, len(groups))
    rows = -(-len(groups) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.8 * rows), squeeze=False)
    for ax in axes.flat[len(groups):]:
        ax.axis("off")
    for ax, (key, r) in zip(axes.flat, groups, strict=False):
        pts = [(f, m) for f, m in zip(r["_points"]["final"], r["_points"]["mean"], strict=True) if f is not None]
        if pts:
            ax.scatter(*zip(*pts, strict=True), s=14)
        ax.set_xlim(-0.05, 1.05)
        ax.set_ylim(-0.5, 10.5)
        rho = "n/a" if r["spearman_final_progress"] is None else f"{r['spearman_final_progress']:.2f}"
        ax.set_title(f"{'orig. ' if key == 'original' else ''}{r['group']}\nSpearman {rho}", fontsize=8)
        ax.set_xlabel("learned final progress", fontsize=7)
        ax.set_ylabel("mean grade", fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _confusion(blind: dict, path: Path) -> Path:
    plt = _plt()
    c = blind["confusion"]
    share = np.array(c["shares"], float)
    fig, ax = plt.subplots(figsize=(1.1 * len(c["cols"]) + 2, 0.8 * len(c["rows"]) + 1.5))
    ax.imshow(np.nan_to_num(share), cmap="Blues", vmin=0, vmax=1)
    for i in range(share.shape[0]):
        for j in range(share.shape[1]):
            if np.isfinite(share[i, j]):
                ax.text(j, i, f"{share[i, j]:.2f}", ha="center", va="center",
                        color="white" if share[i, j] > 0.5 else "black", fontsize=8)
    ax.set_xticks(range(len(c["cols"])), c["cols"], rotation=30)
    ax.set_yticks(range(len(c["rows"])), c["rows"])
    ax.set_xlabel("label given")
    ax.set_ylabel("true action")
    k = blind["fleiss"]["kappa"]
    ax.set_title(f"blind labels (row shares), Fleiss' kappa {'n/a' if k is None else f'{k:.2f}'}")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _views(views: list[dict], path: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(4, 4))
    for v in views:
        ax.scatter(v["_points"]["2d"], v["_points"]["3d"], s=16, label=v["action"])
    ax.plot([0, 10], [0, 10], color="#999", lw=0.8)
    ax.set_xlim(-0.5, 10.5)
    ax.set_ylim(-0.5, 10.5)
    ax.set_xlabel("mean grade, 2-D animation")
    ax.set_ylabel("mean grade, 3-D video")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
