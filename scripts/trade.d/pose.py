# SPDX-License-Identifier: MIT
"""The figure of `prt-bake trade pose` for scripts/plot_trade.py: shaded error on the test frames
against model bytes under the first map and under the directional light (one line per model and
pose dimension p; horizontal: the mean-pose baseline, the unshadowed part alone and the visibility
oracle; dotted: the basis projection, the best any regression onto the residual model's basis could reach), the
cross-validation curve of alpha (alpha.csv beside trade.csv, like the paper's Fig. 3), and the
shading time of every vertex against model bytes."""
import csv
import os

COLUMNS = {"p": int, "q": int, "alpha": float, "model_bytes": int, "training_share": float,
           "frame_share": float, "transfer_error": float, "shaded_rel_rmse": float,
           "shade_cpu_ms": float, "shade_simd_ms": float}
FITTED = ["paper (direct)", "residual"]
TRADE_CSV = "trade.csv"  # set by plot_trade.py

def _lines_vs_bytes(ax, rows, light):
    rows = [r for r in rows if r["map"] == light]
    for i, model in enumerate(FITTED):
        for j, p in enumerate(sorted({r["p"] for r in rows if r["model"] == model})):
            sweep = sorted((r for r in rows if r["model"] == model and r["p"] == p),
                           key=lambda r: r["model_bytes"])
            ax.plot([r["model_bytes"] / 2**10 for r in sweep],
                    [100 * r["shaded_rel_rmse"] for r in sweep], "o-x^s"[j % 4] + "-",
                    color=f"C{i}", label=f"{model}, p={p}", alpha=1.0 - 0.25 * j)
    bound = sorted((r for r in rows if r["model"] == "basis projection"),
                   key=lambda r: r["q"])
    residual_bytes = {r["q"]: r["model_bytes"] for r in rows if r["model"] == "residual"}
    points = [(residual_bytes[r["q"]] / 2**10, 100 * r["shaded_rel_rmse"]) for r in bound
              if r["q"] in residual_bytes]
    if points:
        points.sort()
        ax.plot([x for x, _ in points], [y for _, y in points], ":", color="C1",
                label="basis projection (bound)")
    for style, model in (("--", "mean pose"), ("-.", "unshadowed only"),
                         (":", "visibility oracle")):
        for r in rows:
            if r["model"] == model:
                ax.axhline(100 * r["shaded_rel_rmse"], linestyle=style, color="grey",
                           label=model)
    ax.set_xscale("log")
    ax.set_xlabel("model bytes (KiB)")
    ax.set_ylabel("shaded relative RMSE on the test frames (%)")
    ax.set_title(f"Held-out error under {light}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def error_vs_bytes_map(ax, rows, maps):
    _lines_vs_bytes(ax, rows, maps[0])


def error_vs_bytes_directional(ax, rows, maps):
    _lines_vs_bytes(ax, rows, maps[-1])


def alpha_curve(ax, rows, maps):
    path = os.path.join(os.path.dirname(os.path.abspath(TRADE_CSV)), "alpha.csv")
    if not os.path.exists(path):
        ax.set_title("alpha.csv not found")
        return
    with open(path, newline="") as f:
        curve = list(csv.DictReader(f))
    chosen = {(r["model"], r["p"], r["q"]): r["alpha"] for r in rows if r["model"] in FITTED}
    for i, model in enumerate(FITTED):
        keys = sorted({(c["p"], c["q"]) for c in curve if c["model"] == model},
                      key=lambda k: (int(k[0]), int(k[1])))
        for j, (p, q) in enumerate(keys[:3]):
            pts = sorted((float(c["alpha"]), float(c["cv error"])) for c in curve
                         if c["model"] == model and c["p"] == p and c["q"] == q
                         and float(c["alpha"]) > 0)
            ax.plot([a for a, _ in pts], [100 * e for _, e in pts], "-", color=f"C{i}",
                    alpha=1.0 - 0.3 * j, label=f"{model}, p={p} q={q}")
            a = chosen.get((model, int(p), int(q)))
            if a:
                best = min(pts, key=lambda t: abs(t[0] - a), default=None)
                if best:
                    ax.plot([best[0]], [100 * best[1]], "o", color=f"C{i}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ridge alpha")
    ax.set_ylabel("cross-validation error |dy|²/|y|² (%)")
    ax.set_title("Alpha by cross-validation (dot: chosen)\npaper: frames left out; residual: clips")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def time_vs_bytes(ax, rows, maps):
    rows = [r for r in rows if r["map"] == maps[0] and r["model"] in FITTED]
    for i, model in enumerate(FITTED):
        for backend, style in (("shade_cpu_ms", "o--"), ("shade_simd_ms", "o-")):
            sweep = sorted((r for r in rows if r["model"] == model and r[backend] is not None),
                           key=lambda r: r["model_bytes"])
            ax.plot([r["model_bytes"] / 2**10 for r in sweep], [r[backend] for r in sweep],
                    style, color=f"C{i}", label=f"{model}, {backend.split('_')[1].upper()}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("model bytes (KiB)")
    ax.set_ylabel("ms per shade of every vertex, one thread")
    ax.set_title("Evaluation time (features → coefficients → radiance)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


PANELS = [error_vs_bytes_map, error_vs_bytes_directional, alpha_curve, time_vs_bytes]


def title(rows):
    return "prt-bake trade pose: held-out frames, model bytes and alpha"
