# SPDX-License-Identifier: MIT
"""The figure of `prt-bake trade sh` for scripts/plot_trade.py: error vs SH order (one line per
map, log y; dashed: the light de-ringed at the largest --dering strength, when the table has
one), error vs blob size, shading time per frame vs order (CPU and SIMD backends) and bake time vs
rays per vertex. Every other panel shows the light as projected (dering 0); tables written before
the dering column count as dering 0."""
from plot_trade import PERCENT_TICKS, in_sweep, plain_numbers

COLUMNS = {"order": int, "rays": int, "bounces": int, "blob_bytes": int, "rel_rmse": float,
           "ref_noise": float, "shade_cpu_ms": float, "shade_simd_ms": float,
           "bake_seconds": float, "rays_per_second": float}


def dering(row):
    """The row's de-ringing strength (0 for tables without the column)."""
    return float(row.get("dering") or 0)


def as_projected(rows):
    """The rows shaded with the light as projected, not de-ringed."""
    return [r for r in rows if dering(r) == 0]


def plot_error_vs_order(ax, all_rows, maps):
    rows = as_projected(all_rows)
    strongest = max(dering(r) for r in all_rows)
    for i, name in enumerate(maps):
        sweep = sorted((r for r in rows if r["map"] == name and in_sweep(r, "order")),
                       key=lambda r: r["order"])
        colour = f"C{i}"
        ax.plot([r["order"] for r in sweep], [100 * r["rel_rmse"] for r in sweep], "o-",
                color=colour, label=name)
        ax.plot([r["order"] for r in sweep], [100 * r["ref_noise"] for r in sweep], ":",
                color=colour, linewidth=1)
        if strongest > 0:
            windowed = sorted((r for r in all_rows if r["map"] == name and in_sweep(r, "order")
                               and dering(r) == strongest), key=lambda r: r["order"])
            ax.plot([r["order"] for r in windowed], [100 * r["rel_rmse"] for r in windowed],
                    "x--", color=colour, linewidth=1, label=f"{name}, dering {strongest:g}")
    ax.set_yscale("log")
    plain_numbers(ax.yaxis, PERCENT_TICKS)
    ax.set_xlabel("SH order n (n² coefficients)")
    ax.set_ylabel("relative RMSE vs reference (%)")
    ax.set_title("Error against the path-traced reference\n(dotted: the reference's own noise)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def plot_error_vs_bytes(ax, all_rows, maps):
    rows = as_projected(all_rows)
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


def plot_shading_time(ax, all_rows, maps):
    rows = as_projected(all_rows)
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


def plot_bake_time(ax, all_rows, maps):
    rows = as_projected(all_rows)
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


PANELS = [plot_error_vs_order, plot_error_vs_bytes, plot_shading_time, plot_bake_time]


def title(rows):
    return (f"Technique sh on {rows[0]['scene']}: speed versus accuracy "
            f"(reference {rows[0]['ref_spp']} spp, {rows[0]['bits']}-bit transfer)")
