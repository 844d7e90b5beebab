// SPDX-License-Identifier: MIT
#include "prt/baker/wavelet/wavelet_transfer.hpp"

#include <prt/prt_wavelet.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <string>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"
#include "prt/baker/ray_batch.hpp"
#include "prt/baker/sampling.hpp"
#include "wavelet_grid.hpp"

namespace prt::bake {
namespace {

constexpr double kInvPi = 0.31830988618379067154;
constexpr std::size_t kWaveletVerticesPerTask = 8;
constexpr std::uint64_t kJitterTag = 0x57564c54;  // "WVLT": distinct from sh and the reference

void validate(const WaveletTransferSettings& s) {
  if (prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(s.param), s.size) == 0) {
    throw Error("wavelet transfer: --cube/face size must be a power of two in " +
                std::to_string(PRT_WAVELET_MIN_SIZE) + ".." + std::to_string(PRT_WAVELET_MAX_SIZE));
  }
  const auto k = static_cast<std::uint32_t>(std::lround(std::sqrt(double(s.samples))));
  if (s.samples < 1 || k * k != s.samples || s.samples > 1024) {
    throw Error("wavelet transfer: samples per texel must be a square k*k (1, 4, 9, ..., 1024)");
  }
  if (!(s.keep_energy >= 0.0 && s.keep_energy <= 1.0)) {
    throw Error("wavelet transfer: keep-energy must lie in (0, 1]");
  }
  if (s.vertex_stride < 1) throw Error("wavelet transfer: vertex stride must be >= 1");
  if (s.bounces < 0 || s.bounces > 8) throw Error("wavelet transfer: bounces must be in 0..8");
  const glm::vec3& a = s.albedo;
  if (s.override_albedo &&
      !(a.r >= 0.0f && a.r <= 1.0f && a.g >= 0.0f && a.g <= 1.0f && a.b >= 0.0f && a.b <= 1.0f)) {
    throw Error("wavelet transfer: albedo must lie in [0,1]");
  }
}

// select_wavelet_coefficients, also returning the row's squared norm and its nonzero count (the
// statistics keep_row needs) from the same scan.
std::vector<std::uint32_t> select_and_measure(const std::vector<float>& row, std::uint32_t keep,
                                              double keep_energy, double* squared_norm,
                                              std::size_t* nonzeros);

bool wavelet_usable(const glm::vec3& p, const glm::vec3& n) {
  const float len2 = glm::dot(n, n);
  return std::isfinite(len2) && len2 > 1e-12f && std::isfinite(p.x) && std::isfinite(p.y) &&
         std::isfinite(p.z);
}

// Calls visit(j, w, weight) for every jittered sample direction w of every texel j not entirely
// below the horizon of n with n.w > 0, weight = dw_j / pi * J cos / sum of the texel's J (k x k
// samples; those off the paraboloid's disc skipped, the centre when all are): so the weights of
// an unoccluded texel sum to its integral of cos / pi (dw_j times the T_j of an open sky).
// A texel's samples, computed once for both the Jacobian total and the visits; kept by a thread
// from vertex to vertex so the bake does not allocate per vertex.
struct TexelSamples {
  std::vector<std::uint32_t> column;        // the row's texels not below the horizon
  std::vector<float> u, v;                  // their samples' positions, texel by texel
  std::vector<glm::vec3> w;                 // and directions
  std::vector<double> jacobian;             // and Jacobians
  std::vector<unsigned char> on_grid;       // and whether each has a direction
  std::vector<float> stratum_u, stratum_v;  // float(i % k), float(i / k)
  std::vector<unsigned char> corner_above;  // TexelGrid::Horizon's buffer
};

// The sample positions of texel (x, y): stratum i of k x k, jittered by the hash of (vertex,
// texel, i). One sample per texel (k = 1) skips the division by 1, which is exact.
void sample_positions(std::uint32_t vertex_key, std::uint32_t j, std::uint32_t x, std::uint32_t y,
                      std::uint32_t samples, std::uint32_t k, const TexelSamples& s, float* u,
                      float* v) {
  for (std::uint32_t i = 0; i < samples; ++i) {
    const std::uint32_t h = hash_key(vertex_key, j, i);
    const float ju = (float(h & 0xFFFFu) + 0.5f) / 65536.0f,
                jv = (float(h >> 16) + 0.5f) / 65536.0f;
    u[i] = float(x) + (k == 1 ? ju : (s.stratum_u[i] + ju) / float(k));
    v[i] = float(y) + (k == 1 ? jv : (s.stratum_v[i] + jv) / float(k));
  }
}

// Row y of a face: the positions of its texels' samples, their directions in one runtime call,
// then the weights; the visits come in texel then sample order.
template <typename Visit>
void row_samples(const wavelet::TexelGrid& grid, const wavelet::TexelGrid::Horizon& horizon,
                 const glm::vec3& n, std::uint32_t vertex_key, std::uint32_t samples,
                 std::uint32_t k, std::uint32_t face, std::uint32_t y, TexelSamples& s,
                 Visit& visit) {
  const std::uint32_t size = grid.size(), first = (face * size + y) * size;
  s.column.clear();
  for (std::uint32_t x = 0; x < size; ++x)
    if (!horizon.below(face, x, y)) s.column.push_back(x);
  for (std::size_t t = 0; t < s.column.size(); ++t) {
    sample_positions(vertex_key, first + s.column[t], s.column[t], y, samples, k, s,
                     s.u.data() + t * samples, s.v.data() + t * samples);
  }
  grid.sample(face, s.column.size() * samples, s.u.data(), s.v.data(), s.w.data(),
              s.jacobian.data(), s.on_grid.data());
  for (std::size_t t = 0; t < s.column.size(); ++t) {
    const std::uint32_t x = s.column[t], j = first + x;
    const std::size_t at = t * samples;
    double total = 0.0;
    for (std::uint32_t i = 0; i < samples; ++i)
      if (s.on_grid[at + i]) total += s.jacobian[at + i];
    const double scale = grid.solid_angle(j) * kInvPi;
    if (total == 0.0) {  // every jittered sample fell off the disc: the centre is inside
      glm::vec3 centre;
      double ignored;
      grid.sample(face, x + 0.5f, y + 0.5f, &centre, &ignored);
      const float cosine = glm::dot(n, centre);
      if (cosine > 0.0f) visit(j, centre, scale * cosine);
      continue;
    }
    for (std::uint32_t i = 0; i < samples; ++i) {
      if (!s.on_grid[at + i]) continue;
      const float cosine = glm::dot(n, s.w[at + i]);
      if (cosine > 0.0f) visit(j, s.w[at + i], scale * s.jacobian[at + i] * cosine / total);
    }
  }
}

template <typename Visit>
void for_each_sample(const wavelet::TexelGrid& grid, const glm::vec3& n, std::uint32_t vertex_key,
                     std::uint32_t samples, TexelSamples& scratch, Visit visit) {
  const std::uint32_t size = grid.size(),
                      k = static_cast<std::uint32_t>(std::lround(std::sqrt(samples)));
  const std::size_t row = std::size_t(size) * samples;
  scratch.u.resize(row);
  scratch.v.resize(row);
  scratch.w.resize(row);
  scratch.jacobian.resize(row);
  scratch.on_grid.resize(row);
  scratch.stratum_u.resize(samples);
  scratch.stratum_v.resize(samples);
  for (std::uint32_t i = 0; i < samples; ++i) {
    scratch.stratum_u[i] = float(i % k);
    scratch.stratum_v[i] = float(i / k);
  }
  const wavelet::TexelGrid::Horizon horizon(grid, n, scratch.corner_above);
  for (std::uint32_t face = 0; face < grid.faces(); ++face)
    for (std::uint32_t y = 0; y < size; ++y)
      row_samples(grid, horizon, n, vertex_key, samples, k, face, y, scratch, visit);
}

// One thread's buffers for bake_texels, reused from vertex to vertex.
struct TexelScratch {
  TexelSamples samples;
  std::vector<std::uint32_t> texel;
  std::vector<double> weight;
  std::vector<glm::vec3> direction;
  std::vector<unsigned char> visible;
};

// Texel values of one vertex: the visible samples' weights; `batch` null = unoccluded. Returns
// the rays traced.
std::uint64_t bake_texels(const wavelet::TexelGrid& grid, const glm::vec3& n,
                          const glm::vec3& origin, RayBatch* batch, std::uint32_t vertex_key,
                          std::uint32_t samples, TexelScratch& scratch, float* row) {
  std::vector<std::uint32_t>& texel = scratch.texel;
  std::vector<double>& weight = scratch.weight;
  std::vector<glm::vec3>& direction = scratch.direction;
  std::vector<unsigned char>& visible = scratch.visible;
  texel.clear();
  weight.clear();
  direction.clear();
  for_each_sample(grid, n, vertex_key, samples, scratch.samples,
                  [&](std::uint32_t j, const glm::vec3& w, double x) {
                    texel.push_back(j);
                    direction.push_back(w);
                    weight.push_back(x);
                  });
  visible.assign(texel.size(), 1);
  std::uint64_t traced = 0;
  // Every sample is above the horizon (cosine > 0), so the batch casts all of them.
  if (batch) traced = batch->cast(origin, n, direction.data(), direction.size(), visible.data());
  // A texel's samples come one after another, so its sum is the run's (from 0.0, in sample
  // order); the texels no sample reached stay 0. The samples' weights integrate over the texel;
  // the transfer is the texel's mean (§14).
  std::fill(row, row + grid.count(), 0.0f);
  for (std::size_t i = 0; i < texel.size();) {
    const std::uint32_t j = texel[i];
    double sum = 0.0;
    for (; i < texel.size() && texel[i] == j; ++i)
      if (visible[i]) sum += weight[i];
    if (sum != 0.0) row[j] = static_cast<float>(sum / grid.solid_angle(j));
  }
  return traced;
}

void transform_faces(const wavelet::TexelGrid& grid, float* row) {
  const std::size_t face_texels = std::size_t(grid.size()) * grid.size();
  for (std::uint32_t f = 0; f < grid.faces(); ++f) {
    if (prt_haar_forward(grid.size(), 1, row + f * face_texels) != PRT_OK) {
      throw Error("wavelet transfer: prt_haar_forward failed");
    }
  }
}

// The vertices to bake, in ascending order.
std::vector<std::uint32_t> subset(const WaveletTransferSettings& s, std::size_t vertex_count) {
  std::vector<std::uint32_t> out;
  if (!s.vertex_list.empty()) {
    for (std::uint32_t v : s.vertex_list) {
      if (v >= vertex_count) {
        throw Error("wavelet transfer: vertex " + std::to_string(v) +
                    " of the subset is not in "
                    "the scene (" +
                    std::to_string(vertex_count) + " vertices)");
      }
      out.push_back(v);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  for (std::size_t v = 0; v < vertex_count; v += s.vertex_stride) out.push_back(std::uint32_t(v));
  return out;
}

// One task's output: the sparse rows of its vertices, in order, and their statistics.
struct TaskRows {
  std::vector<std::uint32_t> vertex, count, index, nonzeros_before;
  std::vector<float> value;
  std::vector<double> energy_kept;
  std::uint64_t traced = 0;
};

// What every pass knows about the scene's vertices (Scene order).
struct WaveletVertexTable {
  std::vector<glm::vec3> position, normal, albedo;  // normal: unit, or 0 when not usable
  std::vector<unsigned char> usable;
  std::vector<std::size_t> first_of_mesh;

  WaveletVertexTable(const Scene& scene, const WaveletTransferSettings& s) {
    for (const Mesh& mesh : scene.meshes) {
      first_of_mesh.push_back(position.size());
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
        const bool ok = wavelet_usable(mesh.positions[v], n);
        position.push_back(mesh.positions[v]);
        normal.push_back(ok ? glm::normalize(n) : glm::vec3(0.0f));
        usable.push_back(ok ? 1 : 0);
        albedo.push_back(s.override_albedo ? s.albedo : scene.vertex_albedo(mesh, v));
      }
    }
  }
  std::size_t size() const { return position.size(); }
};

// Truncates a dense row into `rows` (and its statistics).
void keep_row(std::uint32_t v, const std::vector<float>& row, const WaveletTransferSettings& s,
              TaskRows& rows) {
  double total = 0.0, sum = 0.0;
  std::size_t nonzeros = 0;
  const std::vector<std::uint32_t> kept =
      select_and_measure(row, s.keep, s.keep_energy, &total, &nonzeros);
  for (std::uint32_t j : kept) {
    sum += double(row[j]) * row[j];
    rows.index.push_back(j);
    rows.value.push_back(row[j]);
  }
  rows.vertex.push_back(v);
  rows.count.push_back(static_cast<std::uint32_t>(kept.size()));
  rows.energy_kept.push_back(total > 0.0 ? sum / total : 1.0);
  rows.nonzeros_before.push_back(static_cast<std::uint32_t>(nonzeros));
}

// The means of the per-vertex statistics over the baked vertices of `todo` (t's row v - first is
// vertex v's), summed per task of a pass over `todo` and then over the tasks, as the bake has
// always summed them: a whole bake and the join of its ranges then give the same doubles.
void set_wavelet_means(const std::vector<std::uint32_t>& todo, std::size_t first,
                       WaveletTransfer& t) {
  double energy = 0.0, nonzeros = 0.0;
  std::size_t baked = 0;
  for (std::size_t at = 0; at < todo.size(); at += kWaveletVerticesPerTask) {
    double task_energy = 0.0, task_nonzeros = 0.0;
    for (std::size_t i = at; i < std::min(todo.size(), at + kWaveletVerticesPerTask); ++i) {
      const std::size_t v = todo[i] - first;
      if (!t.baked[v]) continue;
      task_energy += t.energy_kept[v];
      task_nonzeros += double(t.nonzeros_before[v]);
      ++baked;
    }
    energy += task_energy;
    nonzeros += task_nonzeros;
  }
  t.mean_energy_kept = baked > 0 ? energy / baked : 1.0;
  t.mean_nonzeros_before = baked > 0 ? nonzeros / baked : 0.0;
}

// The tasks' rows (of vertices of `todo`, all in [first, first + count)) as the transfer of
// vertices [first, first + count) (rows of vertices not in any task empty).
WaveletTransfer gather_rows(const std::vector<TaskRows>& task_rows,
                            const std::vector<std::uint32_t>& todo, std::size_t first,
                            std::size_t count) {
  WaveletTransfer out;
  out.vertex_count = count;
  out.baked.assign(count, 0);
  out.energy_kept.assign(count, 0.0);
  out.nonzeros_before.assign(count, 0);
  out.row_start.assign(count + 1, 0);
  std::vector<std::uint32_t> row_size(count, 0);
  for (const TaskRows& rows : task_rows) {
    for (std::size_t i = 0; i < rows.vertex.size(); ++i) {
      const std::size_t v = rows.vertex[i] - first;
      row_size[v] = rows.count[i];
      out.baked[v] = 1;
      out.energy_kept[v] = rows.energy_kept[i];
      out.nonzeros_before[v] = rows.nonzeros_before[i];
    }
    out.rays_traced += rows.traced;
  }
  for (std::size_t v = 0; v < count; ++v) out.row_start[v + 1] = out.row_start[v] + row_size[v];
  out.index.resize(out.row_start.back());
  out.value.resize(out.row_start.back());
  for (const TaskRows& rows : task_rows) {
    std::size_t at = 0;
    for (std::size_t i = 0; i < rows.vertex.size(); ++i) {
      const std::uint64_t start = out.row_start[rows.vertex[i] - first];
      std::copy_n(rows.index.begin() + at, rows.count[i], out.index.begin() + start);
      std::copy_n(rows.value.begin() + at, rows.count[i], out.value.begin() + start);
      at += rows.count[i];
    }
  }
  set_wavelet_means(todo, first, out);
  return out;
}

// One pass over the usable vertices of `todo` (all in [first, first + count)): row_of(v, row)
// fills vertex v's dense row in the wavelet domain and returns the rays it traced; rows are
// truncated by the settings. The transfer returned has the rows of [first, first + count).
template <typename RowOf>
WaveletTransfer run_pass(const std::vector<std::uint32_t>& todo, const WaveletVertexTable& vertices,
                         std::size_t first, std::size_t count, std::uint32_t coefficients,
                         const WaveletTransferSettings& s, const Context& ctx,
                         const std::string& stage, RowOf row_of) {
  const std::size_t tasks = (todo.size() + kWaveletVerticesPerTask - 1) / kWaveletVerticesPerTask;
  std::vector<TaskRows> task_rows(tasks);
  render::parallel_tasks(tasks, ctx, stage, [&](std::size_t task) {
    std::vector<float> row(coefficients);
    const std::size_t end = std::min(todo.size(), (task + 1) * kWaveletVerticesPerTask);
    for (std::size_t i = task * kWaveletVerticesPerTask; i < end; ++i) {
      if (!vertices.usable[todo[i]]) continue;
      task_rows[task].traced += row_of(todo[i], row);
      keep_row(todo[i], row, s, task_rows[task]);
    }
  });
  return gather_rows(task_rows, todo, first, count);
}

// A bounce (Sloan 2002 §5 in the wavelet domain): along vertex v's texel samples that hit the
// front of a surface, the previous pass's rows of the hit triangle's vertices, weighted by the
// sample's weight, the barycentrics and the vertex's grey albedo (mean of its RGB).
std::uint64_t gather_bounce(std::uint32_t v, const WaveletTransfer& previous,
                            const WaveletVertexTable& vertices, const Scene& scene,
                            const EmbreeScene& rays, const wavelet::TexelGrid& grid,
                            const WaveletTransferSettings& s, std::vector<float>& row) {
  const glm::vec3 n = vertices.normal[v];
  std::vector<glm::vec3> directions;
  std::vector<double> weights;
  TexelSamples scratch;
  for_each_sample(grid, n, hash_key(s.seed, v, kJitterTag), s.samples, scratch,
                  [&](std::uint32_t, const glm::vec3& w, double weight) {
                    directions.push_back(w);
                    weights.push_back(weight);
                  });
  // Every visited sample is above the horizon (cos > 0), so the batch casts them all.
  std::vector<RayHit> found_hits(directions.size());
  std::vector<unsigned char> found(directions.size());
  RayBatch batch(rays);
  const std::uint64_t traced =
      batch.intersect(rays.offset_origin(vertices.position[v], n), n, directions.data(),
                      directions.size(), found_hits.data(), found.data());
  std::vector<std::pair<std::uint32_t, double>> hits;
  for (std::size_t k = 0; k < directions.size(); ++k) {
    if (!found[k]) continue;
    const RayHit& hit = found_hits[k];
    if (hit.mesh >= scene.meshes.size()) continue;  // an occluder reflects nothing
    const Mesh& mesh = scene.meshes[hit.mesh];
    const std::size_t first = vertices.first_of_mesh[hit.mesh];
    const float bary[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
    std::uint32_t corner[3];
    glm::vec3 normal(0.0f);
    for (int c = 0; c < 3; ++c) {
      corner[c] =
          static_cast<std::uint32_t>(first + mesh.indices[3 * std::size_t(hit.triangle) + c]);
      normal += bary[c] * vertices.normal[corner[c]];
    }
    if (glm::dot(normal, directions[k]) >= 0.0f) continue;  // the back, or no normal
    for (int c = 0; c < 3; ++c) {
      const glm::vec3& rho = vertices.albedo[corner[c]];
      hits.emplace_back(corner[c], weights[k] * bary[c] * (rho.r + rho.g + rho.b) / 3.0);
    }
  }
  std::sort(hits.begin(), hits.end());
  std::vector<double> sum(row.size(), 0.0);
  for (std::size_t i = 0; i < hits.size();) {
    const std::uint32_t u = hits[i].first;
    double weight = 0.0;
    for (; i < hits.size() && hits[i].first == u; ++i) weight += hits[i].second;
    for (std::uint64_t p = previous.row_start[u]; p < previous.row_start[u + 1]; ++p) {
      sum[previous.index[p]] += weight * previous.value[p];
    }
  }
  for (std::size_t j = 0; j < row.size(); ++j) row[j] = static_cast<float>(sum[j]);
  return traced;
}

// Row v of a + b, dense.
void add_rows(const WaveletTransfer& a, const WaveletTransfer& b, std::uint32_t v,
              std::vector<float>& row) {
  std::fill(row.begin(), row.end(), 0.0f);
  for (const WaveletTransfer* t : {&a, &b}) {
    for (std::uint64_t p = t->row_start[v]; p < t->row_start[v + 1]; ++p) {
      row[t->index[p]] += t->value[p];
    }
  }
}

}  // namespace

const char* wavelet_param_name(std::uint32_t param) {
  return param == PRT_WAVELET_PARAM_CUBE              ? "cube"
         : param == PRT_WAVELET_PARAM_DUAL_PARABOLOID ? "dual-paraboloid"
                                                      : "unknown";
}

std::uint32_t parse_wavelet_param(const char* name) {
  if (name && std::strcmp(name, "cube") == 0) return PRT_WAVELET_PARAM_CUBE;
  if (name && std::strcmp(name, "dual-paraboloid") == 0) return PRT_WAVELET_PARAM_DUAL_PARABOLOID;
  throw Error(std::string("wavelet: unknown parameterisation '") + (name ? name : "") +
              "' (cube or dual-paraboloid)");
}

std::uint32_t default_wavelet_keep(std::uint32_t param, std::uint32_t size) {
  const double count = prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(param), size);
  const double fraction = 1000.0 / prt_wavelet_coefficient_count(PRT_WAVELET_PARAM_CUBE, 64);
  return std::max<std::uint32_t>(64, static_cast<std::uint32_t>(std::lround(count * fraction)));
}

std::vector<std::uint32_t> select_wavelet_coefficients(const std::vector<float>& row,
                                                       std::uint32_t keep, double keep_energy) {
  double squared_norm;
  std::size_t nonzeros;
  return select_and_measure(row, keep, keep_energy, &squared_norm, &nonzeros);
}

namespace {

// The keys (|value|'s bits above the complemented index) of the entries of `order` whose
// |value| is at least the keep-th largest's, rounded down to a histogram bin: every one of the
// keep largest keys and few others, so nth_element sorts far fewer. A float's bits order as its
// magnitude, so the bins (its top 12 bits: exponent and 3 mantissa bits) order as well.
std::vector<std::uint64_t> largest_keys(const std::vector<float>& row,
                                        const std::vector<std::uint32_t>& order,
                                        std::uint32_t keep) {
  constexpr int kBinShift = 20;
  std::vector<std::uint32_t> bits(order.size());
  std::vector<std::uint32_t> histogram(std::size_t(1) << (32 - kBinShift), 0);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const float magnitude = std::abs(row[order[i]]);
    std::memcpy(&bits[i], &magnitude, sizeof bits[i]);
    ++histogram[bits[i] >> kBinShift];
  }
  std::size_t bin = histogram.size(), above = 0;
  while (above < keep && bin > 0) above += histogram[--bin];
  std::vector<std::uint64_t> keys;
  keys.reserve(above);
  for (std::size_t i = 0; i < order.size(); ++i)
    if ((bits[i] >> kBinShift) >= bin) keys.push_back((std::uint64_t(bits[i]) << 32) | ~order[i]);
  return keys;
}

std::vector<std::uint32_t> select_and_measure(const std::vector<float>& row, std::uint32_t keep,
                                              double keep_energy, double* squared_norm,
                                              std::size_t* nonzeros) {
  std::vector<std::uint32_t> order;
  // Zeros add nothing to the norm: summing the others in index order gives the same double.
  double norm = 0.0;
  for (std::uint32_t j = 0; j < row.size(); ++j) {
    if (row[j] != 0.0f) {
      order.push_back(j);
      norm += double(row[j]) * row[j];
    }
  }
  *squared_norm = norm;
  *nonzeros = order.size();
  const auto larger = [&](std::uint32_t a, std::uint32_t b) {
    const float fa = std::abs(row[a]), fb = std::abs(row[b]);
    return fa > fb || (fa == fb && a < b);
  };
  if (keep_energy > 0.0) {
    std::sort(order.begin(), order.end(), larger);
    double total = 0.0, sum = 0.0;
    for (std::uint32_t j : order) total += double(row[j]) * row[j];
    std::size_t kept = 0;
    while (kept < order.size() && sum < keep_energy * total) {
      sum += double(row[order[kept]]) * row[order[kept]];
      ++kept;
    }
    order.resize(kept);
  } else if (keep > 0 && order.size() > keep) {
    // `larger` as one integer comparison: |value|'s bits (ordered as |value|, being >= 0) above
    // the complemented index (lower index first on ties). The keys are distinct, so the kept
    // set is the one nth_element with `larger` picks.
    std::vector<std::uint64_t> keys = largest_keys(row, order, keep);
    std::nth_element(keys.begin(), keys.begin() + keep, keys.end(), std::greater<>());
    order.resize(keep);
    for (std::size_t i = 0; i < keep; ++i) order[i] = ~std::uint32_t(keys[i]);
  }
  std::sort(order.begin(), order.end());
  return order;
}

}  // namespace

