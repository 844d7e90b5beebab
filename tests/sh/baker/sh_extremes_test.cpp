// SPDX-License-Identifier: MIT
// Technique sh at its extremes, end to end: bake -> quantise -> blob -> runtime load (full
// validation) -> runtime projection of the map -> runtime shading. Each case checks finite output
// and its stated behaviour against an independent expected value:
// - order 1 and PRT_SH_MAX_ORDER: a white furnace (closed convex sphere under radiance 1 reflects
//   exactly its albedo); orders outside 1..PRT_SH_MAX_ORDER are refused;
// - a 10^5:1 sun on a dim sky: unshadowed transfer shades to the band-limited irradiance
//   rho/pi sum_lm A_l L_lm Y_lm(n) (ringing included: SH is not clamped), within the transfer's
//   own Monte Carlo noise measured from a second seed;
// - an all-black map: exactly 0 everywhere;
// - NaN / Inf / negative texels: sanitised to 0, so the same light and shading, bit for bit, as the
//   map with those texels 0;
// - a zero normal: transfer exactly 0, counted; runtime radiance 0 up to quantisation; a NaN
//   normal: the same, and the blob stores (0, 0, 0) for it (full validation refuses NaN);
// - a vertex inside a closed box: shadowed transfer exactly 0; runtime radiance 0 up to
//   quantisation;
// - a constant transfer vector (min = max): scale 0, decoded exactly.
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/io/radiance_error.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A blob loaded through the runtime at full validation.
class RuntimeBlob {
 public:
  explicit RuntimeBlob(const std::vector<std::uint8_t>& blob) {
    auto loaded =
        prt::load_asset_memory(context_.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL);
    EXPECT_EQ(loaded.result, PRT_OK) << prt_context_last_message(context_.get());
    asset_ = std::move(loaded.handle);
    EXPECT_EQ(prt_sh_get_info(asset_.get(), &info_), PRT_OK);
  }
  const prt_sh_info& info() const { return info_; }

  std::vector<glm::vec3> shade(const std::vector<float>& light_rgb) const {
    std::vector<glm::vec3> out(info_.vertex_count, glm::vec3(-1.0f));
    EXPECT_EQ(prt_sh_shade(asset_.get(), PRT_BACKEND_CPU, light_rgb.data(), 0, info_.vertex_count,
                           &out[0].x),
              PRT_OK);
    return out;
  }
  std::vector<float> decode() const {
    std::vector<float> out(std::size_t(info_.vertex_count) * info_.channels * info_.order *
                           info_.order);
    EXPECT_EQ(prt_sh_decode_transfer(asset_.get(), 0, info_.vertex_count, out.data()), PRT_OK);
    return out;
  }

 private:
  prt::ContextPtr context_ = prt::create_context().handle;
  prt::AssetPtr asset_;
  prt_sh_info info_ = prt::sized<prt_sh_info>();
};

struct Baked {
  ShTransfer transfer;
  QuantizedShTransfer quantized;
  std::vector<std::uint8_t> blob;
};

Baked bake(const Scene& scene, ShTransferKind kind, std::uint32_t order, std::uint32_t rays,
           float albedo, std::uint32_t seed = 0) {
  ShTransferSettings s;
  s.kind = kind;
  s.order = order;
  s.rays = rays;
  s.seed = seed;
  s.override_albedo = true;
  s.albedo = glm::vec3(albedo);
  Baked b;
  b.transfer = compute_sh_transfer(scene, nullptr, s, Context{});
  b.quantized = quantize_sh_transfer(b.transfer, 16);
  b.blob = build_sh_blob(scene, b.quantized, "extremes test");
  return b;
}

// The runtime's SH projection of a lat-long map.
std::vector<float> project(const io::EnvMap& map, std::uint32_t order) {
  std::vector<float> light(std::size_t(order) * order * 3);
  const prt_env_image env = prt::latlong_env(map.width(), map.height(), map.pixels().data());
  EXPECT_EQ(prt_sh_project(order, &env, light.data()), PRT_OK);
  return light;
}

