// SPDX-License-Identifier: MIT
// `prt-bake trade cloth`: the method against the brute-force reference (prt_cloth_reference over
// every texel of the map) on the scene's surface frames, each seen from 32 views, under each map
// turned about +Y. One knob at a time moves from the defaults: the light's lobes K (and the
// runtime's per-frame fit), the rank (energy left out), the stored bits, the table grids, the
// theta panels and phi nodes of the integrals, the cone table and the lobe culling; and paper
// 003's printed rules, each alone and all together (the `paper` sweep). The
// reference's own error is stated from the same reference over texels merged 2 x 2, and the light's
// alone from the reference under the fitted SG light. docs/cloth/trade.md reads the table.
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "../common/trade_common.hpp"
#include "cloth_technique.hpp"
#include "cloth_trade_measure.hpp"
#include "prt/baker/cloth/cloth_light.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/text.hpp"

namespace prt::bake {
namespace {

using namespace cloth_trade;

struct ClothTradeSettings {
  std::vector<std::string> fabrics{"linen_plain", "polyester_satin_charmeuse"};
  // Each list's first value is the defaults' row; the others are swept one at a time.
  std::vector<std::uint32_t> lobes{10, 4, 16, 32, 64};
  std::vector<std::string> energies{"1e-4", "1e-3", "1e-5"};
  std::vector<std::uint32_t> xi_sizes{32, 16};
  std::vector<std::uint32_t> levels{10, 6};
  std::vector<std::uint32_t> view_nodes{16, 8};
  std::vector<std::uint32_t> panels{2, 1, 4, 8};
  std::vector<std::uint32_t> phi_nodes{3, 1, 2, 5};
  std::uint32_t turns = 4;
  std::uint32_t surface_frames = 1;
};

// One table configuration: the grid, the bits, the rank by energy.
struct TableConfig {
  std::uint32_t xi = 0, levels = 0, views = 0;
  int bits = 16;
  double energy = 0.0;       // 0: every computed rank (up to 64)
  bool full_sphere = false;  // T over the lobe's integral over the sphere (paper 003)
};

struct ClothTradeRow {
  std::string fabric, map, setting;
  std::string knob;  // what moved from the defaults (the CSV's sweep column)
  std::uint32_t lobes = 0, panels = 0, phi_nodes = 0;
  TableConfig table;
  std::uint32_t max_rank = 0;
  std::uint64_t table_bytes = 0;
  double nrmse = -1.0, bias = 0.0, truncation_cost = -1.0;
  double cpu_us = -1.0, simd_us = -1.0;
};

struct MapTurns {
  std::string name;
  std::vector<io::EnvMap> turned;  // one per turn
  // Per turn: the static fit of each K of the sweep (same order), the runtime's fit at K0.
  std::vector<std::vector<std::vector<prt_cloth_lobe>>> fitted;
  std::vector<std::vector<prt_cloth_lobe>> fast;
  std::vector<SgLightFit> reports;  // turn 0's static fits, per K
};

// A bake at the largest rank, truncated per energy as the rows need.
struct BakedTables {
  TableConfig config;
  ClothSection section;
  std::vector<std::vector<double>> full_sv, cone_sv;

  std::vector<std::uint8_t> blob(double energy, int bits, std::uint32_t* max_rank,
                                 std::uint64_t* bytes) const {
    const ClothSection s =
        energy > 0.0 ? truncated_section(section, full_sv, cone_sv, energy) : section;
    *max_rank = 0;
    *bytes = 0;
    for (const ClothTable& t : s.tables) {
      *max_rank = std::max({*max_rank, t.full.rank, t.cone.rank});
      *bytes += cloth_factor_bytes(s.grid, t.full.rank, bits) +
                cloth_factor_bytes(s.grid, t.cone.rank, bits);
    }
    return write_cloth_blob(s, bits, nullptr, "prtkit cloth trade");
  }
};

double parse_energy(const std::string& text) {
  char* end = nullptr;
  const double e = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(e > 0.0 && e < 1.0))
    throw Error("trade cloth: --energy: '" + text + "' is not a number in (0, 1)");
  return e;
}

class ClothTrade final : public TechniqueTrade {
 public:
  TradeInput defaults() const override {
    TradeInput input;
    input.frames = 5;
    return input;
  }

