// SPDX-License-Identifier: MIT
// Technique `pose` in `prt-bake scene` on RiggedSimple (a bent cylinder, 2 joints, 1 clip): fit
// says yes for the skinned node and why not for a static one or one no clip moves; every rung of
// the ladder is a valid bake; the measurement falls as the ladder climbs, and it sees the light's
// frame (the same blob on the character turned a quarter turn, i.e. lit from the side in its
// model frame, measures far worse) and agrees with the sh technique's error at the same order on
// the bind pose; and the scene command picks pose for the character within its budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/options.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/technique.hpp"
#include "support/checked_blob.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

constexpr const char* kCharacter = "characters/RiggedSimple/RiggedSimple.gltf";

Context two_threads() {
  Context ctx;
  ctx.threads = 2;
  return ctx;
}

const Technique& pose() {
  const Technique* technique = find_technique("pose");
  if (!technique) throw std::runtime_error("no technique pose");
  return *technique;
}

// The object whose node a skin places.
const SceneObject& skinned_object(const std::vector<SceneObject>& objects, const Scene& scene) {
  for (const SceneObject& object : objects) {
    if (node_kind(scene, object.node).skinned) return object;
  }
  throw std::runtime_error("no skinned object");
}

// The character with its root node turned a quarter turn about +X: the skin's joints and so the
// posed mesh turn with it.
Scene turned_character(const Scene& object) {
  Scene turned = object;
  int root = object.skins.front().joints.front();
  while (turned.nodes[std::size_t(root)].parent >= 0) root = turned.nodes[std::size_t(root)].parent;
  Node& node = turned.nodes[std::size_t(root)];
  const glm::quat quarter = glm::angleAxis(glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  node.rotation = quarter * node.rotation;
  node.translation = quarter * node.translation;
  node.local = glm::mat4_cast(quarter) * node.local;
  return turned;
}

class PoseScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string file = prt_test::shared_asset(kCharacter);
    if (file.empty()) return;
    file_ = new std::string(file);
    scene_ = new Scene(import_scene(file, two_threads()));
    objects_ = new std::vector<SceneObject>(scene_objects(*scene_));
    sky_ = new io::EnvMap(make_demo_sky());
  }
  static void TearDownTestSuite() {
    delete file_;
    delete scene_;
    delete objects_;
    delete sky_;
    file_ = nullptr;
    scene_ = nullptr;
    objects_ = nullptr;
    sky_ = nullptr;
  }
  void SetUp() override {
    if (!scene_) GTEST_SKIP() << "shared assets not found";
  }

  static ObjectMeasureInput measure_input(const Scene& object, int node) {
    ObjectMeasureInput input;
    input.scene = scene_;
    input.object = &object;
    input.node = node;
    input.lights = {sky_};
    input.bounces = 0;
    input.ref_spp = 1024;
    input.probe_vertices = 96;
    return input;
  }

  static std::string* file_;
  static Scene* scene_;
  static std::vector<SceneObject>* objects_;
  static io::EnvMap* sky_;
};
std::string* PoseScene::file_ = nullptr;
Scene* PoseScene::scene_ = nullptr;
std::vector<SceneObject>* PoseScene::objects_ = nullptr;
io::EnvMap* PoseScene::sky_ = nullptr;

TEST_F(PoseScene, FitsTheSkinnedAnimatedNodeOnly) {
  const SceneObject& character = skinned_object(*objects_, *scene_);
  const ObjectFit fit = pose().fit(*scene_, character.node);
  EXPECT_TRUE(fit.suits) << fit.reason;

  // A clip that moves only the mesh's own node (no joint, no node above one) does not pose it.
  Scene still = *scene_;
  for (Animation& clip : still.animations) {
    for (AnimationChannel& channel : clip.channels) channel.node = character.node;
  }
  ASSERT_EQ(still.nodes[std::size_t(character.node)].children.size(), 0u);
  const ObjectFit unmoved = pose().fit(still, character.node);
  EXPECT_FALSE(unmoved.suits);
  EXPECT_EQ(unmoved.reason, "skinned but no clip moves it");
  still.animations.clear();
  EXPECT_FALSE(pose().fit(still, character.node).suits);

  Scene box;
  box.nodes.resize(1);
  box.nodes[0].mesh = 0;
  box.meshes.push_back(make_box_mesh(-1, glm::vec3(0.0f), 0.5f, 0.0f, 2));
  box.meshes[0].node = 0;
  const ObjectFit static_fit = pose().fit(box, 0);
  EXPECT_FALSE(static_fit.suits);
  EXPECT_EQ(static_fit.reason, "not skinned");
}

// A scene bake keys its cache on the clips that move the object: a clip that moves another node
// must not change the blob.
TEST_F(PoseScene, AClipThatMovesNothingOfTheCharacterLeavesTheBlobAsItWas) {
  const Context ctx = two_threads();
  const SceneObject& character = skinned_object(*objects_, *scene_);
  Scene with_other_clip = character.scene;
  ASSERT_FALSE(with_other_clip.animations.empty());
  Animation other = with_other_clip.animations.front();
  other.name = "the mesh node alone";
  for (AnimationChannel& channel : other.channels) channel.node = character.node;
  with_other_clip.animations.push_back(other);
  const Rung cheapest = pose().ladder(0).front();
  EXPECT_EQ(prt_test::checked_blob("pose", cheapest.args, with_other_clip, "RiggedSimple", ctx),
            prt_test::checked_blob("pose", cheapest.args, character.scene, "RiggedSimple", ctx));
}

