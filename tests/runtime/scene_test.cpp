// SPDX-License-Identifier: MIT
// Scene API (prt_scene.h) on the golden blobs of every technique: one load, one shade per frame.
// Each object's radiance is what its technique's own functions give for the same light, pose,
// placement and eye; radiance is linear in the light; a turned moving object sees the light as
// the unturned one sees the light turned back; and every failure names the object and is clean.
#include <gtest/gtest.h>

#include <prt/format/scene_layout.h>
#include <prt/format/scene_writer.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/counting_allocator.hpp"

namespace {

using namespace prt_test;
namespace fs = std::filesystem;

const std::string kGolden = std::string(PRT_GOLDEN_DIR) + "/1.0";

// The golden blob of each technique, by its section tag.
struct GoldenObject {
  const char* name;
  const char* file;
  std::uint32_t tag;
};
const GoldenObject kObjects[] = {
    {"sh_quad", "sh_quad.prtk", PRT_SECTION_SHTR},
    {"wavelet_quad", "wavelet_quad.prtk", PRT_SECTION_WVLT},
    {"pose_hinge", "pose_hinge.prtk", PRT_SECTION_PSTR},
    {"cloth_quad", "cloth_quad.prtk", PRT_SECTION_CLTH},
    {"shadowfield_quad", "shadowfield_quad.prtk", PRT_SECTION_SFLD},
};

prt::format::SceneManifestObject manifest_object(const char* name, const std::string& blob,
                                                 std::uint32_t tag) {
  prt::format::SceneManifestObject o;
  o.technique_tag = tag;
  o.name = name;
  o.blob = blob;
  return o;
}

std::vector<prt::format::SceneManifestObject> golden_objects() {
  std::vector<prt::format::SceneManifestObject> objects;
  for (const GoldenObject& g : kObjects) objects.push_back(manifest_object(g.name, g.file, g.tag));
  return objects;
}

// A sky with a bright warm patch: lat-long RGB, scaled by `gain`.
struct Sky {
  static constexpr std::uint32_t kWidth = 64, kHeight = 32;
  std::vector<float> texels;
  explicit Sky(float gain = 1.0f) : texels(3 * kWidth * kHeight) {
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const bool sun = x >= 10 && x < 14 && y >= 6 && y < 9;
        float* t = &texels[3 * (y * kWidth + x)];
        const float up = 1.0f - float(y) / kHeight;
        t[0] = gain * (sun ? 20.0f : 0.2f + 0.5f * up);
        t[1] = gain * (sun ? 16.0f : 0.3f + 0.5f * up);
        t[2] = gain * (sun ? 10.0f : 0.5f + 0.6f * up);
      }
  }
  prt_env_image image(const float* rotation = nullptr) const {
    prt_env_image env = prt::sized<prt_env_image>();
    env.layout = PRT_ENV_LATLONG;
    env.width = kWidth;
    env.height = kHeight;
    env.channels = 3;
    env.texels = texels.data();
    env.rotation = rotation;
    return env;
  }
};

class Scene : public ::testing::Test {
 protected:
  Context ctx;
  prt_scene* scene = nullptr;
  Sky sky;
  const float eye[3] = {0.3f, 2.0f, 3.0f};

  void TearDown() override { prt_scene_destroy(scene); }