// Only L_00 = sqrt(4 pi): a constant environment of radiance 1.
std::vector<float> constant_light(std::uint32_t order) {
  std::vector<float> light(std::size_t(order) * order * 3, 0.0f);
  for (int c = 0; c < 3; ++c) light[c] = float(std::sqrt(4.0 * kPi));
  return light;
}

void expect_all_finite(const std::vector<glm::vec3>& values) {
  for (std::size_t v = 0; v < values.size(); ++v) {
    ASSERT_TRUE(std::isfinite(values[v].r) && std::isfinite(values[v].g) &&
                std::isfinite(values[v].b))
        << "vertex " << v;
  }
}

// The most a vertex whose float transfer is 0 can shade to after quantisation: each decoded
// coefficient is within scale/2 of 0 (formats/SPEC.md: q = round((t - offset) / scale)), plus
// float rounding of the dequantisation.
double quantisation_bound(const QuantizedShTransfer& q, const std::vector<float>& light,
                          int channel) {
  double bound = 0.0;
  for (std::size_t k = 0; k < q.coefficient_count(); ++k) {
    const std::size_t i = channel * q.coefficient_count() + k;
    const double per_value = 0.5 * q.scales[i] + 1e-6 * (std::abs(q.offsets[i]) + q.scales[i]);
    bound += per_value * std::abs(light[k * 3 + channel]);
  }
  return bound;
}

// A closed cube of half-size `half` about the origin, outward normals; each face overlaps its
// neighbours by a little so no ray can slip out along an edge.
std::vector<Mesh> closed_cube(float half, int cells) {
  const float h = half * 1.02f;
  std::vector<Mesh> faces;
  for (int axis = 0; axis < 3; ++axis) {
    for (float side : {-1.0f, 1.0f}) {
      glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
      normal[axis] = side;
      u[(axis + 1) % 3] = 2.0f * h;
      v[(axis + 2) % 3] = 2.0f * h;
      const glm::vec3 corner = normal * half - 0.5f * u - 0.5f * v;
      faces.push_back(test::make_grid("cube face", corner, u, v, cells, cells, normal));
    }
  }
  return faces;
}

TEST(ShExtremes, OrderOneAndTheMaximumOrderKeepTheWhiteFurnace) {
  // A closed convex sphere never sees itself, so under radiance 1 every vertex reflects its
  // albedo; cosine-weighted sampling makes t_00 exact, and the constant light has no l > 0 term.
  const Scene scene = test::scene_of({test::make_icosphere(2, 1.0f)});
  const float rho = 0.6f;
  for (std::uint32_t order : {1u, PRT_SH_MAX_ORDER}) {
    const Baked b = bake(scene, ShTransferKind::Shadowed, order, 256, rho);
    const RuntimeBlob blob(b.blob);
    EXPECT_EQ(blob.info().order, order);
    const std::vector<glm::vec3> shaded = blob.shade(constant_light(order));
    expect_all_finite(shaded);
    for (std::size_t v = 0; v < shaded.size(); ++v) {
      ASSERT_NEAR(shaded[v].g, rho, 1e-5) << "order " << order << " vertex " << v;
    }
  }
}

TEST(ShExtremes, OrdersOutsideTheSupportedRangeAreRefused) {
  const Scene scene = test::scene_of({test::make_icosphere(0, 1.0f)});
  for (std::uint32_t order : {0u, PRT_SH_MAX_ORDER + 1}) {
    ShTransferSettings s;
    s.order = order;
    s.kind = ShTransferKind::Unshadowed;
    EXPECT_THROW(compute_sh_transfer(scene, nullptr, s, Context{}), Error) << "order " << order;
  }
}

// Band-limited irradiance of `light` at unit normal n, times rho/pi, per channel: the value an
// exact unshadowed transfer gives (Ramamoorthi-Hanrahan convolution, computed without the bake).
glm::vec3 band_limited_radiance(std::uint32_t order, const std::vector<float>& light, glm::vec3 n,
                                float rho) {
  std::vector<float> irradiance(light.size()), y(std::size_t(order) * order);
  EXPECT_EQ(prt_sh_convolve_cosine(order, light.data(), irradiance.data(), 3), PRT_OK);
  EXPECT_EQ(prt_sh_eval(order, &n.x, y.data()), PRT_OK);
  glm::dvec3 sum(0.0);
  for (std::size_t k = 0; k < y.size(); ++k) {
    for (int c = 0; c < 3; ++c) sum[c] += double(irradiance[k * 3 + c]) * y[k];
  }
  return glm::vec3(sum * double(rho) / kPi);
}

