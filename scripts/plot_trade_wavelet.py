#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots the wavelet-against-sh trade that `prt-bake trade wavelet` writes (trade.csv) as a 2x2
figure: error vs transfer bytes per vertex (both techniques, both maps: the equal-bytes
comparison), error vs light terms M, error vs cube size N (and the dual paraboloid), and shading
time per frame vs bytes per vertex. Errors are the relative RMSE with the reference's noise
removed.

Usage: /usr/bin/python3 scripts/plot_trade_wavelet.py TRADE.csv OUT.png
(the Debian matplotlib is only visible to /usr/bin/python3.)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    """A CSV cell as a float; None when empty or "n/a"."""
    return None if text in ("", "n/a") else float(text)


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_trade_wavelet: {path} has no rows")
    for row in rows:
        for key in ("rel_rmse_noise_removed", "transfer_bytes_per_vertex", "shade_cpu_ms",
                    "shade_simd_ms", "size", "keep", "sh_order"):
            row[key] = number(row[key])
        row["sweeps"] = row["sweeps"].split("+")
    return rows


COLOURS = ["tab:red", "tab:blue", "tab:green", "tab:purple"]


def line(ax, points, **style):
    points = sorted(p for p in points if p[0] is not None and p[1] is not None)
    if points:
        ax.plot([p[0] for p in points], [p[1] for p in points], **style)


def error_vs_bytes(ax, rows, maps):
    for colour, m in zip(COLOURS, maps):
        def pick(predicate):
            return [(r["transfer_bytes_per_vertex"], 100 * r["rel_rmse_noise_removed"])
                    for r in rows if r["map"] == m and predicate(r)]
        line(ax, pick(lambda r: r["technique"] == "wavelet" and "K" in r["sweeps"]
                      and r["quantizer"] == "band"),
             color=colour, marker="o", label=f"{m}: wavelet N=64, band")
        line(ax, pick(lambda r: r["technique"] == "wavelet" and "K" in r["sweeps"]
                      and r["quantizer"] == "vertex"),
             color=colour, marker="x", linestyle=":", label=f"{m}: wavelet N=64, vertex")
        line(ax, pick(lambda r: r["technique"] == "sh" and r["quantizer"].startswith("16")),
             color=colour, marker="s", linestyle="--", label=f"{m}: sh 16-bit (orders)")
        line(ax, pick(lambda r: r["technique"] == "sh" and r["quantizer"].startswith("8")),
             color=colour, marker="^", linestyle="-.", label=f"{m}: sh 8-bit (orders)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("transfer bytes per vertex")
    ax.set_ylabel("relative RMSE, noise removed (%)")
    ax.set_title("Error vs bytes per vertex")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)


def error_vs_terms(ax, rows, maps):
    for colour, m in zip(COLOURS, maps):
        points, total = [], None
        sel = [r for r in rows if r["map"] == m and "M" in r["sweeps"]]
        for r in sel:
            if r["light_terms"] == "all":
                total = 100 * r["rel_rmse_noise_removed"]
            else:
                points.append((max(float(r["light_terms"]), 1.0),
                               100 * r["rel_rmse_noise_removed"]))
        line(ax, points, color=colour, marker="o", label=f"{m}")
        if total is not None:
            ax.axhline(total, color=colour, linestyle=":", label=f"{m}: M = all")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("light detail coefficients M (0 plotted at 1)")
    ax.set_ylabel("relative RMSE, noise removed (%)")
    ax.set_title("Error vs light terms (N = 64, K = 1000)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def error_vs_size(ax, rows, maps):
    for colour, m in zip(COLOURS, maps):
        line(ax, [(r["size"], 100 * r["rel_rmse_noise_removed"]) for r in rows
                  if r["map"] == m and "N" in r["sweeps"]],
             color=colour, marker="o", label=f"{m}: cube N")
        line(ax, [(r["size"], 100 * r["rel_rmse_noise_removed"]) for r in rows
                  if r["map"] == m and r["param"] == "dual-paraboloid"],
             color=colour, marker="D", linestyle="--", label=f"{m}: dual paraboloid P")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("face size (K = 4 % of the coefficients)")
    ax.set_ylabel("relative RMSE, noise removed (%)")
    ax.set_title("Error vs face size")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def time_vs_bytes(ax, rows, maps):
    first = maps[0]
    for technique, marker in (("wavelet", "o"), ("sh", "s")):
        sel = [r for r in rows if r["map"] == first and r["technique"] == technique
               and r["transfer_bytes_per_vertex"] is not None
               and (technique == "sh" or ("K" in r["sweeps"] and r["quantizer"] == "band"))
               and (technique == "wavelet" or r["quantizer"].startswith("16"))]
        line(ax, [(r["transfer_bytes_per_vertex"], r["shade_cpu_ms"]) for r in sel],
             marker=marker, label=f"{technique}: CPU")
        line(ax, [(r["transfer_bytes_per_vertex"], r["shade_simd_ms"]) for r in sel],
             marker=marker, linestyle="--", label=f"{technique}: SIMD")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("transfer bytes per vertex")
    ax.set_ylabel("ms per frame, whole mesh, one thread")
    ax.set_title(f"Shading time ({first})")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = read_rows(sys.argv[1])
    maps = list(dict.fromkeys(r["map"] for r in rows))
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    error_vs_bytes(axes[0][0], rows, maps)
    error_vs_terms(axes[0][1], rows, maps)
    error_vs_size(axes[1][0], rows, maps)
    time_vs_bytes(axes[1][1], rows, maps)
    scene = rows[0]["scene"]
    fig.suptitle(f"prt-bake trade wavelet: {scene}, {rows[0]['vertices']} vertices")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
