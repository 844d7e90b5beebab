// SPDX-License-Identifier: MIT
// The one environment-image description (prt_env.h): every rejection of prt_env_image_validate,
// and that every projection and resampling rejects exactly what it rejects (one check for all).
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace {

struct Case {
  const char* name;
  std::function<void(prt_env_image&)> edit;
  bool valid;
};

// Edits of a valid 8 x 4 lat-long RGB image (texels for any stride below) or, with `cube`, a valid
// 4 x 4 cube.
std::vector<Case> cases(bool cube) {
  const float kNan = std::nanf("");
  static const float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const float turn[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};  // 90 degrees about +Y
  static const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const float scaled[9] = {1.01f, 0, 0, 0, 1, 0, 0, 0, 1};
  static const float sheared[9] = {1, 0.01f, 0, 0, 1, 0, 0, 0, 1};
  static const float nearly[9] = {1.0004f, 0, 0, 0, 1, 0, 0, 0, 1};  // within 1e-3
  static float not_finite[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  not_finite[4] = kNan;
  std::vector<Case> all = {
      {"as built", [](prt_env_image&) {}, true},
      {"struct_size 0", [](prt_env_image& e) { e.struct_size = 0; }, false},
      {"struct_size one short of 1.0",
       [](prt_env_image& e) { e.struct_size = offsetof(prt_env_image, rotation); }, false},
      {"struct_size of a newer, larger struct",
       [](prt_env_image& e) { e.struct_size = sizeof(prt_env_image) + 64; }, true},
      {"layout 2", [](prt_env_image& e) { e.layout = static_cast<prt_env_layout>(2); }, false},
      {"width 0", [](prt_env_image& e) { e.width = 0; }, false},
      {"height 0", [](prt_env_image& e) { e.height = 0; }, false},
      {"channels 0", [](prt_env_image& e) { e.channels = 0; }, false},
      {"channels 1", [](prt_env_image& e) { e.channels = 1; }, false},
      {"channels 5", [](prt_env_image& e) { e.channels = 5; }, false},
      {"channels 4", [](prt_env_image& e) { e.channels = 4; }, true},
      {"texels NULL", [](prt_env_image& e) { e.texels = nullptr; }, false},
      {"row_stride one short", [](prt_env_image& e) { e.row_stride = e.width * e.channels - 1; },
       false},
      {"row_stride exact", [](prt_env_image& e) { e.row_stride = e.width * e.channels; }, true},
      {"row_stride padded", [](prt_env_image& e) { e.row_stride = e.width * e.channels + 3; },
       true},
      {"row_stride overflowing", [](prt_env_image& e) { e.row_stride = SIZE_MAX / 2; }, false},
      {"rotation identity", [](prt_env_image& e) { e.rotation = identity; }, true},
      {"rotation 90 degrees", [](prt_env_image& e) { e.rotation = turn; }, true},
      {"rotation within 1e-3", [](prt_env_image& e) { e.rotation = nearly; }, true},
      {"rotation NaN", [](prt_env_image& e) { e.rotation = not_finite; }, false},
      {"rotation a reflection", [](prt_env_image& e) { e.rotation = mirror; }, false},
      {"rotation scaled", [](prt_env_image& e) { e.rotation = scaled; }, false},
      {"rotation sheared", [](prt_env_image& e) { e.rotation = sheared; }, false},
  };
  if (cube) {
    all.push_back({"cube width != height", [](prt_env_image& e) { e.height = 2; }, false});
    all.push_back({"cube face above the limit",
                   [](prt_env_image& e) { e.width = e.height = PRT_ENV_MAX_FACE_SIZE + 1; },
                   false});
    all.push_back({"face_stride one short",
                   [](prt_env_image& e) { e.face_stride = e.height * e.width * 3 - 1; }, false});
    all.push_back({"face_stride exact",
                   [](prt_env_image& e) { e.face_stride = e.height * e.width * 3; }, true});
    all.push_back(
        {"face_stride overflowing", [](prt_env_image& e) { e.face_stride = SIZE_MAX / 4; }, false});
  } else {
    all.push_back({"lat-long of any aspect", [](prt_env_image& e) { e.width = 3; }, true});
    all.push_back(
        {"lat-long ignores face_stride", [](prt_env_image& e) { e.face_stride = 1; }, true});
  }
  return all;
}

void check_every_case(bool cube) {
  // Enough texels for every valid case (the padded strides included).
  const std::vector<float> texels(6 * 4 * (4 * 8 + 3), 0.5f);
  const prt_env_image base =
      cube ? prt::cube_env(4, texels.data()) : prt::latlong_env(8, 4, texels.data());
  std::vector<float> sh(9 * 3), wavelet(4 * 6 * 16 * 16);
  for (const Case& c : cases(cube)) {
    prt_env_image env = base;
    c.edit(env);
    const prt_result expected = c.valid ? PRT_OK : PRT_ERROR_INVALID_ARGUMENT;
    EXPECT_EQ(prt_env_image_validate(&env), expected) << c.name;
    EXPECT_EQ(prt_sh_project(3, &env, sh.data()), expected) << c.name;
    EXPECT_EQ(prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, 16, &env, wavelet.data()), expected)
        << c.name;
  }
}

TEST(EnvImage, LatLongRejectionsAreTheSameEverywhere) {
  check_every_case(false);
}

TEST(EnvImage, CubeRejectionsAreTheSameEverywhere) {
  check_every_case(true);
}

TEST(EnvImage, NullIsRejected) {
  std::vector<float> out(4 * 6 * 16 * 16);
  EXPECT_EQ(prt_env_image_validate(nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, nullptr, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, 16, nullptr, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
}

// A struct from newer headers (larger struct_size) is read as far as this runtime knows it.
TEST(EnvImage, ANewerLargerStructIsReadAsFarAsKnown) {
  const std::vector<float> texels(8 * 4 * 3, 1.0f);
  static const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  struct Newer {
    prt_env_image env;
    float future_field;
  } newer;
  newer.env = prt::latlong_env(8, 4, texels.data());
  newer.env.struct_size = sizeof newer;
  newer.future_field = std::nanf("");
  EXPECT_EQ(prt_env_image_validate(&newer.env), PRT_OK);
  newer.env.rotation = mirror;  // still read: it is a 1.0 field
  EXPECT_EQ(prt_env_image_validate(&newer.env), PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
