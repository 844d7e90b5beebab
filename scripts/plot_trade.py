#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots the speed/accuracy trade that `prt-bake trade sh` writes (trade.csv) as a 2x2 figure:
error vs SH order (one line per map, log y), error vs blob size, shading time per frame vs order
(CPU and SIMD backends) and bake time vs rays per vertex.

Usage: /usr/bin/python3 scripts/plot_trade.py TRADE.csv OUT.png
(the Debian matplotlib is only visible to /usr/bin/python3.)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter  # noqa: E402


def number(text):
    """A CSV cell as a float; None for "n/a"."""
    return None if text in ("", "n/a") else float(text)


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_trade: {path} has no rows")
    for row in rows:
        for key in ("order", "rays", "bounces", "blob_bytes"):
            row[key] = int(row[key])
        for key in ("rel_rmse", "ref_noise", "shade_cpu_ms", "shade_simd_ms", "bake_seconds",
                    "rays_per_second"):
            row[key] = number(row[key])
    return rows


def plain_numbers(axis, ticks):
    """Log axes labelled 0.5, 1, 2, 5 rather than 5x10^-1, at the given ticks."""
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


PERCENT_TICKS = [0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 20, 30, 50]


def in_sweep(row, name):
    return name in row["sweeps"].split("+")


def maps_of(rows):
    names = []
    for row in rows:
        if row["map"] not in names:
            names.append(row["map"])
    return names


def plot_error_vs_order(ax, rows, maps):
    for i, name in enumerate(maps):
        sweep = sorted((r for r in rows if r["map"] == name and in_sweep(r, "order")),
                       key=lambda r: r["order"])
        colour = f"C{i}"
        ax.plot([r["order"] for r in sweep], [100 * r["rel_rmse"] for r in sweep], "o-",
                color=colour, label=name)
        ax.plot([r["order"] for r in sweep], [100 * r["ref_noise"] for r in sweep], ":",
                color=colour, linewidth=1)
    ax.set_yscale("log")
    plain_numbers(ax.yaxis, PERCENT_TICKS)
    ax.set_xlabel("SH order n (n² coefficients)")
    ax.set_ylabel("relative RMSE vs reference (%)")
    ax.set_title("Error against the path-traced reference\n(dotted: the reference's own noise)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def plot_error_vs_bytes(ax, rows, maps):
    for i, name in enumerate(maps):
        sweep = sorted((r for r in rows if r["map"] == name and in_sweep(r, "order")),
                       key=lambda r: r["blob_bytes"])
        ax.plot([r["blob_bytes"] / 2**20 for r in sweep], [100 * r["rel_rmse"] for r in sweep],
                "o-", color=f"C{i}", label=name)
        for r in sweep:
            ax.annotate(str(r["order"]), (r["blob_bytes"] / 2**20, 100 * r["rel_rmse"]),
                        textcoords="offset points", xytext=(3, 3), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_numbers(ax.xaxis, [0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 15, 20])
    plain_numbers(ax.yaxis, PERCENT_TICKS)
    ax.set_xlabel("blob size (MiB, 16-bit transfer + mesh)")
    ax.set_ylabel("relative RMSE (%)")
    ax.set_title("Error against memory (labels: order)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def plot_shading_time(ax, rows, maps):
    sweep = sorted((r for r in rows if r["map"] == maps[0] and in_sweep(r, "order")),
                   key=lambda r: r["order"])
    vertices = int(sweep[0]["vertices"])
    for key, label, style in (("shade_cpu_ms", "CPU (scalar)", "o-"),
                              ("shade_simd_ms", "SIMD", "s-")):
        points = [(r["order"], r[key]) for r in sweep if r[key] is not None]
        if points:
            ax.plot(*zip(*points), style, label=label)
    ax.set_yscale("log")
    ax.set_xlabel("SH order n")
    ax.set_ylabel("ms per frame (median, one thread)")
    ax.set_title(f"Runtime shading of all {vertices} vertices")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def plot_bake_time(ax, rows, maps):
    sweep = sorted((r for r in rows if r["map"] == maps[0] and in_sweep(r, "rays")),
                   key=lambda r: r["rays"])
    ax.plot([r["rays"] for r in sweep], [r["bake_seconds"] for r in sweep], "o-", color="C3",
            label="bake seconds")
    for r in sweep:
        ax.annotate(f"{r['rays_per_second'] / 1e6:.1f} Mrays/s", (r["rays"], r["bake_seconds"]),
                    textcoords="offset points", xytext=(4, -10), fontsize=7)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel(f"rays per vertex (order {sweep[0]['order']}, shadowed)")
    ax.set_ylabel("bake seconds")
    ax.set_title("Bake time against rays")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, which="both", alpha=0.3)
    twin = ax.twinx()
    for i, name in enumerate(maps):
        errors = sorted((r for r in rows if r["map"] == name and in_sweep(r, "rays")),
                        key=lambda r: r["rays"])
        twin.plot([r["rays"] for r in errors], [100 * r["rel_rmse"] for r in errors], "x--",
                  color=f"C{i}", linewidth=1, label=f"error, {name}")
    twin.set_ylabel("relative RMSE (%, dashed)")
    twin.legend(fontsize=7, loc="upper center")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_trade.py TRADE.csv OUT.png")
    rows = read_rows(sys.argv[1])
    maps = maps_of(rows)
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    plot_error_vs_order(axes[0][0], rows, maps)
    plot_error_vs_bytes(axes[0][1], rows, maps)
    plot_shading_time(axes[1][0], rows, maps)
    plot_bake_time(axes[1][1], rows, maps)
    scene = rows[0]["scene"]
    fig.suptitle(f"Technique sh on {scene}: speed versus accuracy "
                 f"(reference {rows[0]['ref_spp']} spp, {rows[0]['bits']}-bit transfer)")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print(f"plot_trade: wrote {sys.argv[2]}")


if __name__ == "__main__":
    main()
