// SPDX-License-Identifier: MIT
#include "scene_view.hpp"

#include <imgui.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <utility>

#include "blob_scene.hpp"
#include "env_image.hpp"
#include "path_names.hpp"
#include "prt/io/envmap.hpp"

namespace prt::view {
namespace {

std::string last_message(prt_context* context, prt_result result) {
  const char* message = prt_context_last_message(context);
  return message && *message ? std::string(message) : std::string(prt_result_string(result));
}

std::string technique_name(prt_technique technique) {
  prt_technique_info info = prt::sized<prt_technique_info>();
  return prt_technique_get_info(technique, &info) == PRT_OK ? info.name : "?";
}

}  // namespace

bool is_scene_manifest(const std::string& path) {
  if (has_extension(path, ".prts")) return true;
  // Any other name: a manifest is a blob, so load it (quick validation: its table, no section
  // decoded) and look for the SCNE section.
  auto [context, made] = prt::create_context();
  if (made != PRT_OK) return false;
  auto [asset, loaded] = prt::load_asset_file(context.get(), path.c_str(), PRT_VALIDATE_QUICK);
  if (loaded != PRT_OK) return false;
  std::uint32_t index = 0;
  return prt_asset_find_section(asset.get(), PRT_SECTION_SCNE, &index) == PRT_OK;
}

// One loaded scene. The mesh holds every object's vertices back to back (object i's from
// objects[i].first), so the renderer draws the scene as one mesh: views of one viewport each
// draw the background first, so they cannot be stacked.
struct SceneView::Loaded {
  struct Object {
    std::string name, blob, technique;
    std::uint32_t vertices = 0, triangles = 0, first = 0;
    bool moves = false, poses = false;
  };

  prt_context* context = nullptr;
  prt_scene* scene = nullptr;
  std::vector<Object> objects;
  std::uint32_t vertex_count = 0, triangle_count = 0;
  std::unique_ptr<prt::sample::GpuMesh> mesh;

  Loaded() = default;
  Loaded(const Loaded&) = delete;
  Loaded& operator=(const Loaded&) = delete;
  ~Loaded() {
    prt_scene_destroy(scene);
    prt_context_destroy(context);
  }
};

SceneView::SceneView(std::string path, std::string backend_option)
    : path_(std::move(path)), backend_option_(std::move(backend_option)) {}

SceneView::~SceneView() = default;

std::unique_ptr<SceneView::Loaded> SceneView::load(const std::string& path) const {
  auto loaded = std::make_unique<Loaded>();
  // As BlobScene's: messages recorded, not printed; PRT_BACKEND / PRT_SIMD_ISA may lower the
  // backends, as --backend cannot.
  prt_context_desc context_desc = prt::sized<prt_context_desc>();
  context_desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&context_desc, &loaded->context) != PRT_OK)
    throw ViewerError("cannot create a prtkit context");
  // Full validation, as the blob mode loads: the drawing relies on the triangles' indices.
  prt_scene_desc desc = prt::sized<prt_scene_desc>();
  desc.validation = PRT_VALIDATE_FULL;
  const prt_result result =
      prt_scene_load_file(loaded->context, path.c_str(), &desc, &loaded->scene);
  if (result != PRT_OK) throw ViewerError(path + ": " + last_message(loaded->context, result));

  const std::uint32_t count = prt_scene_object_count(loaded->scene);
  if (count == 0) throw ViewerError(path + ": the scene has no objects");
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  for (std::uint32_t i = 0; i < count; ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    const prt_result got = prt_scene_get_object(loaded->scene, i, &info);
    if (got != PRT_OK)
      throw ViewerError(path + ": prt_scene_get_object " + std::to_string(i) +
                        " failed: " + prt_result_string(got));
    Loaded::Object object;
    object.name = info.name ? info.name : "";
    object.blob = info.blob ? info.blob : "";
    object.technique = technique_name(info.technique);
    object.moves = info.moves != 0;
    object.poses = info.poses != 0;
    const std::string where = path + ": object " + object.name + " (" + object.blob + ")";
    const BlobMesh mesh = read_blob_mesh(info.asset, where);
    if (mesh.vertex_count != info.vertex_count)
      throw ViewerError(where + ": VPOS has " + std::to_string(mesh.vertex_count) +
                        " vertices but the scene shades " + std::to_string(info.vertex_count));
    if (std::uint64_t(loaded->vertex_count) + mesh.vertex_count >
        std::numeric_limits<std::uint32_t>::max())
      throw ViewerError(path + ": more vertices than one mesh can index");
    object.first = loaded->vertex_count;
    object.vertices = mesh.vertex_count;
    object.triangles = mesh.triangle_count;
    // Blobs are baked in world space at rest, where the scene shades its static objects: their
    // positions are drawn as they are.
    positions.insert(positions.end(), mesh.positions, mesh.positions + 3u * mesh.vertex_count);
    for (std::size_t k = 0; k < 3u * mesh.triangle_count; ++k)
      indices.push_back(object.first + mesh.indices[k]);
    loaded->vertex_count += mesh.vertex_count;
    loaded->triangle_count += mesh.triangle_count;
    loaded->objects.push_back(std::move(object));
  }
  loaded->mesh = std::make_unique<prt::sample::GpuMesh>(positions.data(), loaded->vertex_count,
                                                        indices.data(), loaded->triangle_count);
  return loaded;
}

