// SPDX-License-Identifier: MIT
// The tables of prt-bake trade wavelet: trade.csv (one row per measurement and map) and trade.md
// (settings, machine, a table per sweep and map, and where each technique wins at equal bytes).
#include <algorithm>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "prt/io/envmap.hpp"

#include "wavelet_trade.hpp"

namespace prt::bake::wavelet_trade {
namespace {

using namespace trade;

const std::vector<std::string> kCsvColumns = {"scene",
                                              "technique",
                                              "map",
                                              "sweeps",
                                              "param",
                                              "size",
                                              "keep",
                                              "quantizer",
                                              "light_terms",
                                              "sh_order",
                                              "sh_rays",
                                              "samples",
                                              "vertices",
                                              "rel_rmse",
                                              "ref_noise",
                                              "rel_rmse_noise_removed",
                                              "ref_spp",
                                              "transfer_bytes_per_vertex",
                                              "pairs_per_vertex",
                                              "blob_bytes",
                                              "shade_cpu_ms",
                                              "shade_simd_ms",
                                              "light_update_ms",
                                              "bake_seconds",
                                              "rays_traced",
                                              "rays_per_second",
                                              "quant_shading_rel_rmse"};

// Cells that only one technique has are empty for the other.
std::vector<std::string> csv_cells(const Row& r, const Settings& o, const TradeInput& input,
                                   std::size_t vertices) {
  const bool wavelet = r.technique == "wavelet";
  auto only = [](bool has, const std::string& text) { return has ? text : std::string(); };
  return {stem(input.scene),
          r.technique,
          r.map,
          r.sweeps,
          r.param,
          only(wavelet, std::to_string(r.size)),
          only(wavelet, std::to_string(r.keep)),
          r.quantizer,
          only(wavelet, terms_text(r.terms)),
          only(!wavelet, std::to_string(r.order)),
          only(!wavelet, std::to_string(r.rays)),
          only(wavelet, std::to_string(o.samples)),
          std::to_string(vertices),
          format("%.6g", r.error),
          format("%.6g", r.ref_noise),
          format("%.6g", r.clean_error()),
          std::to_string(input.ref_spp),
          optional_number(r.bytes_per_vertex, "%.2f"),
          optional_number(r.pairs_per_vertex, "%.2f"),
          only(r.blob_bytes != 0, std::to_string(r.blob_bytes)),
          optional_number(r.cpu_ms, "%.3f"),
          optional_number(r.simd_ms, "%.3f"),
          optional_number(r.light_ms, "%.3f"),
          format("%.4g", r.bake_seconds),
          format("%.0f", r.rays_traced),
          format("%.4g", r.rays_per_second()),
          optional_number(r.quant_error, "%.4g")};
}

std::string pct(double fraction) {
  return format("%.2f", 100 * fraction);
}

const std::vector<Column> kSweepColumns = {{"technique", false},
                                           {"param", false},
                                           {"size"},
                                           {"K"},
                                           {"quantiser", false},
                                           {"M"},
                                           {"sh order"},
                                           {"error %"},
                                           {"error, noise removed %"},
                                           {"B/vertex"},
                                           {"pairs/vertex"},
                                           {"blob KiB"},
                                           {"CPU ms"},
                                           {"SIMD ms"},
                                           {"light ms"},
                                           {"bake s"},
                                           {"Mrays/s"},
                                           {"quant. %"}};

std::vector<std::string> sweep_cells(const Row& r) {
  const bool wavelet = r.technique == "wavelet";
  return {r.technique,
          r.param,
          wavelet ? std::to_string(r.size) : "",
          wavelet ? std::to_string(r.keep) : "",
          r.quantizer,
          wavelet ? terms_text(r.terms) : "",
          wavelet ? "" : std::to_string(r.order),
          pct(r.error),
          pct(r.clean_error()),
          optional_number(r.bytes_per_vertex, "%.0f"),
          optional_number(r.pairs_per_vertex, "%.0f"),
          r.blob_bytes ? format("%.0f", r.blob_bytes / 1024.0) : "",
          optional_number(r.cpu_ms, "%.2f"),
          optional_number(r.simd_ms, "%.2f"),
          optional_number(r.light_ms, "%.2f"),
          format("%.1f", r.bake_seconds),
          format("%.1f", 1e-6 * r.rays_per_second()),
          r.quant_error < 0 ? "" : format("%.3f", 100 * r.quant_error)};
}

bool in_sweep(const Row& r, const std::string& sweep) {
  std::string names = "+" + r.sweeps + "+";
  return names.find("+" + sweep + "+") != std::string::npos;
}

std::string describe(const Row* r) {
  if (!r) return "—";
  if (r->technique == "sh") return "order " + std::to_string(r->order) + ", " + r->quantizer;
  return r->param + " " + std::to_string(r->size) + ", K " + std::to_string(r->keep) + ", " +
         r->quantizer;
}

// Where each technique wins at equal bytes per vertex: for every budget (the bytes per vertex
// of a quantised row), the lowest noise-removed error of each technique within that budget.
void write_comparison(std::ofstream& md, const std::vector<Row>& rows, const std::string& map) {
  std::vector<const Row*> candidates;
  for (const Row& r : rows) {
    if (r.map == map && r.bytes_per_vertex > 0 && r.terms == kAllTerms) candidates.push_back(&r);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Row* a, const Row* b) { return a->bytes_per_vertex < b->bytes_per_vertex; });
  md << "\n### " << map << ": sh against wavelet at equal bytes per vertex\n\n";
  md << "For each budget (a measured row's transfer bytes per vertex), the lowest error "
        "(noise removed) each technique reaches within it.\n\n";
  write_markdown_header(md, {{"budget B/vertex"},
                             {"best sh", false},
                             {"error %"},
                             {"best wavelet", false},
                             {"error %"},
                             {"wins", false}});
  const Row *best_sh = nullptr, *best_wavelet = nullptr;
  std::string last_winner, summary;
  double range_start = 0.0;
  for (const Row* r : candidates) {
    const Row*& best = r->technique == "sh" ? best_sh : best_wavelet;
    if (!best || r->clean_error() < best->clean_error()) best = r;
    std::string winner = "sh";
    if (!best_sh || (best_wavelet && best_wavelet->clean_error() < best_sh->clean_error()))
      winner = "wavelet";
    write_markdown_row(md, {format("%.0f", r->bytes_per_vertex), describe(best_sh),
                            best_sh ? pct(best_sh->clean_error()) : "—", describe(best_wavelet),
                            best_wavelet ? pct(best_wavelet->clean_error()) : "—", winner});
    if (winner != last_winner) {
      if (!last_winner.empty())
        summary += last_winner + " from " + format("%.0f", range_start) + " B/vertex; ";
      last_winner = winner;
      range_start = r->bytes_per_vertex;
    }
  }
  if (!last_winner.empty())
    summary += last_winner + " from " + format("%.0f", range_start) + " B/vertex up.";
  md << "\nWinner by budget on " << map << ": " << summary << "\n";
  if (best_sh && best_wavelet) {
    md << "Best of each: sh " << describe(best_sh) << " at "
       << format("%.0f", best_sh->bytes_per_vertex) << " B/vertex, " << pct(best_sh->clean_error())
       << " %; wavelet " << describe(best_wavelet) << " at "
       << format("%.0f", best_wavelet->bytes_per_vertex) << " B/vertex, "
       << pct(best_wavelet->clean_error()) << " % (ratio "
       << format("%.2f", best_wavelet->clean_error() / best_sh->clean_error()) << ").\n";
  }
}

void write_settings(std::ofstream& md, const Settings& o, const TradeInput& input,
                    const Scene& scene) {
  md << scene_description(input.scene, scene) << "; albedo "
     << (input.albedo.empty() ? "from the materials" : input.albedo)
     << "; direct light with shadows (no bounces)."
     << (o.vertex_stride > 1 ? " Wavelet bakes and every error cover every " +
                                   std::to_string(o.vertex_stride) + "-th vertex only."
                             : std::string())
     << "\n\n";
  md << "Wavelet sweeps (" << o.samples << " ray(s) per texel, seed " << input.seed
     << "; the default quantiser is `" << o.quantizer << "`): **N** cube sizes " << joined(o.sizes)
     << " at K = 4 % of the coefficients; **K** " << joined(o.keeps) << " at N = " << o.base_size
     << ", float rows and both quantisers; **M** light terms";
  for (const std::string& m : o.light_terms) md << ' ' << m;
  md << " at N = " << o.base_size << ", K = " << base_keep(o) << "; **param** dual paraboloid P = "
     << (o.no_paraboloid ? std::string("none") : joined(o.paraboloid_sizes))
     << " against the cube at the same size and at half of it (about as many coefficients), "
        "each at K = 4 %. One bake per (param, size) at the largest K "
        "measured on it; smaller K are its rows truncated to the K largest |c|, exactly what a "
        "bake at that K keeps. **sh**: orders "
     << joined(o.sh_orders) << ", " << o.sh_rays << " rays, " << joined(o.sh_bits)
     << " bits, shadowed, one grey channel when the albedo is grey.\n\n";
  md << "Reference: " << input.ref_spp
     << " samples per vertex, direct light with visibility. Error = relative RMSE of per-vertex "
        "RGB radiance against it; error, noise removed = sqrt(error² − noise²) with the "
        "reference's own noise estimate. B/vertex = the raw WVLT or SHTR section bytes / "
        "vertices (the transfer a game holds; the blob adds the mesh). CPU / SIMD ms = median "
        "of "
     << input.frames
     << " shadings of every vertex on one thread; light ms = one light update (wavelet: resample, "
        "Haar transform, select M, prepare; sh: the runtime's SH projection). Quant. = what the "
        "quantisation adds: runtime shading against the float rows' under the same light.\n\n";
}

}  // namespace

