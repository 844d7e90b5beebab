// SPDX-License-Identifier: MIT
// The sh rows of prt-bake trade wavelet: sh baked, stored and shaded through its own runtime in
// the same run, for the comparison at equal bytes per vertex.
#include <prt/prt.h>
#include <prt/prt_sh.h>

#include <algorithm>
#include <string>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"

#include "wavelet_trade.hpp"

namespace prt::bake::wavelet_trade {
namespace {

using namespace trade;

// One channel instead of three when R, G and B are the same (a grey albedo): SPEC §7.1's C = 1,
// the grey transfer the wavelet rows also store.
QuantizedShTransfer grey_if_possible(QuantizedShTransfer q) {
  const std::size_t n2 = q.coefficient_count();
  for (std::uint32_t c = 1; c < 3; ++c) {
    for (std::size_t k = 0; k < n2; ++k) {
      if (q.offsets[c * n2 + k] != q.offsets[k] || q.scales[c * n2 + k] != q.scales[k]) return q;
    }
  }
  for (std::size_t v = 0; v < q.vertex_count; ++v) {
    for (std::size_t k = 0; k < n2; ++k) {
      const std::uint16_t r = q.q[(v * 3) * n2 + k];
      if (q.q[(v * 3 + 1) * n2 + k] != r || q.q[(v * 3 + 2) * n2 + k] != r) return q;
    }
  }
  std::vector<std::uint16_t> grey(q.vertex_count * n2);
  for (std::size_t v = 0; v < q.vertex_count; ++v)
    std::copy_n(q.q.begin() + (v * 3) * n2, n2, grey.begin() + v * n2);
  q.q = std::move(grey);
  q.offsets.resize(n2);
  q.scales.resize(n2);
  q.channels = 1;
  return q;
}

double time_sh_projection(const TradeLight& light, std::uint32_t order, int frames) {
  std::vector<float> rgb(std::size_t(order) * order * 3);
  const prt_env_image env = env_image(light);
  return median_frame_ms(frames, "SH projection",
                         [&] { return prt_sh_project(order, &env, rgb.data()); });
}

}  // namespace

void measure_sh(const Scene& scene, const EmbreeScene& rays, std::uint32_t order,
                const std::vector<TradeLight>& lights, const Settings& o, const TradeInput& input,
                const Context& ctx, std::vector<Row>* rows) {
  ShTransferSettings settings;
  settings.order = order;
  settings.rays = o.sh_rays;
  settings.kind = ShTransferKind::Shadowed;
  settings.seed = input.seed;
  if (!input.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(input.albedo);
  }
  const ShTransfer transfer = compute_sh_transfer(scene, &rays, settings, ctx);
  const std::uint32_t vertices = static_cast<std::uint32_t>(transfer.vertex_count);
  for (std::uint32_t bits : o.sh_bits) {
    const QuantizedShTransfer q = grey_if_possible(quantize_sh_transfer(transfer, int(bits)));
    const std::size_t section = encode_shtr_section(q).size();
    const std::vector<std::uint8_t> blob = build_sh_blob(scene, q, "prtkit wavelet trade (sh)");
    const RuntimeAsset runtime = load_runtime_asset(blob);
    for (const TradeLight& light : lights) {
      const std::vector<float> l = light.sh.at_order(order);
      Row row;
      row.technique = "sh";
      row.map = light.sh.name;
      row.sweeps = "sh";
      row.quantizer = std::to_string(bits) + "-bit" + (q.channels == 1 ? " grey" : " rgb");
      row.order = order;
      row.rays = o.sh_rays;
      row.ref_noise = light.reference.noise;
      std::vector<float> shaded, simd_shaded;
      const prt_asset* asset = runtime.asset.get();
      row.simd_ms =
          time_sh_shading(asset, PRT_BACKEND_SIMD, l, vertices, input.frames, &simd_shaded);
      row.cpu_ms = time_sh_shading(asset, PRT_BACKEND_CPU, l, vertices, input.frames, &shaded);
      row.light_ms = time_sh_projection(light, order, input.frames);
      const std::vector<glm::vec3> radiance = as_vec3(shaded);
      row.error = subset_rmse(radiance, light.reference.radiance, o.vertex_stride);
      row.quant_error =
          subset_rmse(radiance, shade_sh_transfer(transfer, as_vec3(l)), o.vertex_stride);
      row.bytes_per_vertex = double(section) / vertices;
      row.blob_bytes = blob.size();
      row.bake_seconds = transfer.seconds;
      row.rays_traced = double(transfer.rays_traced);
      rows->push_back(row);
      ctx.info("  " + row.map + " sh order " + std::to_string(order) + ", " + row.quantizer +
               format(": error %.3f %%", 100 * row.error) +
               format(" (%.3f %% without noise)", 100 * row.clean_error()) +
               format(", %.0f B/vertex", row.bytes_per_vertex));
    }
  }
}

}  // namespace prt::bake::wavelet_trade