void SceneView::show(prt::sample::Sample& sample, std::unique_ptr<Loaded> loaded) {
  release_gl();
  loaded_ = std::move(loaded);
  radiance_.assign(3u * loaded_->vertex_count, 0.0f);
  light_version_ = ~0ull;  // a new scene has no light yet
  sample.set_scene_bounds(loaded_->mesh->lo(), loaded_->mesh->hi(), true);
  sample.meter_exposure();
  std::printf("%s: scene of %zu objects, %u vertices, %u triangles (prt_scene_load_file)\n",
              path_.c_str(), loaded_->objects.size(), loaded_->vertex_count,
              loaded_->triangle_count);
  for (const Loaded::Object& object : loaded_->objects)
    std::printf("  %s: %s, %u vertices, %u triangles, %s (%s)\n", object.name.c_str(),
                object.technique.c_str(), object.vertices, object.triangles,
                object.poses   ? "a character, at its bind pose"
                : object.moves ? "moving, at its rest placement"
                               : "static, shaded in place",
                object.blob.c_str());
}

void SceneView::start(prt::sample::Sample& sample) {
  show(sample, load(path_));
  previous_ = std::chrono::steady_clock::now();
}

void SceneView::open(prt::sample::Sample& sample, const std::string& path) {
  std::unique_ptr<Loaded> loaded = load(path);
  path_ = path;
  show(sample, std::move(loaded));
}

void SceneView::release_gl() {
  if (loaded_) loaded_->mesh.reset();
}

// The command line's --backend on the first frame, then the overlay's whenever it changes. gl
// (the command line's or the overlay's) shades with AUTO: prt_scene_shade runs on the CPU-side
// backends only, each technique's GL shading being a shader of its own.
void SceneView::choose_backend(prt::sample::Sample& sample) {
  const prt::sample::Backend now = sample.backend();
  if (backend_chosen_ && now == sample_backend_) return;
  const std::string wanted = backend_chosen_ ? prt::sample::backend_name(now) : backend_option_;
  backend_chosen_ = true;
  sample_backend_ = now;
  backend_ = wanted == "cpu"    ? PRT_BACKEND_CPU
             : wanted == "simd" ? PRT_BACKEND_SIMD
                                : PRT_BACKEND_AUTO;
  if (wanted == "gl" && !told_gl_) {
    std::printf(
        "prt-viewer: note: a scene shades on the CPU-side backends (prt_scene_shade); with gl it "
        "shades with auto, each technique on its best one, and the GPU draws\n");
    told_gl_ = true;
  }
}

// Work of a light change, not of every frame: the map is made an environment image once (cross
// and probe maps are resampled to cube faces then), and a turn only sets its rotation.
void SceneView::set_environment(prt::sample::Sample& sample) {
  prt::sample::Environments& envs = sample.environments();
  if (light_version_ == envs.light_version()) return;
  const prt::io::EnvMap& map = envs.current();
  if (env_map_ != &map) {
    env_ = environment_image(map, nullptr, &faces_);
    env_map_ = &map;
  }
  float rotation[9];
  prt::io::rotation_about_y_row_major(envs.rotation_degrees(), rotation);
  prt_env_image env = env_;
  env.rotation = rotation;
  const prt_result result = prt_scene_set_environment(loaded_->scene, &env);
  if (result != PRT_OK)
    throw ViewerError(envs.current_path() + ": prt_scene_set_environment failed: " +
                      last_message(loaded_->context, result));
  if (light_version_ == ~0ull)
    std::printf(
        "%s: %dx%d %s map, rotated %g deg about +Y, the light of every technique in the "
        "scene (prt_scene_set_environment, %s)\n",
        envs.current_path().c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), envs.rotation_degrees(),
        environment_image_layout(map).c_str());
  light_version_ = envs.light_version();
}

