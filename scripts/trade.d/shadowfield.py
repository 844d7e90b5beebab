# SPDX-License-Identifier: MIT
"""The figure of `prt-bake trade shadowfield` on a scene preset for scripts/plot_trade.py: error
against baked bytes and against CPU time per frame for every setting (one colour per swept knob,
the defaults circled), error against each knob's value, and error and frame time against the
bounce count. A setting's error is the RMS of its placements' errors."""
import math

from plot_trade import in_sweep, plain_numbers

COLUMNS = {"order": int, "terms": int, "rays": int, "oof_shells": int, "oof_face": int,
           "srf_shells": int, "srf_face": int, "basis": int, "bits": int, "bounces": int,
           "time_s": float, "rel_rmse": float, "bias": float, "ref_noise": float,
           "simd_cpu_ms": float, "scalar_cpu_ms": float, "runtime_bytes": int,
           "blob_bytes": int, "bake_seconds": float}

KNOBS = ["order", "terms", "rays", "oof_shells", "oof_face", "srf_shells", "srf_face", "basis",
         "bits", "bounces"]
LABELS = {"order": "SH order", "terms": "BRDF terms K", "rays": "rays", "oof_shells": "OOF shells",
          "oof_face": "OOF face (6 F² points)", "srf_shells": "SRF shells",
          "srf_face": "SRF face (6 F² points)", "basis": "basis size N", "bits": "bits",
          "bounces": "bounces"}


def settings(rows):
    """One entry per setting and map: its knobs, sweeps and the placements' figures combined."""
    grouped = {}
    for r in rows:
        key = (r["map"],) + tuple(r[k] for k in KNOBS)
        grouped.setdefault(key, []).append(r)
    out = []
    for group in grouped.values():
        first = dict(group[0])
        first["rel_rmse"] = math.sqrt(sum(r["rel_rmse"] ** 2 for r in group) / len(group))
        first["ref_noise"] = max(r["ref_noise"] for r in group)
        for column in ("simd_cpu_ms", "scalar_cpu_ms"):
            known = [r[column] for r in group if r[column] is not None]
            first[column] = sum(known) / len(known) if known else None
        out.append(first)
    return out


def swept_knobs(rows):
    return [k for k in KNOBS if any(in_sweep(r, k) for r in rows)]


def _style(knob):
    i = KNOBS.index(knob)
    return {"color": f"C{i}", "marker": "osD^v<>ph*"[i]}


def _base(rows):
    """The setting in the most sweeps: the defaults."""
    return max(rows, key=lambda r: len(r["sweeps"].split("+")))


def _scatter_by_sweep(ax, rows, x_of, xlabel, title):
    rows = settings(rows)
    for knob in swept_knobs(rows):
        points = [r for r in rows if in_sweep(r, knob) and x_of(r) is not None]
        ax.scatter([x_of(r) for r in points], [100 * r["rel_rmse"] for r in points],
                   label=LABELS[knob], **_style(knob))
    base = _base(rows)
    if x_of(base) is not None:
        ax.scatter([x_of(base)], [100 * base["rel_rmse"]], s=220, facecolors="none",
                   edgecolors="black", label="defaults")
    ax.set_xscale("log")
    plain_numbers(ax.xaxis, [1, 2, 3, 5, 10, 20, 30, 50, 100, 200, 300, 500])
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative RMSE vs reference (%)")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def error_vs_bytes(ax, rows, maps):
    _scatter_by_sweep(ax, rows, lambda r: r["blob_bytes"] / 1e6, "baked bytes, all objects (MB)",
                      "Error against baked bytes")


def error_vs_time(ax, rows, maps):
    _scatter_by_sweep(ax, rows, lambda r: r["simd_cpu_ms"], "SIMD CPU time per frame (ms)",
                      "Error against frame time (one thread)")


def error_vs_knob(ax, rows, maps):
    rows = settings(rows)
    for knob in swept_knobs(rows):
        if knob in ("bits", "bounces"):
            continue
        sweep = sorted((r for r in rows if in_sweep(r, knob)), key=lambda r: r[knob])
        ax.plot([r[knob] for r in sweep], [100 * r["rel_rmse"] for r in sweep],
                label=LABELS[knob], **_style(knob))
    noise = max(r["ref_noise"] for r in rows)
    ax.axhline(100 * noise, linestyle=":", color="grey", label="reference noise")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("the knob's value (the others at the defaults)")
    ax.set_ylabel("relative RMSE vs reference (%)")
    ax.set_title("Error against each knob")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def bounces(ax, rows, maps):
    rows = sorted((r for r in settings(rows) if in_sweep(r, "bounces")), key=lambda r: r["bounces"])
    x = [r["bounces"] for r in rows]
    ax.plot(x, [100 * r["rel_rmse"] for r in rows], "o-", color="C0", label="error")
    ax.set_xlabel("bounces (the reference with as many)")
    ax.set_ylabel("relative RMSE vs reference (%)", color="C0")
    ax.set_xticks(x)
    times = ax.twinx()
    for column, style, label in (("simd_cpu_ms", "s--", "SIMD"), ("scalar_cpu_ms", "^:", "scalar")):
        times.plot(x, [r[column] for r in rows], style, color="C1", label=f"{label} CPU ms")
    times.set_ylabel("CPU time per frame (ms)", color="C1")
    times.set_ylim(bottom=0)
    ax.set_title("Bounces: error and frame time")
    ax.grid(True, alpha=0.3)
    handles = ax.get_legend_handles_labels()
    more = times.get_legend_handles_labels()
    ax.legend(handles[0] + more[0], handles[1] + more[1], fontsize=7)


PANELS = [error_vs_bytes, error_vs_time, error_vs_knob, bounces]


def title(rows):
    scene = rows[0]["scene"]
    maps = ", ".join(dict.fromkeys(r["map"] for r in rows))
    return f"prt-bake trade shadowfield: the {scene} preset under {maps} against the path tracer"
