// SPDX-License-Identifier: MIT
// The measurement of static objects in prt-bake scene (prt/baker/technique.hpp): the diffuse
// reference of the object alone on a spread of its vertices, under each light, against the
// technique's shade() of the blob.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "prt/baker/reference.hpp"
#include "prt/baker/technique.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"

namespace prt::bake {
namespace {

class DiffuseMeasure final : public ObjectMeasure {
 public:
  explicit DiffuseMeasure(const ObjectMeasureInput& input)
      : input_(input),
        probes_(spread_vertices(input.object->vertex_count(), input.probe_vertices)),
        references_(input.lights.size()) {}

  Measurement measure(const Technique& technique, const std::vector<std::uint8_t>& blob,
                      const Context& ctx) override {
    Measurement worst;
    for (std::size_t l = 0; l < input_.lights.size(); ++l) {
      const std::vector<glm::vec3> shaded = technique.shade(blob, *input_.lights[l], ctx);
      if (shaded.size() != input_.object->vertex_count())
        throw Error("the blob shades " + std::to_string(shaded.size()) + " vertices, not " +
                    std::to_string(input_.object->vertex_count()));
      std::vector<glm::vec3> at_probes;
      for (const std::size_t v : probes_) at_probes.push_back(shaded[v]);
      const VertexRadiance& ref = reference(l, ctx);
      double error =
          trade::noise_removed(io::relative_rmse(at_probes, ref.radiance), ref.relative_rmse);
      if (!std::isfinite(error)) error = HUGE_VAL;
      if (l == 0 || error > worst.error) worst = {error, ref.relative_rmse};
    }
    return worst;
  }

 private:
  const VertexRadiance& reference(std::size_t light, const Context& ctx) {
    if (!references_[light]) {
      ReferenceSettings rs;
      rs.bounces = input_.bounces;
      rs.spp = input_.ref_spp;
      rs.seed = input_.seed;
      const ReferenceRenderer renderer(*input_.object, *input_.lights[light], rs, ctx);
      references_[light] = std::make_unique<VertexRadiance>(renderer.render_vertices(probes_, ctx));
    }
    return *references_[light];
  }

  ObjectMeasureInput input_;
  std::vector<std::size_t> probes_;
  std::vector<std::unique_ptr<VertexRadiance>> references_;
};

}  // namespace

std::vector<std::size_t> spread_vertices(std::size_t vertices, std::size_t count) {
  std::vector<std::size_t> probes;
  const std::size_t n = std::min(vertices, std::max<std::size_t>(count, 1));
  for (std::size_t i = 0; i < n; ++i) probes.push_back((2 * i + 1) * vertices / (2 * n));
  return probes;
}

std::unique_ptr<ObjectMeasure> make_diffuse_measure(const ObjectMeasureInput& input) {
  return std::make_unique<DiffuseMeasure>(input);
}

}  // namespace prt::bake
