# SPDX-License-Identifier: MIT
"""The figure of `prt-bake trade cloth` for scripts/plot_trade.py: error against the brute-force
reference against the light's lobes K (with the light's own error, the reference under the fitted
light, dotted); error and rank truncation cost against table bytes (energy, bits and grids); error
against the theta panels and phi nodes of the integrals; and each fabric's and map's defaults
beside the paper's single table, each of the paper's printed rules and all of them, the runtime's
per-frame light fit and the reference's own discretisation error."""
from plot_trade import in_sweep, line

COLUMNS = {"lobes": int, "energy": float, "bits": int, "max_rank": int, "table_mb": float,
           "panels": int, "phi_nodes": int, "nrmse": float, "bias": float,
           "truncation_cost": float, "cpu_us": float, "simd_us": float}


def _cases(rows):
    return list(dict.fromkeys((r["fabric"], r["map"]) for r in rows))


def _of(rows, fabric, map_name, sweep):
    return [r for r in rows if r["fabric"] == fabric and r["map"] == map_name
            and in_sweep(r, sweep)]


def _style(i):
    return {"color": f"C{i}", "marker": "osd^v<>"[i % 7]}


def error_vs_lobes(ax, rows, maps):
    for i, (fabric, m) in enumerate(_cases(rows)):
        line(ax, [(r["lobes"], 100 * r["nrmse"]) for r in _of(rows, fabric, m, "lobes")],
             label=f"{fabric}, {m}", **_style(i))
        for r in _of(rows, fabric, m, "reference_sg"):
            ax.plot([r["lobes"]], [100 * r["nrmse"]], linestyle="none", markerfacecolor="none",
                    **_style(i))
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("SG lobes K of the light (hollow: the reference under the K light)")
    ax.set_ylabel("NRMSE against the reference (%)")
    ax.set_title("Error against the light's lobes")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def error_vs_bytes(ax, rows, maps):
    for i, (fabric, m) in enumerate(_cases(rows)):
        points = [r for r in rows if r["fabric"] == fabric and r["map"] == m
                  and r["table_mb"] is not None and (in_sweep(r, "energy") or in_sweep(r, "bits")
                                                     or in_sweep(r, "grid"))]
        ax.scatter([r["table_mb"] for r in points], [100 * r["nrmse"] for r in points],
                   label=f"{fabric}, {m}: NRMSE", **_style(i))
        costs = [r for r in points if r["truncation_cost"] is not None]
        ax.scatter([r["table_mb"] for r in costs], [100 * r["truncation_cost"] for r in costs],
                   facecolors="none", edgecolors=f"C{i}", marker="s",
                   label=f"{fabric}, {m}: truncation cost")
    ax.axvline(4.0, linestyle="--", color="grey", label="4 MB")
    ax.axhline(2.0, linestyle=":", color="grey", label="2 % truncation cost")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("stored tables per fabric (MB)")
    ax.set_ylabel("%")
    ax.set_title("Error and rank truncation cost against table bytes")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)


def error_vs_quadrature(ax, rows, maps):
    for i, (fabric, m) in enumerate(_cases(rows)):
        line(ax, [(r["panels"], 100 * r["nrmse"]) for r in _of(rows, fabric, m, "panels")],
             label=f"{fabric}, {m}: theta panels", linestyle="-", **_style(i))
        line(ax, [(r["phi_nodes"], 100 * r["nrmse"]) for r in _of(rows, fabric, m, "phi_nodes")],
             label=f"{fabric}, {m}: phi nodes", linestyle="--", **_style(i))
    ax.set_yscale("log")
    ax.set_xlabel("theta panels per window (solid) / phi nodes (dashed)")
    ax.set_ylabel("NRMSE against the reference (%)")
    ax.set_title("Error against the integrals' quadrature")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)


# The `paper` sweep's rows by setting: (setting, label).
PAPER_ROWS = [("paper: T over the full sphere", "paper: T / sphere"),
              ("paper: phi over the fibre's front", "paper: phi front"),
              ("paper: 6 straight theta segments", "paper: 6 segments"),
              ("paper: Schlick's Fresnel (Eq. 13 corrected)", "paper: Schlick"),
              ("paper: Schlick with cos phi_d as printed", "paper: Schlick, cos phi_d"),
              ("paper: Schlick's sum cut at the cube as printed", "paper: Schlick, cube"),
              ("paper: Eq. 13's Fresnel as printed", "paper: Eq. 13"),
              ("paper: g_u as printed", "paper: g_u"),
              ("the paper as printed", "paper as printed")]


def variants(ax, rows, maps):
    kinds = [("defaults", None, "defaults"), ("no_cone", None, "T alone (paper)")]
    kinds += [("paper", setting, label) for setting, label in PAPER_ROWS]
    kinds += [("fast_light", None, "per-frame light fit"), ("no_culling", None, "no lobe culling"),
              ("reference_merged", None, "reference, texels 2x2")]
    cases = _cases(rows)
    width = 0.8 / max(1, len(cases))
    for i, (fabric, m) in enumerate(cases):
        values = []
        for kind, setting, _ in kinds:
            found = [r for r in _of(rows, fabric, m, kind)
                     if setting is None or r["setting"] == setting]
            values.append(100 * found[0]["nrmse"] if found else 0.0)
        ax.bar([k + i * width for k in range(len(kinds))], values, width,
               label=f"{fabric}, {m}", color=f"C{i}")
    ax.set_xticks([k + 0.4 - width / 2 for k in range(len(kinds))])
    ax.set_xticklabels([label for _, _, label in kinds], fontsize=7, rotation=30, ha="right")
    ax.set_yscale("log")  # the paper's Fresnel expansion is off by several times the signal
    ax.set_ylabel("NRMSE against the reference (%)")
    ax.set_title("The defaults beside the paper's rules, the fast fit, no culling")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=6)


PANELS = [error_vs_lobes, error_vs_bytes, error_vs_quadrature, variants]


def title(rows):
    fabrics = ", ".join(dict.fromkeys(r["fabric"] for r in rows))
    return f"prt-bake trade cloth: {fabrics} against the brute-force reference"