std::vector<float> unoccluded_wavelet_texels(std::uint32_t param, std::uint32_t size,
                                             std::uint32_t samples, const glm::vec3& normal,
                                             std::uint32_t seed) {
  WaveletTransferSettings s;
  s.param = param;
  s.size = size;
  s.samples = samples;
  validate(s);
  const wavelet::TexelGrid grid(param, size);
  std::vector<float> row(grid.count());
  TexelScratch scratch;
  bake_texels(grid, glm::normalize(normal), glm::vec3(0.0f), nullptr, hash_key(seed, 0, kJitterTag),
              samples, scratch, row.data());
  return row;
}

namespace {

std::unique_ptr<EmbreeScene> wavelet_own_rays(const Scene& scene, const Context& ctx) {
  std::unique_ptr<EmbreeScene> own;
  tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
  arena.execute([&] { own = std::make_unique<EmbreeScene>(scene, ctx); });
  return own;
}

void warn_wavelet_without_normal(const WaveletTransfer& transfer, const Context& ctx) {
  if (transfer.vertices_without_normal == 0) return;
  ctx.warn("wavelet transfer: " + std::to_string(transfer.vertices_without_normal) +
           " vertices have no usable normal (zero or non-finite) or position; their row is "
           "empty");
}

// The subset's vertices in [first, first + count), ascending.
std::vector<std::uint32_t> wavelet_subset_in(const WaveletTransferSettings& s,
                                             std::size_t vertex_count, std::size_t first,
                                             std::size_t count) {
  std::vector<std::uint32_t> todo = subset(s, vertex_count);
  const auto begin = std::lower_bound(todo.begin(), todo.end(), first);
  const auto end = std::lower_bound(begin, todo.end(), first + count);
  return std::vector<std::uint32_t>(begin, end);
}

// The direct pass of the subset's vertices in [first, first + count), without timing or warning.
WaveletTransfer wavelet_direct_range(const EmbreeScene& rays, const wavelet::TexelGrid& grid,
                                     const WaveletVertexTable& vertices,
                                     const WaveletTransferSettings& settings, std::size_t first,
                                     std::size_t count, const Context& ctx) {
  if (first > vertices.size() || count > vertices.size() - first) {
    throw Error("wavelet transfer: vertices [" + std::to_string(first) + ", " +
                std::to_string(first + count) + ") are not all in the scene (" +
                std::to_string(vertices.size()) + " vertices)");
  }
  const std::vector<std::uint32_t> todo =
      wavelet_subset_in(settings, vertices.size(), first, count);
  // A ray batch and texel buffers per thread, not per vertex: the bake then does not allocate.
  struct DirectScratch {
    RayBatch batch;
    TexelScratch texels;
    explicit DirectScratch(const EmbreeScene& scene) : batch(scene) {}
  };
  tbb::enumerable_thread_specific<std::unique_ptr<DirectScratch>> direct_scratch;
  // Every random number is keyed by the vertex's index in the scene: a range's rows are the
  // whole bake's.
  WaveletTransfer out = run_pass(
      todo, vertices, first, count, grid.count(), settings, ctx, "wavelet transfer: direct",
      [&](std::uint32_t v, std::vector<float>& row) {
        const glm::vec3 n = vertices.normal[v];
        std::unique_ptr<DirectScratch>& local = direct_scratch.local();
        if (!local) local = std::make_unique<DirectScratch>(rays);
        DirectScratch& scratch = *local;
        const std::uint64_t traced = bake_texels(
            grid, n, rays.offset_origin(vertices.position[v], n), &scratch.batch,
            hash_key(settings.seed, v, kJitterTag), settings.samples, scratch.texels, row.data());
        transform_faces(grid, row.data());
        return traced;
      });
  out.param = settings.param;
  out.size = settings.size;
  out.coefficient_count = grid.count();
  out.albedo.assign(vertices.albedo.begin() + std::ptrdiff_t(first),
                    vertices.albedo.begin() + std::ptrdiff_t(first + count));
  for (std::uint32_t v : todo) out.vertices_without_normal += vertices.usable[v] ? 0 : 1;
  return out;
}

// Replaces t's rows and their statistics by `pass`'s (a pass over the same vertices).
void take_wavelet_rows(WaveletTransfer& t, WaveletTransfer&& pass) {
  t.row_start = std::move(pass.row_start);
  t.index = std::move(pass.index);
  t.value = std::move(pass.value);
  t.baked = std::move(pass.baked);
  t.energy_kept = std::move(pass.energy_kept);
  t.nonzeros_before = std::move(pass.nonzeros_before);
  t.mean_energy_kept = pass.mean_energy_kept;
  t.mean_nonzeros_before = pass.mean_nonzeros_before;
}

// The bounce passes added to every vertex's direct pass, without timing or warning. A bounce
// reads the previous pass's truncated rows (the direct pass's for the first), as the rows the
// direct pass stores.
void wavelet_bounces(const Scene& scene, const EmbreeScene& rays, const wavelet::TexelGrid& grid,
                     const WaveletVertexTable& vertices, const WaveletTransferSettings& settings,
                     WaveletTransfer& whole, const Context& ctx) {
  const std::vector<std::uint32_t> todo = subset(settings, vertices.size());
  const std::size_t all = vertices.size();
  WaveletTransfer last_bounce;
  for (int b = 1; b <= settings.bounces; ++b) {
    const WaveletTransfer& previous = b == 1 ? whole : last_bounce;
    const std::string stage = "wavelet transfer: bounce " + std::to_string(b);
    WaveletTransfer bounce =
        run_pass(todo, vertices, 0, all, grid.count(), settings, ctx, stage,
                 [&](std::uint32_t v, std::vector<float>& row) {
                   return gather_bounce(v, previous, vertices, scene, rays, grid, settings, row);
                 });
    WaveletTransfer sum = run_pass(todo, vertices, 0, all, grid.count(), settings, ctx,
                                   stage + " (sum)", [&](std::uint32_t v, std::vector<float>& row) {
                                     add_rows(whole, bounce, v, row);
                                     return std::uint64_t(0);
                                   });
    take_wavelet_rows(whole, std::move(sum));
    whole.rays_traced += bounce.rays_traced;
    last_bounce = std::move(bounce);
  }
}

// Error unless t is every vertex's transfer with these settings.
void check_wavelet_whole(const WaveletTransfer& t, const WaveletTransferSettings& settings,
                         std::size_t vertex_count) {
  if (t.param != settings.param || t.size != settings.size || t.vertex_count != vertex_count ||
      t.row_start.size() != vertex_count + 1 || t.baked.size() != vertex_count ||
      t.albedo.size() != vertex_count || t.energy_kept.size() != vertex_count ||
      t.nonzeros_before.size() != vertex_count || t.index.size() != t.row_start.back() ||
      t.value.size() != t.row_start.back()) {
    throw Error(
        "wavelet transfer: the bounces need every vertex's direct pass with these "
        "settings");
  }
}

}  // namespace