TEST(ShExtremes, TinySunOfTenToTheFiveOverTheSkyShadesToTheBandLimitedIrradiance) {
  // Sky of radiance 1 with a 2x2-texel sun of 1e5 (0.0015 % of the sphere, ~5 times the sky's
  // power) above the horizon towards -Z and +X.
  const int width = 512, height = 256;
  std::vector<float> rgb(std::size_t(width) * height * 3, 1.0f);
  for (int j = 80; j < 82; ++j) {
    for (int i = 300; i < 302; ++i) {
      for (int c = 0; c < 3; ++c) rgb[(std::size_t(j) * width + i) * 3 + c] = 1e5f;
    }
  }
  const io::EnvMap map(width, height, std::move(rgb), io::EnvMapping::LatLong, "sun");
  const Scene scene = test::scene_of({test::make_icosphere(2, 1.0f)});
  const Mesh& sphere = scene.meshes[0];
  const float rho = 0.8f;
  for (std::uint32_t order : {6u, PRT_SH_MAX_ORDER}) {
    const std::vector<float> light = project(map, order);
    const std::vector<glm::vec3> shaded =
        RuntimeBlob(bake(scene, ShTransferKind::Unshadowed, order, 4096, rho).blob).shade(light);
    const std::vector<glm::vec3> other_seed =
        RuntimeBlob(bake(scene, ShTransferKind::Unshadowed, order, 4096, rho, 1).blob).shade(light);
    expect_all_finite(shaded);
    std::vector<glm::vec3> expected;
    for (const glm::vec3& n : sphere.normals) {
      expected.push_back(band_limited_radiance(order, light, n, rho));
    }
    // Two seeds differ by sqrt(2) times one estimate's noise; allow 3 sigma of it, and 1e-4 for
    // the quantisation and float sums.
    const double noise = io::relative_rmse(shaded, other_seed) / std::sqrt(2.0);
    const double error = io::relative_rmse(shaded, expected);
    RecordProperty("order" + std::to_string(order) + "_error", std::to_string(error));
    EXPECT_LT(error, 3.0 * noise + 1e-4) << "order " << order << ", noise " << noise;
  }
}

TEST(ShExtremes, AllBlackMapShadesToExactlyZero) {
  const Scene scene = test::scene_of(test::make_fine_open_box(1.0f, 6, 3));
  const Baked b = bake(scene, ShTransferKind::Shadowed, 4, 64, 0.8f);
  const io::EnvMap black(64, 32, std::vector<float>(64 * 32 * 3, 0.0f), io::EnvMapping::LatLong,
                         "black");
  const std::vector<float> light = project(black, 4);
  for (float l : light) ASSERT_EQ(l, 0.0f);
  for (const glm::vec3& radiance : RuntimeBlob(b.blob).shade(light)) {
    ASSERT_EQ(radiance, glm::vec3(0.0f));
  }
}