  // Writes the manifest into a fresh folder beside copies of the golden blobs.
  static fs::path write_scene(const std::vector<prt::format::SceneManifestObject>& objects,
                              const std::string& folder) {
    const fs::path dir = fs::path(testing::TempDir()) / folder;
    fs::remove_all(dir);
    fs::create_directories(dir / "blobs");
    for (const GoldenObject& g : kObjects) fs::copy_file(fs::path(kGolden) / g.file, dir / g.file);
    const std::vector<std::uint8_t> bytes = prt::format::write_scene_manifest(objects);
    std::ofstream(dir / "scene.prts", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return dir / "scene.prts";
  }

  prt_result load(const fs::path& path) {
    prt_scene_desc desc = prt::sized<prt_scene_desc>();
    desc.validation = PRT_VALIDATE_FULL;
    return prt_scene_load_file(ctx.ctx, path.c_str(), &desc, &scene);
  }

  void load_golden() { ASSERT_EQ(load(write_scene(golden_objects(), "scene_golden")), PRT_OK); }

  prt_scene_frame frame(prt_backend backend = PRT_BACKEND_CPU) const {
    prt_scene_frame f = prt::sized<prt_scene_frame>();
    f.backend = backend;
    for (int i = 0; i < 3; ++i) f.eye[i] = eye[i];
    return f;
  }

  std::vector<float> radiance(std::uint32_t object) const {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    EXPECT_EQ(prt_scene_get_object(scene, object, &info), PRT_OK);
    const float* r = prt_scene_object_radiance(scene, object);
    EXPECT_NE(r, nullptr);
    return r ? std::vector<float>(r, r + 3 * std::size_t(info.vertex_count)) : std::vector<float>();
  }

  std::string message() const { return prt_context_last_message(ctx.ctx); }
};

// ---- What each technique's own functions give (the scene must give the same) ---------------

std::vector<float> project(std::uint32_t order, const prt_env_image& env) {
  std::vector<float> light(3 * order * order);
  EXPECT_EQ(prt_sh_project(order, &env, light.data()), PRT_OK);
  return light;
}

std::vector<float> section_floats(const prt_asset* asset, std::uint32_t tag) {
  const void* data = nullptr;
  size_t size = 0;
  EXPECT_EQ(prt_asset_section_data(asset, tag, &data, &size), PRT_OK);
  const float* f = static_cast<const float*>(data);
  return std::vector<float>(f, f + size / sizeof(float));
}

std::vector<float> own_sh(const prt_asset* asset, const prt_env_image& env) {
  auto info = prt::sized<prt_sh_info>();
  EXPECT_EQ(prt_sh_get_info(asset, &info), PRT_OK);
  const std::vector<float> light = project(info.order, env);
  std::vector<float> out(3 * std::size_t(info.vertex_count));
  EXPECT_EQ(prt_sh_shade(asset, PRT_BACKEND_CPU, light.data(), 0, info.vertex_count, out.data()),
            PRT_OK);
  return out;
}

std::vector<float> own_wavelet(const prt_asset* asset, const prt_env_image& env) {
  auto info = prt::sized<prt_wavelet_info>();
  EXPECT_EQ(prt_wavelet_get_info(asset, &info), PRT_OK);
  std::vector<float> light(4 * std::size_t(info.coefficient_count));
  std::vector<std::uint8_t> zero_blocks(info.block_count);
  EXPECT_EQ(prt_wavelet_resample(info.param, info.size, &env, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_transform_light(info.param, info.size, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_prepare_light(asset, light.data(), light.data(), zero_blocks.data()),
            PRT_OK);
  std::vector<float> out(3 * std::size_t(info.vertex_count));
  EXPECT_EQ(prt_wavelet_shade(asset, PRT_BACKEND_CPU, light.data(), zero_blocks.data(), 0,
                              info.vertex_count, out.data()),
            PRT_OK);
  return out;
}

std::vector<float> own_pose(const prt_asset* asset, const prt_env_image& env,
                            const std::vector<float>& rotations, const float* turn) {
  auto info = prt::sized<prt_pose_info>();
  EXPECT_EQ(prt_pose_get_info(asset, &info), PRT_OK);
  const std::vector<float> light = project(info.order, env);
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  prt_pose_light pose_light = prt::sized<prt_pose_light>();
  pose_light.light_rgb = light.data();
  pose_light.world_from_character = turn;
  std::vector<float> out(3 * std::size_t(info.vertex_count));
  EXPECT_EQ(
      prt_pose_shade(asset, PRT_BACKEND_CPU, &pose, &pose_light, 0, info.vertex_count, out.data()),
      PRT_OK);
  return out;
}

std::vector<float> own_cloth(prt_context* context, const prt_asset* asset, const prt_env_image& env,
                             const float eye[3]) {
  std::vector<prt_cloth_lobe> lobes(64);
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  desc.lobe_count = 64;
  EXPECT_EQ(prt_cloth_fit_light(context, &env, &desc, lobes.data(), nullptr), PRT_OK);
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = 64;
  light.lobes = lobes.data();
  const std::vector<float> positions = section_floats(asset, PRT_SECTION_VPOS);
  const std::vector<float> normals = section_floats(asset, PRT_SECTION_VNRM);
  const std::vector<float> warps = section_floats(asset, PRT_SECTION_VTAN);
  const std::size_t vertices = positions.size() / 3;
  std::vector<float> views(positions.size());
  // Each vertex seen from the eye: the unit vector towards it, normalised in double.
  for (std::size_t v = 0; v < vertices; ++v) {
    double d[3], length = 0.0;
    for (int i = 0; i < 3; ++i) {
      d[i] = double(eye[i]) - double(positions[3 * v + i]);
      length += d[i] * d[i];
    }
    length = std::sqrt(length);
    for (int i = 0; i < 3; ++i) views[3 * v + i] = float(d[i] / length);
  }
  prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
  pixels.normals = normals.data();
  pixels.warps = warps.data();
  pixels.views = views.data();
  std::vector<float> out(positions.size());
  EXPECT_EQ(prt_cloth_shade(asset, PRT_BACKEND_CPU, 0, nullptr, &light, nullptr, &pixels, 0,
                            std::uint32_t(vertices), out.data()),
            PRT_OK);
  return out;
}

std::vector<float> own_shadowfield(prt_context* context, const prt_asset* asset,
                                   const prt_env_image& env, const float eye[3]) {
  prt_shadowfield_scene* sf = nullptr;
  EXPECT_EQ(prt_shadowfield_scene_create(context, 1, &sf), PRT_OK);
  std::uint32_t object = 0, instance = 0;
  EXPECT_EQ(prt_shadowfield_scene_add_object(sf, asset, &object), PRT_OK);
  prt_shadowfield_transform identity = prt::sized<prt_shadowfield_transform>();
  identity.rotation[0] = identity.rotation[4] = identity.rotation[8] = 1.0f;
  identity.scale = 1.0f;
  EXPECT_EQ(prt_shadowfield_scene_add_instance(sf, object, &identity, &instance), PRT_OK);
  const std::vector<float> light = project(prt_shadowfield_scene_order(sf), env);
  prt_shadowfield_settings settings = prt::sized<prt_shadowfield_settings>();
  settings.bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES;
  settings.backend = PRT_BACKEND_CPU;
  std::vector<float> out(3 * std::size_t(prt_shadowfield_instance_vertex_count(sf, instance)));
  float* outs[] = {out.data()};
  EXPECT_EQ(prt_shadowfield_shade(sf, light.data(), eye, &settings, outs), PRT_OK);
  prt_shadowfield_scene_destroy(sf);
  return out;
}

float max_abs(const std::vector<float>& v) {
  float m = 0.0f;
  for (float x : v) m = std::max(m, std::fabs(x));
  return m;
}

// ---- Loading ---------------------------------------------------------------------------------

TEST_F(Scene, LoadsEveryObjectWithItsTechniqueAndMesh) {
  load_golden();
  ASSERT_EQ(prt_scene_object_count(scene), 5u);
  const std::map<std::string, prt_technique> expected = {
      {"sh_quad", PRT_TECHNIQUE_SH},
      {"wavelet_quad", PRT_TECHNIQUE_WAVELET},
      {"pose_hinge", PRT_TECHNIQUE_POSE},
      {"cloth_quad", PRT_TECHNIQUE_CLOTH},
      {"shadowfield_quad", PRT_TECHNIQUE_SHADOWFIELD}};
  for (std::uint32_t i = 0; i < 5; ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    ASSERT_EQ(prt_scene_get_object(scene, i, &info), PRT_OK);
    EXPECT_EQ(info.name, std::string(kObjects[i].name));
    EXPECT_EQ(info.blob, std::string(kObjects[i].file));
    EXPECT_EQ(info.technique, expected.at(info.name));
    EXPECT_EQ(info.node, PRT_BLOB_SCNE_NO_NODE);
    EXPECT_EQ(prt_asset_techniques(info.asset), 1u << info.technique);
    uint32_t vpos = 0;
    prt_section_info section = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_find_section(info.asset, PRT_SECTION_VPOS, &vpos), PRT_OK);
    ASSERT_EQ(prt_asset_get_section_info(info.asset, vpos, &section), PRT_OK);
    EXPECT_EQ(info.vertex_count, section.element_count);
    for (int k = 0; k < 16; ++k) EXPECT_EQ(info.rest_transform[k], k % 5 == 0 ? 1.0f : 0.0f);
    EXPECT_EQ(info.moves,
              info.technique == PRT_TECHNIQUE_SHADOWFIELD || info.technique == PRT_TECHNIQUE_POSE)
        << info.name;
    EXPECT_EQ(info.poses, info.technique == PRT_TECHNIQUE_POSE) << info.name;
    std::uint32_t found = 99;
    EXPECT_EQ(prt_scene_find_object(scene, info.name, &found), PRT_OK);
    EXPECT_EQ(found, i);
  }
  std::uint32_t found = 0;
  EXPECT_EQ(prt_scene_find_object(scene, "nobody", &found), PRT_ERROR_NOT_FOUND);
  prt_scene_object_info info = prt::sized<prt_scene_object_info>();
  EXPECT_EQ(prt_scene_get_object(scene, 5, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_scene_object_radiance(scene, 0), nullptr) << "nothing shaded yet";
}

TEST_F(Scene, LoadsFromMemoryThroughTheGamesOwnFiles) {
  const std::vector<std::uint8_t> bytes = prt::format::write_scene_manifest(golden_objects());
  struct Files {
    int calls = 0;
  } files;
  prt_scene_desc desc = prt::sized<prt_scene_desc>();
  desc.load_blob = [](void* user, prt_context* context, const char* path, prt_validation validation,
                      prt_asset** out) {
    ++static_cast<Files*>(user)->calls;
    return prt_asset_load_file(context, (kGolden + "/" + path).c_str(), validation, out);
  };
  desc.load_blob_user = &files;
  ASSERT_EQ(prt_scene_load_memory(ctx.ctx, bytes.data(), bytes.size(), &desc, &scene), PRT_OK)
      << message();
  EXPECT_EQ(files.calls, 5);
  EXPECT_EQ(prt_scene_object_count(scene), 5u);
}

TEST_F(Scene, AnEmptySceneLoadsAndShades) {
  ASSERT_EQ(load(write_scene({}, "scene_empty")), PRT_OK) << message();
  EXPECT_EQ(prt_scene_object_count(scene), 0u);
  const prt_env_image env = sky.image();
  EXPECT_EQ(prt_scene_set_environment(scene, &env), PRT_OK);
  const prt_scene_frame f = frame();
  EXPECT_EQ(prt_scene_shade(scene, &f), PRT_OK);
}

// ---- Shading ---------------------------------------------------------------------------------

TEST_F(Scene, EachObjectShadesAsItsTechniqueDoes) {
  load_golden();
  const prt_env_image env = sky.image();
  ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK) << message();
  const prt_scene_frame f = frame();
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
  for (std::uint32_t i = 0; i < prt_scene_object_count(scene); ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    ASSERT_EQ(prt_scene_get_object(scene, i, &info), PRT_OK);
    std::vector<float> own;
    switch (info.technique) {
      case PRT_TECHNIQUE_SH:
        own = own_sh(info.asset, env);
        break;
      case PRT_TECHNIQUE_WAVELET:
        own = own_wavelet(info.asset, env);
        break;
      case PRT_TECHNIQUE_CLOTH:
        own = own_cloth(ctx.ctx, info.asset, env, eye);
        break;
      case PRT_TECHNIQUE_SHADOWFIELD:
        own = own_shadowfield(ctx.ctx, info.asset, env, eye);
        break;
      case PRT_TECHNIQUE_POSE: {
        auto pose = prt::sized<prt_pose_info>();
        ASSERT_EQ(prt_pose_get_info(info.asset, &pose), PRT_OK);
        std::vector<float> bind(4 * std::size_t(pose.joint_count));
        ASSERT_EQ(prt_pose_bind_pose(info.asset, bind.data(), nullptr, nullptr), PRT_OK);
        own = own_pose(info.asset, env, bind, nullptr);
        break;
      }
      default:
        FAIL() << "unexpected technique " << info.technique;
    }
    const std::vector<float> got = radiance(i);
    ASSERT_EQ(got.size(), own.size()) << info.name;
    EXPECT_GT(max_abs(own), 0.0f) << info.name << " is lit";
    EXPECT_EQ(got, own) << info.name;
  }
}

TEST_F(Scene, RadianceIsLinearInTheLight) {
  load_golden();
  const Sky brighter(2.0f);
  const prt_scene_frame f = frame();
  std::vector<std::vector<float>> once, twice;
  const Sky* skies[] = {&sky, &brighter};
  for (const Sky* s : skies) {
    const prt_env_image env = s->image();
    ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK) << message();
    ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
    auto& into = s == &sky ? once : twice;
    for (std::uint32_t i = 0; i < prt_scene_object_count(scene); ++i) into.push_back(radiance(i));
  }
  for (std::size_t i = 0; i < once.size(); ++i) {
    const float scale = max_abs(once[i]);
    ASSERT_GT(scale, 0.0f);
    for (std::size_t k = 0; k < once[i].size(); ++k)
      EXPECT_NEAR(twice[i][k], 2.0f * once[i][k], 1e-5f * scale)
          << "object " << i << " [" << k << "]";
  }
}

// A rotation by `degrees` about +Y, row-major.
std::array<float, 9> turn_y(double degrees) {
  const double a = degrees * M_PI / 180.0;
  const float c = float(std::cos(a)), s = float(std::sin(a));
  return {c, 0.0f, s, 0.0f, 1.0f, 0.0f, -s, 0.0f, c};
}

TEST_F(Scene, ATurnedObjectSeesTheLightAsTheUnturnedOneSeesItTurnedBack) {
  load_golden();
  std::uint32_t sf = 0;
  ASSERT_EQ(prt_scene_find_object(scene, "shadowfield_quad", &sf), PRT_OK);
  const std::array<float, 9> turn = turn_y(90.0), back = turn_y(-90.0);
  prt_scene_placement placement = prt::sized<prt_scene_placement>();
  std::copy(turn.begin(), turn.end(), placement.rotation);
  placement.scale = 1.0f;
  // Turned about +Y through the origin, and the eye turned with it: the object sees the world
  // turned back, so the unturned object under the light turned back (eye turned back) matches.
  const prt_env_image env = sky.image();
  ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK);
  ASSERT_EQ(prt_scene_set_placement(scene, sf, &placement), PRT_OK) << message();
  prt_scene_frame f = frame();
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
  const std::vector<float> turned = radiance(sf);
  prt_scene_placement rest = prt::sized<prt_scene_placement>();
  rest.rotation[0] = rest.rotation[4] = rest.rotation[8] = 1.0f;
  rest.scale = 1.0f;
  ASSERT_EQ(prt_scene_set_placement(scene, sf, &rest), PRT_OK);
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK);
  ASSERT_NE(radiance(sf), turned) << "the turn changes what the object sees";

  const prt_env_image turned_back = sky.image(back.data());
  ASSERT_EQ(prt_scene_set_environment(scene, &turned_back), PRT_OK);
  for (int i = 0; i < 3; ++i)
    f.eye[i] = back[3 * i] * eye[0] + back[3 * i + 1] * eye[1] + back[3 * i + 2] * eye[2];
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK);
  const std::vector<float> unturned = radiance(sf);
  ASSERT_EQ(turned.size(), unturned.size());
  // The turned object's vertices are where the unturned ones are, turned; each keeps its index.
  const float scale = max_abs(unturned);
  float worst = 0.0f;
  for (std::size_t k = 0; k < turned.size(); ++k)
    worst = std::max(worst, std::fabs(turned[k] - unturned[k]) / scale);
  std::printf("turned against light turned back: largest difference %.2e of the brightest\n",
              double(worst));
  // Both turn SH coefficients (the instance's light, the projection's); float rounding apart,
  // they agree.
  for (std::size_t k = 0; k < turned.size(); ++k)
    EXPECT_NEAR(turned[k], unturned[k], 1e-6f * scale) << k;
}

