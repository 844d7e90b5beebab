// SPDX-License-Identifier: MIT
// Scene::occluders: meshes that block light but have no vertices of their own. A vertex lit
// through an occluder gets exactly what it gets when the occluder is an ordinary mesh of the
// scene and nothing bounces (the reference's direct light, sh's shadowed transfer), and a
// bounce that meets an occluder ends there (it reflects nothing).
#include <gtest/gtest.h>

#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sh/sh_transfer.hpp"

namespace prt::bake {
namespace {

Context two_threads() {
  Context ctx;
  ctx.threads = 2;
  return ctx;
}

// A ground tile under a box: the box as an occluder, or as a mesh after the ground.
Scene ground_under_box(bool box_as_mesh) {
  Scene scene;
  Material grey;
  grey.base_color = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
  scene.materials = {grey};
  scene.meshes.push_back(make_plane_mesh("ground", 0, 1.0f, 1.0f, 8, 8));
  Mesh box = make_box_mesh(0, {0.0f, 0.4f, 0.0f}, 0.3f, 0.3f, 2);
  (box_as_mesh ? scene.meshes : scene.occluders).push_back(box);
  return scene;
}

std::vector<std::size_t> first_vertices(std::size_t count) {
  std::vector<std::size_t> vertices(count);
  for (std::size_t v = 0; v < count; ++v) vertices[v] = v;
  return vertices;
}

TEST(Occluders, HaveNoVerticesButShadowAsTheSameMeshDoes) {
  const Scene with_occluder = ground_under_box(false), with_mesh = ground_under_box(true);
  const std::size_t ground = with_occluder.meshes[0].vertex_count();
  EXPECT_EQ(with_occluder.vertex_count(), ground);
  const Context ctx = two_threads();
  const EmbreeScene rays(with_occluder, ctx);
  EXPECT_EQ(rays.triangle_count(), with_mesh.triangle_count());

  const io::EnvMap sky = make_demo_sky();
  ReferenceSettings rs;
  rs.spp = 64;
  const VertexRadiance occluded =
      ReferenceRenderer(with_occluder, sky, rs, ctx).render_vertices(ctx);
  const VertexRadiance meshed =
      ReferenceRenderer(with_mesh, sky, rs, ctx).render_vertices(first_vertices(ground), ctx);
  ASSERT_EQ(occluded.radiance.size(), ground);
  for (std::size_t v = 0; v < ground; ++v) EXPECT_EQ(occluded.radiance[v], meshed.radiance[v]) << v;

  ShTransferSettings sh;
  sh.order = 3;
  sh.rays = 64;
  const ShTransfer a = compute_sh_transfer(with_occluder, nullptr, sh, ctx);
  const ShTransfer b = compute_sh_direct_range(with_mesh, nullptr, sh, 0, ground, ctx);
  EXPECT_EQ(a.coefficients, b.coefficients);
}

TEST(Occluders, ShadowTheGroundUnderThem) {
  Scene open = ground_under_box(false);
  open.occluders.clear();
  const Context ctx = two_threads();
  const io::EnvMap sky = make_demo_sky();
  ReferenceSettings rs;
  rs.spp = 64;
  const VertexRadiance shadowed =
      ReferenceRenderer(ground_under_box(false), sky, rs, ctx).render_vertices(ctx);
  const VertexRadiance lit = ReferenceRenderer(open, sky, rs, ctx).render_vertices(ctx);
  // The centre vertex of the 9 x 9 grid is under the box.
  const std::size_t centre = 40;
  EXPECT_LT(shadowed.radiance[centre].g, 0.5f * lit.radiance[centre].g);
}

// With bounces, light reflected by a mesh reaches the ground; an occluder reflects none.
TEST(Occluders, ReflectNothing) {
  const Scene with_occluder = ground_under_box(false), with_mesh = ground_under_box(true);
  const std::size_t ground = with_occluder.meshes[0].vertex_count();
  const Context ctx = two_threads();
  ShTransferSettings sh;
  sh.order = 3;
  sh.rays = 64;
  sh.kind = ShTransferKind::Interreflected;
  const ShTransfer direct = compute_sh_direct_range(with_mesh, nullptr, sh, 0, ground, ctx);
  const ShTransfer occluded = compute_sh_transfer(with_occluder, nullptr, sh, ctx);
  EXPECT_EQ(occluded.coefficients, direct.coefficients);
  const ShTransfer bounced = compute_sh_transfer(with_mesh, nullptr, sh, ctx);
  double gained = 0.0;  // DC term of the ground's vertices: what the bounce added
  for (std::size_t v = 0; v < ground; ++v)
    gained += bounced.vertex_channel(v, 1)[0] - direct.vertex_channel(v, 1)[0];
  EXPECT_GT(gained, 0.0);
}

}  // namespace
}  // namespace prt::bake