WaveletTransfer compute_wavelet_transfer(const Scene& scene, const EmbreeScene* rays,
                                         const WaveletTransferSettings& settings,
                                         const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<EmbreeScene> own_rays;
  if (!rays) rays = (own_rays = wavelet_own_rays(scene, ctx)).get();
  const wavelet::TexelGrid grid(settings.param, settings.size);
  const WaveletVertexTable vertices(scene, settings);
  WaveletTransfer out =
      wavelet_direct_range(*rays, grid, vertices, settings, 0, vertices.size(), ctx);
  wavelet_bounces(scene, *rays, grid, vertices, settings, out, ctx);
  warn_wavelet_without_normal(out, ctx);
  out.seconds = seconds_since(start);
  return out;
}

WaveletTransfer compute_wavelet_direct_range(const Scene& scene, const EmbreeScene* rays,
                                             const WaveletTransferSettings& settings,
                                             std::size_t first, std::size_t count,
                                             const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<EmbreeScene> own_rays;
  if (!rays) rays = (own_rays = wavelet_own_rays(scene, ctx)).get();
  const wavelet::TexelGrid grid(settings.param, settings.size);
  const WaveletVertexTable vertices(scene, settings);
  WaveletTransfer out = wavelet_direct_range(*rays, grid, vertices, settings, first, count, ctx);
  warn_wavelet_without_normal(out, ctx);
  out.seconds = seconds_since(start);
  return out;
}