TEST_F(PoseScene, EveryRungIsAValidBake) {
  for (int bounces : {0, 1, 2}) {
    const std::vector<Rung> ladder = pose().ladder(bounces);
    EXPECT_GE(ladder.size(), 4u);
    EXPECT_LE(ladder.size(), 8u);
    for (const Rung& rung : ladder) {
      const std::unique_ptr<TechniqueBake> bake = pose().make_bake();
      EXPECT_NO_THROW(apply_option_args(bake->options(), rung.args));
      const bool interreflected =
          std::find(rung.args.begin(), rung.args.end(), "interreflected") != rung.args.end();
      EXPECT_EQ(interreflected, bounces > 0);
    }
  }
}

// The sh technique's error at `order` on the character at its bind pose, as a static object
// (no skin, no learned model, the static objects' measurement).
double sh_error_at_bind_pose(const ObjectMeasureInput& input, std::uint32_t order,
                             const Context& ctx) {
  const Technique* sh = find_technique("sh");
  if (!sh) throw std::runtime_error("no technique sh");
  std::unique_ptr<TechniqueBake> bake = sh->make_bake();
  apply_option_args(bake->options(), {"--order", std::to_string(order), "--bits", "16", "--rays",
                                      "1024", "--transfer", "shadowed"});
  BakeInput bake_input;
  bake_input.scene = "RiggedSimple";
  bake->bake(*input.object, bake_input, ctx);
  bake->quantize();
  const std::vector<std::uint8_t> blob = bake->write(*input.object, bake_input);
  return sh->measure()(input)->measure(*sh, blob, ctx).error;
}

std::uint32_t order_of(const Rung& rung) {
  const auto at = std::find(rung.args.begin(), rung.args.end(), "--order");
  if (at == rung.args.end() || at + 1 == rung.args.end())
    throw std::runtime_error("a rung without --order");
  return std::uint32_t(std::stoul(*(at + 1)));
}

// Each rung's blob measured as the pipeline does; the bottom and top rungs against the sh
// technique at their order; the top rung also on the turned character.
TEST_F(PoseScene, TheErrorFallsUpTheLadderAsTheShOrderPredictsAndSeesTheLightsFrame) {
  const Context ctx = two_threads();
  const SceneObject& character = skinned_object(*objects_, *scene_);
  const ObjectMeasureInput input = measure_input(character.scene, character.node);
  const std::unique_ptr<ObjectMeasure> measure = pose().measure()(input);
  const std::vector<Rung> ladder = pose().ladder(0);
  std::vector<Measurement> errors;
  std::vector<std::size_t> bytes;
  std::vector<std::uint8_t> top;
  for (const Rung& rung : ladder) {
    top = prt_test::checked_blob("pose", rung.args, character.scene, "RiggedSimple", ctx);
    errors.push_back(measure->measure(pose(), top, ctx));
    bytes.push_back(top.size());
    std::printf("rung %zu: %zu bytes, error %.4f (reference noise %.4f)\n", errors.size(),
                bytes.back(), errors.back().error, errors.back().ref_noise);
  }
  for (std::size_t k = 1; k < bytes.size(); ++k) EXPECT_GE(bytes[k], bytes[k - 1]) << k;
  EXPECT_LT(errors.back().error, 0.8 * errors.front().error);

  // The cylinder hardly shadows itself, so what the order cuts from the light is most of the
  // error: the sh bake of the bind pose, measured without skin or model, gives the figure. The
  // two differ by a few percent of themselves here; allowed: 20 %.
  for (const std::size_t k : {std::size_t(0), ladder.size() - 1}) {
    const double sh = sh_error_at_bind_pose(input, order_of(ladder[k]), ctx);
    std::printf("order %u: pose %.4f, sh at the bind pose %.4f\n", order_of(ladder[k]),
                errors[k].error, sh);
    EXPECT_NEAR(errors[k].error, sh, 0.2 * sh) << "rung " << k + 1;
  }

  // The blob on the character turned a quarter turn: the runtime still lights it as if upright.
  const Scene turned = turned_character(character.scene);
  const std::unique_ptr<ObjectMeasure> turned_measure =
      pose().measure()(measure_input(turned, character.node));
  const Measurement sideways = turned_measure->measure(pose(), top, ctx);
  std::printf("top rung on the turned character: error %.4f\n", sideways.error);
  EXPECT_GT(sideways.error, 5.0 * errors.back().error);
}

TEST_F(PoseScene, TheSceneCommandPicksPoseWithinTheBudget) {
  const prt_test::TempDir dir("pose_scene");
  SceneBakeSettings settings;
  settings.scene = *file_;
  settings.out_dir = dir.file("out");
  // Above what the top rung measures, below the bottom rung's: the command must climb.
  settings.error_budget = 0.04;
  settings.bounces = 0;
  settings.ref_spp = 512;
  settings.probe_vertices = 96;
  const SceneBakeSummary summary = run_scene_bake(settings, two_threads());
  EXPECT_EQ(summary.baked, 1u);
  EXPECT_EQ(summary.over_budget, 0u);
  std::ifstream in(dir.file("out/report.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["objects"].size(), 1u);
  const nlohmann::json& object = report["objects"][0];
  EXPECT_EQ(object["technique"], "pose");
  EXPECT_LE(object["error"].get<double>(), settings.error_budget);
  EXPECT_TRUE(object["meets_budget"].get<bool>());
  ASSERT_GE(object["candidates"].size(), 2u);
  EXPECT_GT(object["candidates"][0]["error"].get<double>(), settings.error_budget);
  std::printf("scene bake: %s, error %.4f, %zu bytes\n", object["settings"].dump().c_str(),
              object["error"].get<double>(), object["bytes"].get<std::size_t>());
}

}  // namespace
}  // namespace prt::bake