  OptionList options() override {
    OptionList list;
    list.add("--fabric", &o_.fabrics, "Fabrics measured (presets)").choices(cloth_fabric_names());
    list.add("--lobes", &o_.lobes, "SG lobes K of the light; the first is the default");
    list.add("--energy", &o_.energies,
             "Share of each table's squared norm the rank leaves out; the first is the default");
    list.add("--xi-size", &o_.xi_sizes, "Lobe-direction grid sizes; the first is the default");
    list.add("--levels", &o_.levels, "Lobe-sharpness levels; the first is the default");
    list.add("--view-nodes", &o_.view_nodes,
             "View nodes over elevation and azimuth; the first is the default");
    list.add("--panels", &o_.panels, "Theta panels per window; the first is the default");
    list.add("--phi-nodes", &o_.phi_nodes, "Nodes of each phi integral; the first is the default");
    list.add("--turns", &o_.turns, "Turns of each map about +Y the samples are seen under")
        .range(1, 64);
    list.add("--surface-frames", &o_.surface_frames,
             "Distinct surface frames of the scene measured (each from 32 views)")
        .range(1, 4096);
    return list;
  }

  void check(const TradeInput& input) const override {
    if (input.envs.empty()) throw Error("trade cloth: --env needs at least one map");
    auto nonempty = [](bool empty, const char* flag) {
      if (empty) throw Error(std::string("trade cloth: ") + flag + " needs at least one value");
    };
    nonempty(o_.fabrics.empty(), "--fabric");
    nonempty(o_.lobes.empty(), "--lobes");
    nonempty(o_.energies.empty(), "--energy");
    nonempty(o_.xi_sizes.empty(), "--xi-size");
    nonempty(o_.levels.empty(), "--levels");
    nonempty(o_.view_nodes.empty(), "--view-nodes");
    nonempty(o_.panels.empty(), "--panels");
    nonempty(o_.phi_nodes.empty(), "--phi-nodes");
    for (const std::string& e : o_.energies) parse_energy(e);
    for (std::uint32_t k : o_.lobes)
      if (k < 1 || k > PRT_CLOTH_MAX_LOBES) throw Error("trade cloth: --lobes out of range");
    for (std::uint32_t p : o_.panels)
      if (p < 1 || p > 16) throw Error("trade cloth: --panels: 1..16");
    for (std::uint32_t n : o_.phi_nodes)
      if (n < 1 || n > 8) throw Error("trade cloth: --phi-nodes: 1..8");
  }

  void prepare(const Scene&, const TradeInput& input, const Context& ctx) override {
    for (const std::string& path : input.envs) {
      MapTurns m;
      m.name = trade::stem(path);
      const io::EnvMap map = io::load_envmap(path, io::EnvMapping::Auto, ctx.io_messages());
      for (std::uint32_t t = 0; t < o_.turns; ++t) {
        m.turned.push_back(map);
        if (t > 0) m.turned.back().set_rotation(io::rotation_about_y(360.0 * t / o_.turns));
        fit_lights(m, ctx);
      }
      maps_.push_back(std::move(m));
    }
  }

  void sweep(const Scene& scene, const EmbreeScene&, const TradeInput& input,
             const Context& ctx) override {
    samples_ = make_samples(surface_frames(scene, o_.surface_frames));
    for (const std::string& name : o_.fabrics) {
      const ClothPreset& fabric = cloth_fabric(name);
      const std::vector<BakedTables> tables = bake_tables(fabric, ctx);
      for (const MapTurns& map : maps_) measure_fabric(fabric, tables, map, input, ctx);
    }
    write_tables(scene, input);
  }