TEST_F(Scene, APosedCharacterShadesAsPoseDoesAtThatPoseAndTurn) {
  load_golden();
  std::uint32_t character = 0;
  ASSERT_EQ(prt_scene_find_object(scene, "pose_hinge", &character), PRT_OK);
  prt_scene_object_info info = prt::sized<prt_scene_object_info>();
  ASSERT_EQ(prt_scene_get_object(scene, character, &info), PRT_OK);
  auto pose_info = prt::sized<prt_pose_info>();
  ASSERT_EQ(prt_pose_get_info(info.asset, &pose_info), PRT_OK);
  std::vector<float> rotations(4 * std::size_t(pose_info.joint_count));
  ASSERT_EQ(prt_pose_bind_pose(info.asset, rotations.data(), nullptr, nullptr), PRT_OK);
  // Turn the last joint by an eighth of a turn about an axis off every coordinate axis, so that
  // whatever direction the model's pose coordinates follow, the turn has a part along it.
  float* q = &rotations[rotations.size() - 4];
  const float half = float(M_PI / 8), norm = std::sqrt(14.0f);
  const float turn_q[4] = {std::sin(half) / norm, 2 * std::sin(half) / norm,
                           3 * std::sin(half) / norm, std::cos(half)};
  const float w = q[3], x = q[0], y = q[1], z = q[2];
  q[0] = turn_q[3] * x + turn_q[0] * w + turn_q[1] * z - turn_q[2] * y;
  q[1] = turn_q[3] * y + turn_q[1] * w + turn_q[2] * x - turn_q[0] * z;
  q[2] = turn_q[3] * z + turn_q[2] * w + turn_q[0] * y - turn_q[1] * x;
  q[3] = turn_q[3] * w - turn_q[0] * x - turn_q[1] * y - turn_q[2] * z;
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  ASSERT_EQ(prt_scene_set_pose(scene, character, &pose), PRT_OK) << message();
  const std::array<float, 9> turn = turn_y(30.0);
  prt_scene_placement placement = prt::sized<prt_scene_placement>();
  std::copy(turn.begin(), turn.end(), placement.rotation);
  placement.translation[0] = 5.0f;
  placement.scale = 2.0f;
  ASSERT_EQ(prt_scene_set_placement(scene, character, &placement), PRT_OK) << message();
  const prt_env_image env = sky.image();
  ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK);
  const prt_scene_frame f = frame();
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
  const std::vector<float> own = own_pose(info.asset, env, rotations, turn.data());
  EXPECT_EQ(radiance(character), own);
  std::vector<float> bind(rotations.size());
  ASSERT_EQ(prt_pose_bind_pose(info.asset, bind.data(), nullptr, nullptr), PRT_OK);
  EXPECT_NE(radiance(character), own_pose(info.asset, env, bind, turn.data()))
      << "the pose changes the shading";
}

