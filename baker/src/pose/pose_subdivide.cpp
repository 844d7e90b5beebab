// SPDX-License-Identifier: MIT
// Midpoint subdivision (pose_subdivide.hpp). Per attribute of an edge's new vertex: positions,
// texture coordinates and colours the mean of the ends; normals (world and local) the mean
// renormalised, or the first end's where the two cancel; tangents the same for xyz, w from the
// first end; skin weights the mean of the two ends' normalised weights per joint, the 4 largest
// kept and renormalised (ties to the lower joint index), so that an edge whose ends share their
// joints gets exactly the blend of their skinning matrices. An attribute a mesh lacks (or whose
// size does not match its positions) stays empty.
#include "prt/baker/pose/pose_subdivide.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <unordered_map>
#include <utility>

namespace prt::bake {
namespace {

template <typename T>
bool has(const std::vector<T>& attribute, std::size_t vertices) {
  return !attribute.empty() && attribute.size() == vertices;
}

glm::vec3 mid_direction(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 m = a + b;
  const float len = glm::length(m);
  return len > 0.0f ? m / len : a;
}

// The ends' weights, each normalised over its non-zero entries, averaged per joint; the four
// largest renormalised.
void mid_weights(const glm::u16vec4& ja, const glm::vec4& wa, const glm::u16vec4& jb,
                 const glm::vec4& wb, glm::u16vec4& joints, glm::vec4& weights) {
  std::array<std::pair<std::uint16_t, float>, 8> merged{};
  int n = 0;
  auto add = [&](const glm::u16vec4& j, const glm::vec4& w) {
    float total = 0.0f;
    for (int k = 0; k < 4; ++k) total += w[k] > 0.0f ? w[k] : 0.0f;
    if (!(total > 0.0f)) return;
    for (int k = 0; k < 4; ++k) {
      if (!(w[k] > 0.0f)) continue;
      const float share = 0.5f * w[k] / total;
      int i = 0;
      while (i < n && merged[i].first != j[k]) ++i;
      if (i == n) merged[n++] = {j[k], 0.0f};
      merged[i].second += share;
    }
  };
  add(ja, wa);
  add(jb, wb);
  // The whole array: unused entries weigh 0 and sort last (a sort of the first n trips GCC's
  // -Warray-bounds on std::sort's small-range path).
  std::sort(merged.begin(), merged.end(), [](const auto& x, const auto& y) {
    return x.second != y.second ? x.second > y.second : x.first < y.first;
  });
  n = std::min(n, 4);
  float total = 0.0f;
  for (int i = 0; i < n; ++i) total += merged[i].second;
  joints = glm::u16vec4(0);
  weights = glm::vec4(0.0f);
  if (n == 0) {  // neither end is weighted: keep the first's (run_bake's checks report it)
    joints = ja, weights = wa;
    return;
  }
  for (int i = 0; i < n; ++i) {
    joints[i] = merged[i].first;
    weights[i] = merged[i].second / total;
  }
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// One level splitting the edges `split_edge` accepts (by key): a triangle with three split
// edges becomes four, with two three (the quad left at the unsplit edge cut from the vertex
// between the unsplit and the first split edge), with one two; winding kept.
template <typename SplitEdge>
Mesh subdivide_edges(const Mesh& mesh, SplitEdge&& split_edge) {
  const std::size_t v0 = mesh.positions.size();
  Mesh out = mesh;
  out.indices.clear();
  out.indices.reserve(mesh.indices.size() * 4);
  const bool normals = has(mesh.normals, v0), tangents = has(mesh.tangents, v0);
  const bool local_positions = has(mesh.local_positions, v0);
  const bool local_normals = has(mesh.local_normals, v0);
  const bool uv = has(mesh.texcoords0, v0), colors = has(mesh.colors0, v0);
  const bool skin = has(mesh.joints0, v0) && has(mesh.weights0, v0);
  std::unordered_map<std::uint64_t, std::uint32_t> midpoint;
  midpoint.reserve(mesh.indices.size());
  auto split = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, inserted] =
        midpoint.emplace(edge_key(a, b), std::uint32_t(out.positions.size()));
    if (!inserted) return it->second;
    out.positions.push_back(0.5f * (mesh.positions[a] + mesh.positions[b]));
    if (normals) out.normals.push_back(mid_direction(mesh.normals[a], mesh.normals[b]));
    if (tangents)
      out.tangents.push_back(
          glm::vec4(mid_direction(mesh.tangents[a], mesh.tangents[b]), mesh.tangents[a].w));
    if (local_positions)
      out.local_positions.push_back(0.5f * (mesh.local_positions[a] + mesh.local_positions[b]));
    if (local_normals)
      out.local_normals.push_back(mid_direction(mesh.local_normals[a], mesh.local_normals[b]));
    if (uv) out.texcoords0.push_back(0.5f * (mesh.texcoords0[a] + mesh.texcoords0[b]));
    if (colors) out.colors0.push_back(0.5f * (mesh.colors0[a] + mesh.colors0[b]));
    if (skin) {
      glm::u16vec4 j;
      glm::vec4 w;
      mid_weights(mesh.joints0[a], mesh.weights0[a], mesh.joints0[b], mesh.weights0[b], j, w);
      out.joints0.push_back(j);
      out.weights0.push_back(w);
    }
    return it->second;
  };
  auto emit = [&](std::initializer_list<std::uint32_t> list) {
    out.indices.insert(out.indices.end(), list);
  };
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    bool cut[3];
    int cuts = 0;
    for (int e = 0; e < 3; ++e) cuts += cut[e] = split_edge(edge_key(v[e], v[(e + 1) % 3]));
    std::uint32_t mid[3] = {0, 0, 0};
    for (int e = 0; e < 3; ++e)
      if (cut[e]) mid[e] = split(v[e], v[(e + 1) % 3]);
    if (cuts == 0) {
      emit({v[0], v[1], v[2]});
    } else if (cuts == 3) {
      emit({v[0], mid[0], mid[2], v[1], mid[1], mid[0], v[2], mid[2], mid[1], mid[0], mid[1],
            mid[2]});
    } else if (cuts == 1) {  // rotated so that the cut edge is a-b
      const int i = cut[0] ? 0 : cut[1] ? 1 : 2;
      const std::uint32_t a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3], m = mid[i];
      emit({a, m, c, m, b, c});
    } else {  // rotated so that the uncut edge is c-a
      const int s = !cut[0] ? 1 : !cut[1] ? 2 : 0;
      const std::uint32_t a = v[s], b = v[(s + 1) % 3], c = v[(s + 2) % 3];
      const std::uint32_t m1 = mid[s], m2 = mid[(s + 1) % 3];
      emit({m1, b, m2, a, m1, m2, a, m2, c});
    }
  }
  return out;
}

}  // namespace