 private:
  void fit_lights(MapTurns& m, const Context& ctx) const {
    std::vector<std::vector<prt_cloth_lobe>> fits;
    for (std::uint32_t k : o_.lobes) {
      SgLightOptions options;
      options.lobe_count = k;
      SgLightFit fit = fit_sg_light(m.turned.back(), options, ctx);
      fits.push_back(fit.lobes);
      if (m.turned.size() == 1) m.reports.push_back(std::move(fit));
    }
    m.fitted.push_back(std::move(fits));
    SgLightOptions fast;
    fast.lobe_count = o_.lobes.front();
    m.fast.push_back(fast_sg_light(m.turned.back(), fast));
  }

  TableConfig default_config() const {
    return {o_.xi_sizes.front(), o_.levels.front(), o_.view_nodes.front(), 16,
            parse_energy(o_.energies.front())};
  }

  // The default grid and each grid variant, baked once at the largest rank.
  std::vector<BakedTables> bake_tables(const ClothPreset& fabric, const Context& ctx) const {
    std::vector<TableConfig> configs = {default_config()};
    auto variant = [&](auto set) {
      TableConfig c = default_config();
      set(c);
      configs.push_back(c);
    };
    for (std::size_t i = 1; i < o_.xi_sizes.size(); ++i)
      variant([&](TableConfig& c) { c.xi = o_.xi_sizes[i]; });
    for (std::size_t i = 1; i < o_.levels.size(); ++i)
      variant([&](TableConfig& c) { c.levels = o_.levels[i]; });
    for (std::size_t i = 1; i < o_.view_nodes.size(); ++i)
      variant([&](TableConfig& c) { c.views = o_.view_nodes[i]; });
    variant([&](TableConfig& c) { c.full_sphere = true; });
    std::vector<BakedTables> baked;
    for (const TableConfig& c : configs) {
      ClothTablesOptions options;
      options.grid.xi_size = c.xi;
      options.grid.lambda_levels = c.levels;
      options.grid.view_theta = options.grid.view_phi = c.views;
      options.sampling.full_sphere_denominator = c.full_sphere;
      options.factor.fixed_rank = 64;  // the format's largest rank
      ctx.info(format("cloth trade: baking %s's tables on grid xi %u, %u levels, %u x %u views%s",
                      fabric.name.c_str(), c.xi, c.levels, c.views, c.views,
                      c.full_sphere ? ", T over the full sphere" : ""));
      ClothTablesBake bake =
          bake_cloth_tables({{fabric.name, fabric.params, fabric.weave}}, options, ctx);
      BakedTables b{c, std::move(bake.section), {}, {}};
      for (const ClothTableReport& r : bake.tables) {
        b.full_sv.push_back(r.full.singular_values);
        b.cone_sv.push_back(r.cone.singular_values);
      }
      baked.push_back(std::move(b));
    }
    return baked;
  }

  // The reference of every turn, one after the other.
  std::vector<float> turned_reference(const ClothPreset& fabric, const MapTurns& map, int block,
                                      const TradeInput& input, const Context& ctx) const {
    std::vector<float> all;
    for (const io::EnvMap& turned : map.turned) {
      const std::vector<float> r =
          cached_reference(fabric, samples_, turned, map.name, block, input.cache_dir, ctx);
      all.insert(all.end(), r.begin(), r.end());
    }
    return all;
  }

  // The method's shading of every turn under `light_of(turn)`.
  template <typename LightOf>
  Shading turned_shading(const std::vector<std::uint8_t>& blob, const MapTurns& map,
                         LightOf light_of, const prt_cloth_settings& settings, bool timed,
                         const Context& ctx) const {
    Shading all;
    for (std::size_t t = 0; t < map.turned.size(); ++t) {
      const Shading s =
          shade(blob, PRT_BACKEND_CPU, samples_, light_of(t), settings, timed ? frames_ : 1, ctx);
      all.rgb.insert(all.rgb.end(), s.rgb.begin(), s.rgb.end());
      if (t == 0) all.microseconds_per_sample = s.microseconds_per_sample;
    }
    return all;
  }

