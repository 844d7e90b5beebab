// SPDX-License-Identifier: MIT
// The scene mode of prt-bake trade shadowfield (docs/shadowfield/trade.md), private to the baker:
// every knob of the technique swept one at a time around a base on a scene preset's objects and
// placements, measured on the runtime against the reference.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/technique.hpp"

#include "shadowfield_trade_shared.hpp"

namespace prt::bake::sf_trade {

// The scene sweep's own options (the order, terms, rays and bits sweeps are the object mode's).
struct SceneSweepOptions {
  std::string shared = "../shared";
  std::vector<std::string> times{"0", "4"};
  std::vector<std::uint32_t> oof_shells{4, 8, 16, 24}, oof_faces{4, 8, 16, 24},
      srf_shells{2, 4, 8, 16}, srf_faces{4, 8, 12}, basis{4, 8, 16, 32}, bounces{0, 1, 2, 3};
  std::uint32_t base_oof_shells = 16, base_oof_face = 16, base_srf_shells = 8, base_srf_face = 8,
                base_basis = 16, base_bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES, lights = 256;
  // The scene mode's rays when --rays / --base-rays are not given: the bake's default.
  std::uint32_t default_rays = 1024;
};

// Throws Error naming the option when a time is not a finite number or a swept value of the
// scene's own knobs is out of its range.
void check_scene_sweep_options(const SceneSweepOptions& options);

// The trade on a preset: each setting bakes every object (blobs cached by settings), the
// placements at the given times are shaded on the runtime and compared with the reference of
// the same placement and bounce count, rendered once and cached.
class SceneSweep {
 public:
  virtual ~SceneSweep() = default;
  // The whole scene placed at the first time: what run_trade builds its ray scene of.
  virtual Scene scene() const = 0;
  // Loads the environments and renders (or reads from the cache) every reference.
  virtual void prepare(const TradeInput& input, const Context& ctx) = 0;
  // Measures every setting and writes trade.csv and trade.md to input.out_dir.
  virtual void sweep(const TradeInput& input, const Context& ctx) = 0;
};

// `object`'s order, terms, rays and bits sweeps become the scene's; its rays sweep only when
// `rays_given`, its base rays only when `base_rays_given` (else options.default_rays).
std::unique_ptr<SceneSweep> make_scene_sweep(std::string preset, const SceneSweepOptions& options,
                                             const SfTradeSettings& object, bool rays_given,
                                             bool base_rays_given);

}  // namespace prt::bake::sf_trade