TEST(ShExtremes, NaNInfiniteAndNegativeTexelsActAsZero) {
  const auto sky = [](glm::vec3 w) { return glm::vec3(1.0f, 0.7f, 0.5f) + 0.4f * w; };
  const io::EnvMap clean_source = test::make_function_map(128, sky);
  std::vector<float> bad = clean_source.pixels(), zeroed = clean_source.pixels();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::size_t texels[] = {0, 77, 4000, 8191};
  const float values[] = {nan, inf, -3.0f, nan};
  for (int i = 0; i < 4; ++i) {
    bad[texels[i] * 3 + 1] = values[i];  // one bad channel; sanitising zeroes just that one
    zeroed[texels[i] * 3 + 1] = 0.0f;
  }
  std::vector<float> raw_bad = bad;
  const io::EnvMap sanitised(128, 64, std::move(bad), io::EnvMapping::LatLong, "bad");
  const io::EnvMap reference(128, 64, std::move(zeroed), io::EnvMapping::LatLong, "zeroed");
  EXPECT_EQ(sanitised.sanitized_texels(), 4u);
  EXPECT_EQ(sanitised.pixels(), reference.pixels());

  const std::uint32_t order = 5;
  const std::vector<float> light = project(sanitised, order);
  EXPECT_EQ(light, project(reference, order));
  // The runtime's own projection also counts such values as 0, without the importer.
  std::vector<float> raw_light(light.size());
  const prt_env_image raw_env = prt::latlong_env(128, 64, raw_bad.data());
  ASSERT_EQ(prt_sh_project(order, &raw_env, raw_light.data()), PRT_OK);
  EXPECT_EQ(raw_light, light);

  const Scene scene = test::scene_of(test::make_fine_open_box(1.0f, 6, 3));
  const RuntimeBlob blob(bake(scene, ShTransferKind::Shadowed, order, 64, 0.8f).blob);
  const std::vector<glm::vec3> shaded = blob.shade(light);
  expect_all_finite(shaded);
  EXPECT_EQ(shaded, blob.shade(project(reference, order)));
}

TEST(ShExtremes, VertexWithANaNNormalGetsZeroTransferAndAZeroStoredNormal) {
  Mesh plane = test::make_plane(1.0f, 4);
  plane.normals[12] = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 1.0f, 0.0f);
  const Scene scene = test::scene_of({plane});
  const std::uint32_t order = 3;
  const Baked b = bake(scene, ShTransferKind::Shadowed, order, 64, 0.8f);
  EXPECT_EQ(b.transfer.vertices_without_normal, 1u);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < b.transfer.coefficient_count(); ++k) {
      EXPECT_EQ(b.transfer.vertex_channel(12, c)[k], 0.0f);
      EXPECT_TRUE(std::isfinite(b.transfer.vertex_channel(11, c)[k]));
    }
  }
  // The blob loads at full validation (RuntimeBlob checks it) and stores a zero normal there.
  const RuntimeBlob blob(b.blob);
  const auto sky = [](glm::vec3 w) { return glm::vec3(1.0f, 0.7f, 0.5f) + 0.4f * w; };
  const std::vector<float> light = project(test::make_function_map(128, sky), order);
  const std::vector<glm::vec3> shaded = blob.shade(light);
  expect_all_finite(shaded);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(std::abs(shaded[12][c]), quantisation_bound(b.quantized, light, c));
  }
  prt_context* context = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_memory(context, b.blob.data(), b.blob.size(), PRT_VALIDATE_FULL, &asset),
            PRT_OK);
  std::vector<float> normals(3 * scene.vertex_count());
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_VNRM, normals.data(),
                                   normals.size() * sizeof(float), nullptr),
            PRT_OK);
  EXPECT_EQ(normals[36], 0.0f);
  EXPECT_EQ(normals[37], 0.0f);
  EXPECT_EQ(normals[38], 0.0f);
  EXPECT_EQ(normals[34], plane.normals[11].y);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
}

TEST(ShExtremes, VertexWithAZeroNormalGetsZeroTransferAndShadesToZero) {
  Mesh plane = test::make_plane(1.0f, 4);
  plane.normals[3] = glm::vec3(0.0f);
  plane.normals[12] = glm::vec3(0.0f);
  const Scene scene = test::scene_of({plane});
  const std::uint32_t order = 3;
  const Baked b = bake(scene, ShTransferKind::Shadowed, order, 64, 0.8f);
  EXPECT_EQ(b.transfer.vertices_without_normal, 2u);
  const auto sky = [](glm::vec3 w) { return glm::vec3(1.0f, 0.7f, 0.5f) + 0.4f * w; };
  const std::vector<float> light = project(test::make_function_map(128, sky), order);
  const std::vector<glm::vec3> shaded = RuntimeBlob(b.blob).shade(light);
  ASSERT_EQ(shaded.size(), scene.vertex_count());
  expect_all_finite(shaded);
  for (std::size_t v : {std::size_t(3), std::size_t(12)}) {
    for (int c = 0; c < 3; ++c) {
      const float* t = b.transfer.vertex_channel(v, c);
      for (std::size_t k = 0; k < b.transfer.coefficient_count(); ++k) ASSERT_EQ(t[k], 0.0f);
      EXPECT_LE(std::abs(shaded[v][c]), quantisation_bound(b.quantized, light, c))
          << "vertex " << v;
    }
  }
  // Its neighbours, which have normals, are lit.
  EXPECT_GT(shaded[4].g, 0.1f);
}