  void measure_fabric(const ClothPreset& fabric, const std::vector<BakedTables>& tables,
                      const MapTurns& map, const TradeInput& input, const Context& ctx) {
    frames_ = input.frames;
    const std::vector<float> reference = turned_reference(fabric, map, 1, input, ctx);
    ClothTradeRow base;
    base.fabric = fabric.name;
    base.map = map.name;
    base.lobes = o_.lobes.front();
    base.panels = o_.panels.front();
    base.phi_nodes = o_.phi_nodes.front();
    base.table = default_config();
    const auto static_light = [&](std::size_t k) {
      return [&map, k](std::size_t t) -> const std::vector<prt_cloth_lobe>& {
        return map.fitted[t][k];
      };
    };
    auto run = [&](ClothTradeRow row, const BakedTables& baked, auto light_of, std::uint32_t flags,
                   bool timed) {
      const std::vector<std::uint8_t> blob =
          baked.blob(row.table.energy, row.table.bits, &row.max_rank, &row.table_bytes);
      prt_cloth_settings settings = prt::sized<prt_cloth_settings>();
      settings.flags = flags;
      settings.theta_segments = row.panels;
      settings.phi_nodes = row.phi_nodes;
      const Shading s = turned_shading(blob, map, light_of, settings, timed, ctx);
      row.nrmse = nrmse(s.rgb, reference);
      row.bias = bias(s.rgb, reference);
      if (timed) {
        row.cpu_us = s.microseconds_per_sample;
        row.simd_us = shade(blob, PRT_BACKEND_SIMD, samples_, light_of(0), settings, frames_, ctx)
                          .microseconds_per_sample;
      }
      rows_.push_back(row);
      return s.rgb;
    };

    ClothTradeRow def = base;
    def.setting = "defaults";
    def.knob = "defaults+lobes+energy+bits+grid+panels+phi_nodes";
    const std::vector<float> shaded = run(def, tables[0], static_light(0), 0u, true);
    ClothTradeRow full = base;
    full.setting = "every rank (up to 64)";
    full.knob = "energy";
    full.table.energy = 0.0;
    const std::vector<float> full_rank = run(full, tables[0], static_light(0), 0u, false);
    rows_[rows_.size() - 2].truncation_cost = nrmse(shaded, full_rank);

    for (std::size_t i = 1; i < o_.energies.size(); ++i) {
      ClothTradeRow r = base;
      r.table.energy = parse_energy(o_.energies[i]);
      r.setting = "energy " + o_.energies[i];
      r.knob = "energy";
      const std::vector<float> s = run(r, tables[0], static_light(0), 0u, false);
      rows_.back().truncation_cost = nrmse(s, full_rank);
    }
    ClothTradeRow eight = base;
    eight.table.bits = 8;
    eight.setting = "8-bit tables";
    eight.knob = "bits";
    run(eight, tables[0], static_light(0), 0u, false);
    for (std::size_t g = 1; g < tables.size(); ++g) {
      if (tables[g].config.full_sphere) continue;  // the paper's rows
      ClothTradeRow r = base;
      r.table = tables[g].config;
      r.setting =
          format("grid xi %u, %u levels, %u views", r.table.xi, r.table.levels, r.table.views);
      r.knob = "grid";
      run(r, tables[g], static_light(0), 0u, false);
    }
    for (std::size_t k = 1; k < o_.lobes.size(); ++k) {
      ClothTradeRow r = base;
      r.lobes = o_.lobes[k];
      r.setting = format("K %u", r.lobes);
      r.knob = "lobes";
      run(r, tables[0], static_light(k), 0u, false);
    }
    ClothTradeRow fast = base;
    fast.setting = "runtime's per-frame light fit";
    fast.knob = "fast_light";
    run(
        fast, tables[0],
        [&map](std::size_t t) -> const std::vector<prt_cloth_lobe>& { return map.fast[t]; }, 0u,
        false);
    for (std::size_t i = 1; i < o_.panels.size(); ++i) {
      ClothTradeRow r = base;
      r.panels = o_.panels[i];
      r.setting = format("%u theta panels", r.panels);
      r.knob = "panels";
      run(r, tables[0], static_light(0), 0u, false);
    }
    for (std::size_t i = 1; i < o_.phi_nodes.size(); ++i) {
      ClothTradeRow r = base;
      r.phi_nodes = o_.phi_nodes[i];
      r.setting = format("%u phi nodes", r.phi_nodes);
      r.knob = "phi_nodes";
      run(r, tables[0], static_light(0), 0u, false);
    }
    ClothTradeRow no_cone = base;
    no_cone.setting = "no cone table (T alone, as the paper)";
    no_cone.knob = "no_cone";
    run(no_cone, tables[0], static_light(0), PRT_CLOTH_NO_CONE_TABLE, false);
    ClothTradeRow keep = base;
    keep.setting = "no lobe culling";
    keep.knob = "no_culling";
    run(keep, tables[0], static_light(0), PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES,
        false);
    paper_rows(base, tables, run, static_light(0));
    reference_rows(fabric, map, reference, input, ctx);
  }