TEST_F(Scene, WorkersGiveTheOneThreadResultBitForBit) {
  load_golden();
  const prt_env_image env = sky.image();
  ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK);
  prt_scene_frame f = frame(PRT_BACKEND_AUTO);
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
  std::vector<std::vector<float>> alone;
  for (std::uint32_t i = 0; i < prt_scene_object_count(scene); ++i) alone.push_back(radiance(i));
  prt_workers_desc desc = prt::sized<prt_workers_desc>();
  desc.thread_count = 3;
  prt_workers* workers = nullptr;
  ASSERT_EQ(prt_workers_create(ctx.ctx, &desc, &workers), PRT_OK);
  f.workers = workers;
  ASSERT_EQ(prt_scene_shade(scene, &f), PRT_OK) << message();
  for (std::uint32_t i = 0; i < prt_scene_object_count(scene); ++i)
    EXPECT_EQ(radiance(i), alone[i]) << "object " << i;
  prt_workers_destroy(workers);
}

// ---- Refusals --------------------------------------------------------------------------------

TEST_F(Scene, FrameCallsRefuseWhatDoesNotApply) {
  load_golden();
  const prt_scene_frame f = frame();
  EXPECT_EQ(prt_scene_shade(scene, &f), PRT_ERROR_INVALID_OPERATION);
  EXPECT_NE(message().find("prt_scene_set_environment"), std::string::npos) << message();
  const prt_env_image env = sky.image();
  ASSERT_EQ(prt_scene_set_environment(scene, &env), PRT_OK);
  const prt_scene_frame gl = frame(PRT_BACKEND_GL);
  EXPECT_EQ(prt_scene_shade(scene, &gl), PRT_ERROR_UNSUPPORTED_BACKEND);

  std::uint32_t sh = 0, sf = 0;
  ASSERT_EQ(prt_scene_find_object(scene, "sh_quad", &sh), PRT_OK);
  ASSERT_EQ(prt_scene_find_object(scene, "shadowfield_quad", &sf), PRT_OK);
  prt_scene_placement placement = prt::sized<prt_scene_placement>();
  placement.rotation[0] = placement.rotation[4] = placement.rotation[8] = 1.0f;
  placement.scale = 1.0f;
  EXPECT_EQ(prt_scene_set_placement(scene, sh, &placement), PRT_ERROR_INVALID_OPERATION);
  EXPECT_NE(message().find("'sh_quad'"), std::string::npos) << message();
  EXPECT_EQ(prt_scene_set_placement(scene, 7, &placement), PRT_ERROR_INVALID_ARGUMENT);
  placement.rotation[0] = -1.0f;  // a reflection
  EXPECT_EQ(prt_scene_set_placement(scene, sf, &placement), PRT_ERROR_INVALID_ARGUMENT);
  placement.rotation[0] = 1.0f;
  placement.scale = 0.0f;
  EXPECT_EQ(prt_scene_set_placement(scene, sf, &placement), PRT_ERROR_INVALID_ARGUMENT);

  const float rotation[4] = {0, 0, 0, 1};
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotation;
  EXPECT_EQ(prt_scene_set_pose(scene, sh, &pose), PRT_ERROR_INVALID_OPERATION);
  pose.joint_rotations = nullptr;
  EXPECT_EQ(prt_scene_set_pose(scene, sh, &pose), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_scene_set_environment(scene, nullptr), PRT_ERROR_INVALID_ARGUMENT);
}