void SceneView::shade(prt::sample::Sample& sample) {
  prt_scene_frame frame = prt::sized<prt_scene_frame>();
  const glm::vec3 eye = sample.camera().camera(1.0f).eye;  // the aspect does not move the eye
  std::copy(&eye.x, &eye.x + 3, frame.eye);
  frame.workers = nullptr;  // the viewer keeps no worker pool: the calling thread shades
  const auto run = [&] {
    frame.backend = backend_;
    const auto start = std::chrono::steady_clock::now();
    const prt_result result =
        sample.time_shading([&] { return prt_scene_shade(loaded_->scene, &frame); });
    shade_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  prt_result result = run();
  if (result == PRT_ERROR_UNSUPPORTED_BACKEND && backend_ != PRT_BACKEND_AUTO) {
    // A technique without the backend asked for: said once, then each shades on its best.
    sample.report(path_ + ": " + last_message(loaded_->context, result) + "; shading with auto");
    backend_ = PRT_BACKEND_AUTO;
    result = run();
  }
  if (result != PRT_OK)
    throw ViewerError(path_ + ": prt_scene_shade failed on backend " + prt_backend_name(backend_) +
                      ": " + last_message(loaded_->context, result));
  for (std::size_t i = 0; i < loaded_->objects.size(); ++i) {
    const Loaded::Object& object = loaded_->objects[i];
    const float* rgb = prt_scene_object_radiance(loaded_->scene, std::uint32_t(i));
    if (!rgb) throw ViewerError(path_ + ": object " + object.name + " has no radiance");
    std::copy(rgb, rgb + 3u * object.vertices, radiance_.begin() + 3u * object.first);
  }
  loaded_->mesh->upload_colours(radiance_.data());
}

std::vector<prt::sample::View> SceneView::frame(prt::sample::Sample& sample) {
  const auto now = std::chrono::steady_clock::now();
  frame_ms_ = std::chrono::duration<double, std::milli>(now - previous_).count();
  previous_ = now;
  choose_backend(sample);
  set_environment(sample);
  shade(sample);
  char line[256];
  // Short, so that the overlay's width holds it; the panel says more.
  std::snprintf(line, sizeof line, "a scene: %s, %zu objects", file_name(path_).c_str(),
                loaded_->objects.size());
  sample.overlay_line(line);
  prt::sample::View view;
  view.mesh = loaded_->mesh.get();
  view.colour_buffer = loaded_->mesh->own_colours();
  return {view};
}

void SceneView::panel(prt::sample::Sample&) {
  if (!loaded_) return;
  ImGui::Text("scene: %s (%zu objects, %u vertices)", file_name(path_).c_str(),
              loaded_->objects.size(), loaded_->vertex_count);
  ImGui::Text("frame %.2f ms, prt_scene_shade %.3f ms (%s)", frame_ms_, shade_ms_,
              prt_backend_name(backend_));
  // A scroll region of at most a dozen rows, so a large scene leaves the panel usable.
  const float rows = float(std::min<std::size_t>(loaded_->objects.size() + 1, 12));
  const ImVec2 size(0.0f, rows * ImGui::GetTextLineHeightWithSpacing() + 4.0f);
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
  if (ImGui::BeginTable("objects", 3, flags, size)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("object");
    ImGui::TableSetupColumn("technique");
    ImGui::TableSetupColumn("vertices");
    ImGui::TableHeadersRow();
    for (const Loaded::Object& object : loaded_->objects) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(object.name.c_str());
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", object.blob.c_str());
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(object.technique.c_str());
      ImGui::TableSetColumnIndex(2);
      ImGui::Text("%u", object.vertices);
    }
    ImGui::EndTable();
  }
}

}  // namespace prt::view
