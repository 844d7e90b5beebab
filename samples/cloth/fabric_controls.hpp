// SPDX-License-Identifier: MIT
// The live parameters of a fabric's two threads as prt-cloth edits them: command-line options
// that override the fabric's defaults (--warp-eta, --weft-albedo R,G,B, ...; angles in degrees)
// and the panel's sliders. Either keeps the coverages' sum within 1: the other thread gives way.
#pragma once

#include <prt/prt.h>

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace prt::cloth_app {

class FabricOverrides {
 public:
  void add_options(CLI::App& app);
  // Parses what CLI11 cannot check alone; throws CLI::ValidationError.
  void check();
  bool empty() const;
  // `defaults` with the options given on the command line; throws CLI::ValidationError naming
  // `fabric` when the result is not valid (prt_cloth_params_validate: coverages over 1, say).
  prt_cloth_params apply(const prt_cloth_params& defaults, const std::string& fabric) const;

 private:
  struct Thread {
    std::optional<float> eta, kd, gamma_s_degrees, gamma_v_degrees, coverage;
    std::string albedo_text;
    std::optional<float> albedo[3];
  };
  Thread threads_[2];
};

// The sliders of both threads (eta, albedo RGB, k_d, gamma_s and gamma_v in degrees, coverage);
// true when one moved.
bool fabric_sliders(prt_cloth_params& params);

// "eta 1.35, albedo (0.20, 0.80, 1.00), kd 0.30, gamma_s 12.0 deg, gamma_v 24.0 deg, coverage 0.33"
std::string describe_thread(const prt_cloth_thread& thread);

}  // namespace prt::cloth_app
