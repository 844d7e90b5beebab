// SPDX-License-Identifier: MIT
// The bake's self-check (baker/src/shadowfield/shadowfield_technique.hpp) passes on the blob of a
// bake and fails when the blob is not that bake's: a transfer value moved by more than its
// quantisation bound, a header that differs.
#include <gtest/gtest.h>

#include <string>

#include "../../../baker/src/shadowfield/shadowfield_technique.hpp"
#include "shadowfield_bake_scenes.hpp"

namespace prt::bake::test {
namespace {

struct GlossyQuad {
  ShadowfieldObject object;
  QuantizedShadowfield quantized;
  std::vector<std::uint8_t> blob;

  explicit GlossyQuad(int bits) {
    ShadowfieldBakeSettings settings = small_bake_settings(3);
    // One term: K = 2 is completed to GGX's three (its order-1 pair whole), and with three the
    // two-step error below stays within the self-check's bound at that vertex.
    settings.brdf.terms = 1;
    settings.brdf.grid_size = 8;
    settings.fields.oof_shells = 2;
    settings.fields.oof_face_size = 2;
    settings.basis.size = 4;
    ShadowfieldMaterialDescription description;
    description.model = ShadowfieldBrdfModel::Ggx;
    const Scene scene =
        one_mesh_scene(make_plane_mesh("quad", 0, 1.0f, 1.0f, 2, 2), glm::vec3(0.9f, 0.5f, 0.2f));
    object = bake_shadowfield_object(scene, make_shadowfield_material(description, settings.brdf),
                                     settings, Context{})
                 .object;
    quantized = quantize_shadowfield(object, bits);
    blob = build_shadowfield_blob(object, quantized, "");
  }
};

TEST(ShadowfieldSelfCheck, PassesOnItsOwnBlobAtBothBitDepths) {
  for (int bits : {8, 16}) {
    const GlossyQuad quad(bits);
    const ShadowfieldBlobCheck check =
        check_shadowfield_blob(quad.blob, quad.object, quad.quantized);
    EXPECT_TRUE(check.passed) << bits << ": " << check.message;
    EXPECT_GT(check.max_budget_ratio, 0.0);
    EXPECT_LE(check.max_budget_ratio, 1.0);
  }
}

// Band 0 of term 0 of vertex 4 (the quad's centre) moved by two quantisation steps of its row:
// twice the half step the bound allows for it, under the constant light of the check.
TEST(ShadowfieldSelfCheck, FailsWhenATransferValueIsOffByTwoSteps) {
  GlossyQuad quad(8);
  const std::size_t n2 = 9, terms = quad.object.material.terms(), vertex = 4;
  const float step = quad.quantized.transfer.scales[0];
  ASSERT_GT(step, 0.0f);
  quad.object.transfer[vertex * terms * n2] += 2.0f * step;
  const ShadowfieldBlobCheck check = check_shadowfield_blob(quad.blob, quad.object, quad.quantized);
  EXPECT_FALSE(check.passed);
  EXPECT_NE(check.message.find("vertex 4"), std::string::npos) << check.message;
}

TEST(ShadowfieldSelfCheck, FailsOnAnotherBakesHeader) {
  const GlossyQuad eight(8), sixteen(16);
  const ShadowfieldBlobCheck check =
      check_shadowfield_blob(eight.blob, sixteen.object, sixteen.quantized);
  EXPECT_FALSE(check.passed);
  EXPECT_NE(check.message.find("bits"), std::string::npos) << check.message;
  const ShadowfieldBlobCheck garbage =
      check_shadowfield_blob(std::vector<std::uint8_t>(64, 0x5a), eight.object, eight.quantized);
  EXPECT_FALSE(garbage.passed);
  EXPECT_FALSE(garbage.message.empty());
}

}  // namespace
}  // namespace prt::bake::test
