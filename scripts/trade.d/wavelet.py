# SPDX-License-Identifier: MIT
"""The figure of `prt-bake trade wavelet` for scripts/plot_trade.py: error vs transfer bytes per
vertex (both techniques, every map: the equal-bytes comparison), error vs light terms M, error vs
cube size N (and the dual paraboloid), and shading time per frame vs bytes per vertex. Errors are
the relative RMSE with the reference's noise removed."""
from plot_trade import in_sweep, line

COLUMNS = {"rel_rmse_noise_removed": float, "transfer_bytes_per_vertex": float,
           "shade_cpu_ms": float, "shade_simd_ms": float, "size": float, "keep": float,
           "sh_order": float}

COLOURS = ["tab:red", "tab:blue", "tab:green", "tab:purple"]


def error_vs_bytes(ax, rows, maps):
    for colour, m in zip(COLOURS, maps):
        def pick(predicate):
            return [(r["transfer_bytes_per_vertex"], 100 * r["rel_rmse_noise_removed"])
                    for r in rows if r["map"] == m and predicate(r)]
        line(ax, pick(lambda r: r["technique"] == "wavelet" and in_sweep(r, "K")
                      and r["quantizer"] == "band"),
             color=colour, marker="o", label=f"{m}: wavelet N=64, band")
        line(ax, pick(lambda r: r["technique"] == "wavelet" and in_sweep(r, "K")
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
        sel = [r for r in rows if r["map"] == m and in_sweep(r, "M")]
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
                  if r["map"] == m and in_sweep(r, "N")],
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
               and (technique == "sh" or (in_sweep(r, "K") and r["quantizer"] == "band"))
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


PANELS = [error_vs_bytes, error_vs_terms, error_vs_size, time_vs_bytes]


def title(rows):
    return f"prt-bake trade wavelet: {rows[0]['scene']}, {rows[0]['vertices']} vertices"