WaveletTransfer join_wavelet_ranges(const WaveletTransferSettings& settings,
                                    std::vector<WaveletTransfer> ranges) {
  validate(settings);
  if (ranges.empty()) throw Error("wavelet transfer: no ranges to join");
  std::size_t vertices = 0, pairs = 0;
  for (const WaveletTransfer& part : ranges) {
    vertices += part.vertex_count;
    pairs += part.index.size();
  }
  WaveletTransfer whole = std::move(ranges.front());
  whole.row_start.reserve(vertices + 1);
  whole.index.reserve(pairs);
  whole.value.reserve(pairs);
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    WaveletTransfer& part = ranges[i];
    if (part.param != whole.param || part.size != whole.size) {
      throw Error("wavelet transfer: range " + std::to_string(i) +
                  " has another parameterisation or size than range 0");
    }
    const std::uint64_t offset = whole.row_start.back();
    for (std::size_t v = 1; v < part.row_start.size(); ++v)
      whole.row_start.push_back(offset + part.row_start[v]);
    whole.vertex_count += part.vertex_count;
    whole.index.insert(whole.index.end(), part.index.begin(), part.index.end());
    whole.value.insert(whole.value.end(), part.value.begin(), part.value.end());
    whole.albedo.insert(whole.albedo.end(), part.albedo.begin(), part.albedo.end());
    whole.baked.insert(whole.baked.end(), part.baked.begin(), part.baked.end());
    whole.energy_kept.insert(whole.energy_kept.end(), part.energy_kept.begin(),
                             part.energy_kept.end());
    whole.nonzeros_before.insert(whole.nonzeros_before.end(), part.nonzeros_before.begin(),
                                 part.nonzeros_before.end());
    whole.vertices_without_normal += part.vertices_without_normal;
    whole.rays_traced += part.rays_traced;
    whole.seconds += part.seconds;
    part = WaveletTransfer();  // freed as soon as copied
  }
  set_wavelet_means(subset(settings, whole.vertex_count), 0, whole);
  return whole;
}