// Loads must fail with `result` and a message holding each of `words`.
void expect_load_fails(Context& ctx, const fs::path& path, prt_result result,
                       const std::vector<std::string>& words) {
  prt_scene* scene = nullptr;
  EXPECT_EQ(prt_scene_load_file(ctx.ctx, path.c_str(), nullptr, &scene), result) << path;
  EXPECT_EQ(scene, nullptr);
  const std::string message = prt_context_last_message(ctx.ctx);
  for (const std::string& word : words)
    EXPECT_NE(message.find(word), std::string::npos) << "'" << word << "' in: " << message;
}

TEST_F(Scene, ALoadThatFailsNamesTheObjectAndItsBlob) {
  std::vector<prt::format::SceneManifestObject> objects = golden_objects();
  objects.push_back(manifest_object("lost", "blobs/lost.prtk", PRT_SECTION_SHTR));
  expect_load_fails(ctx, write_scene(objects, "scene_missing"), PRT_ERROR_IO,
                    {"'lost'", "blobs/lost.prtk"});

  objects = golden_objects();
  objects[1].blob = "sh_quad.prtk";  // a wavelet object whose blob has no WVLT section
  expect_load_fails(ctx, write_scene(objects, "scene_wrong_blob"), PRT_ERROR_CORRUPT,
                    {"'wavelet_quad'", "WVLT"});

  objects = golden_objects();
  objects[0].technique_tag = PRT_TAG('N', 'E', 'W', 'T');  // a technique of a later runtime
  expect_load_fails(ctx, write_scene(objects, "scene_new_technique"), PRT_ERROR_UNSUPPORTED_FEATURE,
                    {"'sh_quad'", "NEWT"});

  expect_load_fails(ctx, fs::path(kGolden) / "sh_quad.prtk", PRT_ERROR_CORRUPT,
                    {"not a scene manifest"});
  expect_load_fails(ctx, fs::path(kGolden) / "no_such_scene.prts", PRT_ERROR_IO,
                    {"no_such_scene.prts"});
}