Mesh subdivide_mesh(const Mesh& mesh) {
  return subdivide_edges(mesh, [](std::uint64_t) { return true; });
}

Scene subdivide_scene(const Scene& scene, std::size_t target_vertices) {
  Scene out = scene;
  while (out.vertex_count() < target_vertices && out.triangle_count() > 0) {
    // Every distinct edge of every mesh with its length in the bind pose.
    struct Edge {
      float length;
      std::size_t mesh;
      std::uint64_t key;
    };
    std::vector<Edge> edges;
    for (std::size_t i = 0; i < out.meshes.size(); ++i) {
      const Mesh& m = out.meshes[i];
      std::unordered_map<std::uint64_t, char> seen;
      for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
          const std::uint32_t a = m.indices[t + e], b = m.indices[t + (e + 1) % 3];
          if (seen.emplace(edge_key(a, b), 0).second)
            edges.push_back({glm::length(m.positions[a] - m.positions[b]), i, edge_key(a, b)});
        }
    }
    const std::size_t needed = target_vertices - out.vertex_count();
    if (edges.size() <= needed) {
      for (Mesh& mesh : out.meshes) mesh = subdivide_mesh(mesh);
      continue;
    }
    // The last level splits only the longest edges, as many as reach the target exactly.
    std::nth_element(edges.begin(), edges.begin() + needed, edges.end(),
                     [](const Edge& x, const Edge& y) {
                       if (x.length != y.length) return x.length > y.length;
                       return x.mesh != y.mesh ? x.mesh < y.mesh : x.key < y.key;
                     });
    std::vector<std::unordered_map<std::uint64_t, char>> chosen(out.meshes.size());
    for (std::size_t e = 0; e < needed; ++e) chosen[edges[e].mesh].emplace(edges[e].key, 0);
    for (std::size_t i = 0; i < out.meshes.size(); ++i)
      out.meshes[i] = subdivide_edges(out.meshes[i],
                                      [&](std::uint64_t key) { return chosen[i].count(key) > 0; });
  }
  return out;
}

}  // namespace prt::bake