void add_wavelet_bounces(const Scene& scene, const EmbreeScene* rays,
                         const WaveletTransferSettings& settings, WaveletTransfer& whole_direct,
                         const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  const WaveletVertexTable vertices(scene, settings);
  check_wavelet_whole(whole_direct, settings, vertices.size());
  if (settings.bounces > 0) {
    std::unique_ptr<EmbreeScene> own_rays;
    if (!rays) rays = (own_rays = wavelet_own_rays(scene, ctx)).get();
    const wavelet::TexelGrid grid(settings.param, settings.size);
    wavelet_bounces(scene, *rays, grid, vertices, settings, whole_direct, ctx);
  }
  warn_wavelet_without_normal(whole_direct, ctx);
  whole_direct.seconds += seconds_since(start);
}

std::vector<glm::vec3> shade_wavelet_transfer(const WaveletTransfer& transfer,
                                              const std::vector<float>& light_rgba) {
  if (light_rgba.size() != std::size_t(transfer.coefficient_count) * 4) {
    throw Error("wavelet shading: the light has " + std::to_string(light_rgba.size() / 4) +
                " coefficients, the transfer " + std::to_string(transfer.coefficient_count));
  }
  std::vector<glm::vec3> radiance(transfer.vertex_count, glm::vec3(0.0f));
  for (std::size_t v = 0; v < transfer.vertex_count; ++v) {
    glm::dvec3 sum(0.0);
    for (std::uint64_t p = transfer.row_start[v]; p < transfer.row_start[v + 1]; ++p) {
      const float* l = light_rgba.data() + std::size_t(transfer.index[p]) * 4;
      sum += double(transfer.value[p]) * glm::dvec3(l[0], l[1], l[2]);
    }
    radiance[v] = glm::vec3(sum * glm::dvec3(transfer.albedo[v]));
  }
  return radiance;
}

}  // namespace prt::bake