// Quick validation skips content checks, but a manifest's rules hold at both levels: a path that
// leaves the manifest's folder is refused before any blob is read.
TEST_F(Scene, AQuickLoadStillRefusesAPathOutOfTheFolder) {
  std::vector<prt::format::SceneManifestObject> objects = golden_objects();
  objects[0].blob = "xx/sh_quad.prtk";
  std::vector<std::uint8_t> bytes = prt::format::write_scene_manifest(objects);
  const std::string from = "xx/sh_quad.prtk", to = "../sh_quad.prtk";
  const auto at = std::search(bytes.begin(), bytes.end(), from.begin(), from.end());
  ASSERT_NE(at, bytes.end());
  std::copy(to.begin(), to.end(), at);  // the checksums no longer match: quick does not look
  int reads = 0;
  prt_scene_desc desc = prt::sized<prt_scene_desc>();
  desc.validation = PRT_VALIDATE_QUICK;
  desc.load_blob = [](void* user, prt_context* context, const char* path, prt_validation v,
                      prt_asset** out) {
    ++*static_cast<int*>(user);
    return prt_asset_load_file(context, (kGolden + "/" + path).c_str(), v, out);
  };
  desc.load_blob_user = &reads;
  EXPECT_EQ(prt_scene_load_memory(ctx.ctx, bytes.data(), bytes.size(), &desc, &scene),
            PRT_ERROR_CORRUPT);
  EXPECT_EQ(scene, nullptr);
  EXPECT_EQ(reads, 0);
  EXPECT_NE(message().find(".."), std::string::npos) << message();
  desc.validation = PRT_VALIDATE_FULL;
  EXPECT_EQ(prt_scene_load_memory(ctx.ctx, bytes.data(), bytes.size(), &desc, &scene),
            PRT_ERROR_CHECKSUM_MISMATCH);
}

TEST_F(Scene, EveryAllocationFailureIsReportedAndFreesEverything) {
  const fs::path path = write_scene(golden_objects(), "scene_allocations");
  expect_every_allocation_failure_reported(
      [&](prt_context* context) {
        prt_scene* s = nullptr;
        prt_result r = prt_scene_load_file(context, path.c_str(), nullptr, &s);
        if (r != PRT_OK) return r;
        const prt_env_image env = sky.image();
        r = prt_scene_set_environment(s, &env);
        const prt_scene_frame f = frame();
        if (r == PRT_OK) r = prt_scene_shade(s, &f);
        prt_scene_destroy(s);
        return r;
      },
      "load, light and shade a scene");
}

}  // namespace