  // Paper 003's printed rules (docs/cloth/method.md, "What the paper gets wrong"), each alone at
  // the defaults, then all of them with its factorisation (T alone): the paper as printed.
  template <typename Run, typename LightOf>
  void paper_rows(const ClothTradeRow& base, const std::vector<BakedTables>& tables, Run& run,
                  LightOf light) {
    const BakedTables& sphere = *std::find_if(tables.begin(), tables.end(),
                                              [](const auto& t) { return t.config.full_sphere; });
    const struct {
      const char* setting;
      bool full_sphere;
      std::uint32_t flags;
    } cases[] = {
        {"paper: T over the full sphere", true, 0u},
        {"paper: phi over the fibre's front", false, PRT_CLOTH_PAPER_PHI_DOMAIN},
        {"paper: 6 straight theta segments", false, PRT_CLOTH_PAPER_THETA_SEGMENTS},
        {"paper: Schlick's Fresnel (Eq. 13 corrected)", false, PRT_CLOTH_PAPER_SCHLICK},
        {"paper: Schlick with cos phi_d as printed", false,
         PRT_CLOTH_PAPER_SCHLICK | PRT_CLOTH_PAPER_SCHLICK_ANGLE},
        {"paper: Schlick's sum cut at the cube as printed", false,
         PRT_CLOTH_PAPER_SCHLICK | PRT_CLOTH_PAPER_SCHLICK_CUBE},
        {"paper: Eq. 13's Fresnel as printed", false, PRT_CLOTH_PAPER_FRESNEL},
        {"paper: g_u as printed", false, PRT_CLOTH_PAPER_NARROW_GU},
        {"the paper as printed", true, PRT_CLOTH_PAPER_FLAGS | PRT_CLOTH_NO_CONE_TABLE},
    };
    for (const auto& c : cases) {
      ClothTradeRow r = base;
      r.setting = c.setting;
      r.knob = "paper";
      r.table.full_sphere = c.full_sphere;
      run(r, c.full_sphere ? sphere : tables[0], light, c.flags, false);
    }
  }

  // What the reference and the light alone contribute to every row's error.
  void reference_rows(const ClothPreset& fabric, const MapTurns& map,
                      const std::vector<float>& reference, const TradeInput& input,
                      const Context& ctx) {
    ClothTradeRow merged;
    merged.fabric = fabric.name;
    merged.map = map.name;
    merged.setting = "reference over texels merged 2 x 2";
    merged.knob = "reference_merged";
    const std::vector<float> coarse = turned_reference(fabric, map, 2, input, ctx);
    merged.nrmse = nrmse(coarse, reference);
    merged.bias = bias(coarse, reference);
    rows_.push_back(merged);
    ClothTradeRow light = merged;
    light.lobes = o_.lobes.front();
    light.setting = format("reference under the K %u light", light.lobes);
    light.knob = "reference_sg";
    std::vector<float> under_light;
    for (std::size_t t = 0; t < map.turned.size(); ++t) {
      const EnvTexels texels = sg_texels(map.fitted[t][0]);
      const std::vector<float> r = cloth_trade::reference(fabric, samples_, texels, ctx);
      under_light.insert(under_light.end(), r.begin(), r.end());
    }
    light.nrmse = nrmse(under_light, reference);
    light.bias = bias(under_light, reference);
    rows_.push_back(light);
  }