void write_csv(const std::string& path, const std::vector<Row>& rows, const Settings& o,
               const TradeInput& input, std::size_t vertices) {
  std::ofstream csv(path);
  write_csv_row(csv, kCsvColumns);
  for (const Row& r : rows) write_csv_row(csv, csv_cells(r, o, input, vertices));
  check_written(csv, path);
}

void write_markdown(const std::string& path, const std::vector<Row>& rows,
                    const std::vector<TradeLight>& lights, const Settings& o,
                    const TradeInput& input, const Scene& scene, unsigned threads,
                    const std::vector<std::string>& notes) {
  std::ofstream md(path);
  md << "# Technique wavelet against sh: speed versus accuracy (prt-bake trade wavelet)\n\n";
  write_settings(md, o, input, scene);
  md << "Machine: " << machine_description(threads) << ".\n";
  md << "\nLight check (power of the runtime's wavelet light, sum of its texels P_j, against the "
        "SH "
        "projection's DC term, beyond 2 %): "
     << (notes.empty() ? "every light passed.\n" : "\n\n");
  for (const std::string& note : notes) md << "- " << note << "\n";
  const std::vector<std::pair<std::string, std::string>> sections = {{"N", "cube size N (K = 4 %)"},
                                                                     {"K", "kept coefficients K"},
                                                                     {"M", "light terms M"},
                                                                     {"param", "parameterisation"},
                                                                     {"sh", "sh orders"}};
  for (const TradeLight& light : lights) {
    const std::string& name = light.sh.name;
    md << "\n## " << name << " (" << io::env_mapping_name(light.sh.map->mapping()) << ", "
       << light.sh.map->width() << "x" << light.sh.map->height() << "; reference noise "
       << pct(light.reference.noise) << " %)\n";
    for (const auto& [sweep, title] : sections) {
      md << "\n### " << name << ": " << title << "\n\n";
      write_markdown_header(md, kSweepColumns);
      for (const Row& r : rows) {
        if (r.map == name && in_sweep(r, sweep)) write_markdown_row(md, sweep_cells(r));
      }
    }
    write_comparison(md, rows, name);
  }
  check_written(md, path);
}

}  // namespace prt::bake::wavelet_trade
