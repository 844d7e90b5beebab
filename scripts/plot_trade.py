#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots the speed/accuracy trade that `prt-bake trade TECHNIQUE` writes (trade.csv) as a 2x2
figure. What each panel shows is the technique's own, in scripts/trade.d/TECHNIQUE.py: its
COLUMNS (numeric columns to convert), PANELS (four functions of (ax, rows, maps)) and
title(rows); the reading, conversion and figure are shared here.

Usage: /usr/bin/python3 scripts/plot_trade.py TECHNIQUE TRADE.csv OUT.png
(the Debian matplotlib is only visible to /usr/bin/python3.)
"""
import csv
import importlib.util
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter  # noqa: E402

SWEEPS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "trade.d")
PERCENT_TICKS = [0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 20, 30, 50]


def number(text):
    """A CSV cell as a float; None when empty or "n/a"."""
    return None if text in ("", "n/a") else float(text)


def in_sweep(row, name):
    """Whether a row belongs to the sweep `name` (its sweeps column is "a+b+...")."""
    return name in row["sweeps"].split("+")


def maps_of(rows):
    """The maps in the order of their first row."""
    return list(dict.fromkeys(r["map"] for r in rows))


def line(ax, points, **style):
    """A line through the points with both coordinates known, in x order."""
    points = sorted(p for p in points if p[0] is not None and p[1] is not None)
    if points:
        ax.plot([p[0] for p in points], [p[1] for p in points], **style)


def plain_numbers(axis, ticks):
    """Log axes labelled 0.5, 1, 2, 5 rather than 5x10^-1, at the given ticks."""
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def load_technique(name):
    path = os.path.join(SWEEPS, f"{name}.py")
    if not os.path.exists(path):
        known = sorted(f[:-3] for f in os.listdir(SWEEPS) if f.endswith(".py"))
        sys.exit(f"plot_trade: no figure for technique '{name}' (known: {', '.join(known)})")
    spec = importlib.util.spec_from_file_location(f"trade_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def read_rows(path, technique):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_trade: {path} has no rows")
    for row in rows:
        for key, kind in technique.COLUMNS.items():
            value = number(row[key])
            row[key] = int(value) if kind is int and value is not None else value
    return rows


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    technique = load_technique(sys.argv[1])
    technique.TRADE_CSV = sys.argv[2]  # for figures that read other tables written beside it
    rows = read_rows(sys.argv[2], technique)
    maps = maps_of(rows)
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    for ax, panel in zip([axes[0][0], axes[0][1], axes[1][0], axes[1][1]], technique.PANELS):
        panel(ax, rows, maps)
    fig.suptitle(technique.title(rows))
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=110)
    print(f"plot_trade: wrote {sys.argv[3]}")


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    main()