  std::vector<std::string> cells(const ClothTradeRow& r) const {
    const bool method = r.max_rank > 0;
    return {r.fabric,
            r.map,
            r.setting,
            r.knob,
            r.lobes ? std::to_string(r.lobes) : "",
            method ? format("%g", r.table.energy) : "",
            method ? format("%u/%u/%u", r.table.xi, r.table.levels, r.table.views) : "",
            method ? std::to_string(r.table.bits) : "",
            method ? std::to_string(r.max_rank) : "",
            method ? format("%.3f", r.table_bytes / 1e6) : "",
            method ? std::to_string(r.panels) : "",
            method ? std::to_string(r.phi_nodes) : "",
            format("%.4f", r.nrmse),
            format("%+.4f", r.bias),
            trade::optional_number(r.truncation_cost, "%.4f"),
            trade::optional_number(r.cpu_us, "%.2f"),
            trade::optional_number(r.simd_us, "%.2f")};
  }

  void write_tables(const Scene& scene, const TradeInput& input) const {
    const std::vector<trade::Column> columns = {{"fabric", false},
                                                {"map", false},
                                                {"setting", false},
                                                {"sweep", false},
                                                {"K"},
                                                {"energy"},
                                                {"grid xi/L/views", false},
                                                {"bits"},
                                                {"max rank"},
                                                {"table MB"},
                                                {"panels"},
                                                {"phi nodes"},
                                                {"NRMSE"},
                                                {"bias"},
                                                {"truncation cost"},
                                                {"CPU us/sample"},
                                                {"SIMD us/sample"}};
    const std::string csv_path = input.out_dir + "/trade.csv";
    std::ofstream csv(csv_path);
    trade::write_csv_row(csv, {"fabric", "map", "setting", "sweeps", "lobes", "energy", "grid",
                               "bits", "max_rank", "table_mb", "panels", "phi_nodes", "nrmse",
                               "bias", "truncation_cost", "cpu_us", "simd_us"});
    for (const ClothTradeRow& r : rows_) trade::write_csv_row(csv, cells(r));
    trade::check_written(csv, csv_path);
    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    md << trade::scene_description(input.scene, scene) << "; " << samples_.count() / 32
       << " surface frame(s), 32 views each, under " << o_.turns
       << " turn(s) of each map about +Y. NRMSE: RMS error over samples and channels / the "
          "reference's mean; bias: mean / the reference's mean - 1; table MB: the fabric's "
          "stored tables (10^6 bytes); truncation cost: NRMSE against the same tables at every "
          "rank.\n"
       << trade::machine_description(1) << ".\n\n";
    trade::write_markdown_header(md, columns);
    for (const ClothTradeRow& r : rows_) trade::write_markdown_row(md, cells(r));
    md << "\nLight fits (turn 0, static fit): ";
    for (const MapTurns& m : maps_)
      for (const SgLightFit& f : m.reports)
        md << m.name << " K " << f.lobe_count
           << format(" relative error %.3f (runtime fit %.3f); ", f.error.relative,
                     f.fast.relative);
    md << "\n";
    trade::check_written(md, md_path);
  }

  ClothTradeSettings o_;
  std::vector<MapTurns> maps_;
  Samples samples_;
  std::vector<ClothTradeRow> rows_;
  int frames_ = 1;
};

}  // namespace

std::unique_ptr<TechniqueTrade> make_cloth_trade() {
  return std::make_unique<ClothTrade>();
}

}  // namespace prt::bake