TEST(ShExtremes, VertexInsideAClosedBoxIsFullyShadowed) {
  std::vector<Mesh> meshes = closed_cube(1.0f, 4);
  std::size_t inside_first = 0;
  for (const Mesh& face : meshes) inside_first += face.vertex_count();
  meshes.push_back(test::make_plane(0.3f, 2));  // 9 vertices inside, facing +Y
  const Scene scene = test::scene_of(std::move(meshes));
  const std::uint32_t order = 4;
  const Baked b = bake(scene, ShTransferKind::Shadowed, order, 256, 0.8f);
  const auto sky = [](glm::vec3 w) { return glm::vec3(1.0f, 0.7f, 0.5f) + 0.4f * w; };
  const std::vector<float> light = project(test::make_function_map(128, sky), order);
  const std::vector<glm::vec3> shaded = RuntimeBlob(b.blob).shade(light);
  ASSERT_EQ(shaded.size(), scene.vertex_count());
  expect_all_finite(shaded);
  for (std::size_t v = inside_first; v < scene.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const float* t = b.transfer.vertex_channel(v, c);
      for (std::size_t k = 0; k < b.transfer.coefficient_count(); ++k) {
        ASSERT_EQ(t[k], 0.0f) << "vertex " << v;
      }
      EXPECT_LE(std::abs(shaded[v][c]), quantisation_bound(b.quantized, light, c))
          << "vertex " << v;
    }
  }
  // The cube's outside faces see the sky: the quantisation range is not trivial.
  EXPECT_GT(shaded[0].g, 0.1f);
}

TEST(ShExtremes, ConstantTransferVectorIsDecodedExactly) {
  // Order 1 on an unoccluded plane: t_00 = rho * Y_00 at every vertex (cosine-weighted samples of
  // a constant), so min = max: scale 0 and an exact decode.
  const Scene plane = test::scene_of({test::make_plane(1.0f, 3)});
  const float rho = 0.7f;
  const Baked b = bake(plane, ShTransferKind::Shadowed, 1, 64, rho);
  for (float s : b.quantized.scales) EXPECT_EQ(s, 0.0f);
  const std::vector<float> decoded = RuntimeBlob(b.blob).decode();
  ASSERT_EQ(decoded.size(), b.transfer.coefficients.size());
  for (std::size_t i = 0; i < decoded.size(); ++i) {
    ASSERT_EQ(decoded[i], b.transfer.coefficients[i]);
    ASSERT_NEAR(decoded[i], rho * 0.5 / std::sqrt(kPi), 1e-6);
  }

  // A constant vector of higher order with negative and tiny values, set by hand.
  ShTransfer t;
  t.order = 4;
  t.kind = ShTransferKind::Shadowed;
  t.vertex_count = plane.vertex_count();
  std::vector<float> vector(3 * 16);
  for (std::size_t k = 0; k < vector.size(); ++k) vector[k] = float(std::sin(1.0 + k)) * 1e-3f;
  vector[5] = 0.0f;
  vector[6] = -1e-30f;
  for (std::size_t v = 0; v < t.vertex_count; ++v) {
    t.coefficients.insert(t.coefficients.end(), vector.begin(), vector.end());
  }
  const QuantizedShTransfer q = quantize_sh_transfer(t, 8);
  EXPECT_EQ(q.max_abs_error, 0.0);
  const RuntimeBlob blob(build_sh_blob(plane, q, "constant"));
  EXPECT_EQ(blob.decode(), t.coefficients);
  const std::vector<float> light = constant_light(4);
  for (const glm::vec3& radiance : blob.shade(light)) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(radiance[c], vector[c * 16] * light[c]);
  }
}

}  // namespace
}  // namespace prt::bake
