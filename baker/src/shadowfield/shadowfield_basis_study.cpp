// SPDX-License-Identifier: MIT
#include "prt/baker/shadowfield/shadowfield_basis_study.hpp"

#include <prt/prt_sh.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sampling.hpp"
#include "prt/baker/shadowfield/shadowfield_fields.hpp"

namespace prt::bake {
namespace {

// A candidate adds nothing when what is left of it outside the span taken is this small a part
// of it: far above the rounding of its values (prt_sh_eval's are floats), far below any real new
// direction.
constexpr double kDependentFraction = 1e-4;
constexpr std::uint32_t kHaarLevels = 10;
constexpr std::uint32_t kCosineMaxSum = 64;
constexpr std::size_t kReceiversPerTask = 16;
// Stream key of the receivers' ray directions (distinct from the other bakes' tags).
constexpr std::uint64_t kReceiverRaysTag = 0x42535459;  // "BSTY"

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

double inner(const std::vector<double>& a, const std::vector<double>& b,
             const std::vector<float>& weights) {
  double sum = 0.0;
  for (std::size_t v = 0; v < weights.size(); ++v) sum += double(weights[v]) * a[v] * b[v];
  return sum;
}

// A vertex weight as the fits read it: negative or non-finite counts as 0.
double usable_weight(float w) {
  return std::isfinite(w) && w > 0.0f ? double(w) : 0.0;
}

double rgb_luminance(const glm::vec3& rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

// Level j of the Haar order: its first index and its cells per side.
struct HaarFunction {
  std::uint32_t level = 0, type = 0, cell_u = 0, cell_v = 0;
};

bool haar_function(std::size_t index, HaarFunction* out) {
  std::size_t first = 1;
  for (std::uint32_t level = 0; level < kHaarLevels; ++level) {
    const std::size_t cells = std::size_t(1) << (2 * level), count = 3 * cells;
    if (index < first + count) {
      const std::size_t k = index - first, cell = k % cells, side = std::size_t(1) << level;
      *out = HaarFunction{level, std::uint32_t(k / cells), std::uint32_t(cell % side),
                          std::uint32_t(cell / side)};
      return true;
    }
    first += count;
  }
  return false;
}

// Which half (+1 first, -1 second) of its level-`level` cell x falls in, and that cell.
std::uint32_t haar_cell(double x, std::uint32_t level, int* sign) {
  const double clamped = std::clamp(x, 0.0, 1.0);
  const double halves = double(std::uint64_t(2) << level);
  const auto half =
      std::min<std::uint64_t>(std::uint64_t(clamped * halves), (std::uint64_t(2) << level) - 1);
  *sign = (half % 2 == 0) ? 1 : -1;
  return std::uint32_t(half / 2);
}

double haar_value(const HaarFunction& f, const glm::vec2& uv) {
  int sign_u = 0, sign_v = 0;
  if (haar_cell(uv.x, f.level, &sign_u) != f.cell_u ||
      haar_cell(uv.y, f.level, &sign_v) != f.cell_v)
    return 0.0;
  switch (f.type) {
    case 0:
      return sign_u;  // horizontal detail: psi(u) phi(v)
    case 1:
      return sign_v;  // vertical: phi(u) psi(v)
    default:
      return sign_u * sign_v;  // diagonal
  }
}

// The (a, b) of cosine function `index`: by a + b, then a.
bool cosine_pair(std::size_t index, std::uint32_t* a, std::uint32_t* b) {
  for (std::uint32_t sum = 0; sum <= kCosineMaxSum; ++sum) {
    if (index <= sum) {
      *a = std::uint32_t(index);
      *b = sum - *a;
      return true;
    }
    index -= sum + 1;
  }
  return false;
}

// The uv the families read: a non-finite coordinate is read as 0.
std::vector<glm::vec2> checked_uv(const std::vector<glm::vec2>& uv,
                                  const std::vector<float>& weights) {
  if (uv.size() != weights.size())
    throw Error("shadowfield basis study: one uv per vertex is needed (TEXCOORD_0)");
  std::vector<glm::vec2> out(uv);
  for (glm::vec2& p : out)
    for (int a = 0; a < 2; ++a)
      if (!std::isfinite(p[a])) p[a] = 0.0f;
  return out;
}

SurfaceBasis prefix(const SurfaceBasis& basis, std::size_t size) {
  SurfaceBasis out;
  out.size = size;
  out.vertices = basis.vertices;
  out.functions.assign(basis.functions.begin(),
                       basis.functions.begin() + std::ptrdiff_t(size * basis.vertices));
  return out;
}

}  // namespace

const char* surface_basis_name(SurfaceBasisFamily family) {
  switch (family) {
    case SurfaceBasisFamily::SphericalHarmonics:
      return "SH";
    case SurfaceBasisFamily::Haar:
      return "Haar";
    case SurfaceBasisFamily::FourierCosine:
      return "Fourier cosine";
    case SurfaceBasisFamily::Pca:
      return "PCA";
  }
  return "?";
}

SurfaceBasis orthonormal_surface_basis(const CandidateFunction& candidate,
                                       const std::vector<float>& surface_weights,
                                       std::size_t size) {
  std::vector<float> weights(surface_weights);
  double area = 0.0;
  for (float& w : weights) {
    w = float(usable_weight(w));
    area += w;
  }
  if (!(area > 0.0)) throw Error("shadowfield basis study: the surface has no area");
  const std::size_t vertices = weights.size();
  std::vector<std::vector<double>> taken;
  std::vector<double> f(vertices);
  for (std::size_t index = 0; taken.size() < size; ++index) {
    if (!candidate(index, f))
      throw Error("shadowfield basis study: the family has only " + std::to_string(taken.size()) +
                  " independent functions over these vertices, not " + std::to_string(size));
    const double norm = std::sqrt(inner(f, f, weights));
    if (!(norm > 0.0) || !std::isfinite(norm)) continue;
    for (int pass = 0; pass < 2; ++pass)
      for (const std::vector<double>& q : taken) {
        const double c = inner(f, q, weights);
        for (std::size_t v = 0; v < vertices; ++v) f[v] -= c * q[v];
      }
    const double left = std::sqrt(inner(f, f, weights));
    if (!(left > kDependentFraction * norm)) continue;
    for (double& x : f) x /= left;
    taken.push_back(f);
  }
  SurfaceBasis basis;
  basis.size = size;
  basis.vertices = vertices;
  for (const std::vector<double>& q : taken)
    basis.functions.insert(basis.functions.end(), q.begin(), q.end());
  return basis;
}

SurfaceBasis sh_surface_basis(const std::vector<glm::vec3>& positions, const glm::vec3& centre,
                              const std::vector<float>& weights, std::size_t size) {
  if (positions.size() != weights.size())
    throw Error("shadowfield basis study: one weight per position is needed");
  constexpr std::uint32_t order = PRT_SH_MAX_ORDER;
  constexpr std::size_t count = std::size_t(order) * order;
  std::vector<float> table(positions.size() * count, 0.0f);
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::vec3 d = positions[v] - centre;
    float* out = table.data() + v * count;
    if (!(glm::dot(d, d) > 0.0f) || prt_sh_eval(order, &d.x, out) != PRT_OK) {
      std::fill(out, out + count, 0.0f);
      out[0] = 1.0f;  // the constant: no direction to read
    }
  }
  return orthonormal_surface_basis(
      [&](std::size_t index, std::vector<double>& values) {
        if (index >= count) return false;
        for (std::size_t v = 0; v < values.size(); ++v) values[v] = table[v * count + index];
        return true;
      },
      weights, size);
}

SurfaceBasis haar_surface_basis(const std::vector<glm::vec2>& uv, const std::vector<float>& weights,
                                std::size_t size) {
  const std::vector<glm::vec2> read = checked_uv(uv, weights);
  return orthonormal_surface_basis(
      [&](std::size_t index, std::vector<double>& values) {
        if (index == 0) {
          std::fill(values.begin(), values.end(), 1.0);
          return true;
        }
        HaarFunction f;
        if (!haar_function(index, &f)) return false;
        for (std::size_t v = 0; v < values.size(); ++v) values[v] = haar_value(f, read[v]);
        return true;
      },
      weights, size);
}

SurfaceBasis cosine_surface_basis(const std::vector<glm::vec2>& uv,
                                  const std::vector<float>& weights, std::size_t size) {
  const std::vector<glm::vec2> read = checked_uv(uv, weights);
  return orthonormal_surface_basis(
      [&](std::size_t index, std::vector<double>& values) {
        std::uint32_t a = 0, b = 0;
        if (!cosine_pair(index, &a, &b)) return false;
        for (std::size_t v = 0; v < values.size(); ++v)
          values[v] = std::cos(kPi * a * read[v].x) * std::cos(kPi * b * read[v].y);
        return true;
      },
      weights, size);
}

SurfaceBasis pca_surface_basis(const ShadowfieldObject& object, std::size_t size) {
  const std::size_t vertices = object.positions.size();
  if (size > object.basis_size || object.basis.size() != object.basis_size * vertices)
    throw Error("shadowfield basis study: the object's PCA basis has fewer than " +
                std::to_string(size) + " functions");
  SurfaceBasis basis;
  basis.size = size;
  basis.vertices = vertices;
  basis.functions.assign(object.basis.begin(),
                         object.basis.begin() + std::ptrdiff_t(size * vertices));
  return basis;
}

std::vector<double> basis_weights(const SurfaceBasis& basis, const std::vector<float>& weights,
                                  const std::vector<double>& radiance) {
  if (weights.size() != basis.vertices || radiance.size() != basis.vertices ||
      basis.functions.size() != basis.size * basis.vertices)
    throw Error("shadowfield basis study: basis, weights and radiance sizes differ");
  const Eigen::Index n = Eigen::Index(basis.size), vertices = Eigen::Index(basis.vertices);
  const Eigen::Map<const RowMajorMatrix> b(basis.functions.data(), n, vertices);
  Eigen::VectorXd w(vertices);
  for (Eigen::Index v = 0; v < vertices; ++v) w[v] = usable_weight(weights[std::size_t(v)]);
  const Eigen::MatrixXd bw = b * w.asDiagonal();
  const Eigen::MatrixXd a = bw * b.transpose();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible())
    throw Error("shadowfield basis study: the basis functions are not independent");
  const Eigen::VectorXd solution =
      lu.solve(bw * Eigen::Map<const Eigen::VectorXd>(radiance.data(), vertices));
  return std::vector<double>(solution.data(), solution.data() + n);
}

std::vector<double> approximated_radiance(const SurfaceBasis& basis,
                                          const std::vector<float>& weights,
                                          const std::vector<double>& radiance) {
  const std::vector<double> w = basis_weights(basis, weights, radiance);
  std::vector<double> out(basis.vertices, 0.0);
  for (std::size_t i = 0; i < basis.size; ++i)
    for (std::size_t v = 0; v < basis.vertices; ++v) out[v] += w[i] * basis.at(i, v);
  return out;
}

// ---- Source irradiance --------------------------------------------------------------------------

std::vector<double> SourceIrradiance::apply(const std::vector<double>& radiance) const {
  if (radiance.size() != sources)
    throw Error("shadowfield basis study: the radiance has the wrong vertex count");
  std::vector<double> out(receivers, 0.0);
  for (std::size_t r = 0; r < receivers; ++r)
    for (std::size_t e = row_start[r]; e < row_start[r + 1]; ++e)
      out[r] += value[e] * radiance[column[e]];
  return out;
}

namespace {

using ReachedSources = std::vector<std::pair<std::uint32_t, double>>;

// One receiver vertex's row: the source vertices its rays reach and their weights, merged.
std::size_t trace_receiver(const ShadowfieldObject& source, const EmbreeScene& scene,
                           const glm::vec3& p, const glm::vec3& normal, std::uint32_t directions,
                           std::uint32_t key, ReachedSources& row) {
  row.clear();
  const float length2 = glm::dot(normal, normal);
  if (!(length2 > 1e-12f) || !std::isfinite(length2)) return 0;
  const glm::vec3 n = normal / std::sqrt(length2);
  const Frame frame(n);
  const SampleStream stream(key);
  const glm::vec3 origin = scene.offset_origin(p, n);
  const double weight = kPi / directions;
  for (std::uint32_t j = 0; j < directions; ++j) {
    const glm::vec3 w = frame.to_world(cosine_hemisphere(stream.get_2d(j, 0)));
    RayHit hit;
    if (!scene.intersect(origin, w, &hit) || hit.mesh != 0 ||
        std::size_t(hit.triangle) * 3 >= source.indices.size())
      continue;
    const std::uint32_t* corner = source.indices.data() + std::size_t(hit.triangle) * 3;
    const double bary[3] = {1.0 - hit.u - hit.v, hit.u, hit.v};
    glm::vec3 hit_normal(0.0f);
    for (int c = 0; c < 3; ++c) hit_normal += float(bary[c]) * source.normals[corner[c]];
    if (!(glm::dot(hit_normal, w) < 0.0f)) continue;  // the source glows from its front only
    for (int c = 0; c < 3; ++c) row.emplace_back(corner[c], weight * bary[c]);
  }
  std::sort(row.begin(), row.end());
  std::size_t kept = 0;
  for (std::size_t e = 0; e < row.size(); ++e) {
    if (kept > 0 && row[kept - 1].first == row[e].first)
      row[kept - 1].second += row[e].second;
    else
      row[kept++] = row[e];
  }
  row.resize(kept);
  return directions;
}

}  // namespace

SourceIrradiance source_irradiance(const ShadowfieldObject& source, const EmbreeScene& scene,
                                   const std::vector<glm::vec3>& receiver_positions,
                                   const std::vector<glm::vec3>& receiver_normals,
                                   std::uint32_t directions, std::uint32_t seed,
                                   const Context& ctx) {
  if (receiver_positions.size() != receiver_normals.size())
    throw Error("shadowfield basis study: the receiver needs one normal per vertex");
  if (directions == 0) throw Error("shadowfield basis study: receiver directions must be >= 1");
  if (source.normals.size() != source.positions.size())
    throw Error("shadowfield basis study: the source needs one normal per vertex");
  const std::size_t receivers = receiver_positions.size();
  std::vector<ReachedSources> rows(receivers);
  std::vector<std::uint64_t> rays(receivers, 0);
  const std::size_t tasks = (receivers + kReceiversPerTask - 1) / kReceiversPerTask;
  render::parallel_tasks(tasks, ctx, "shadowfield basis study: receiver rays", [&](std::size_t t) {
    const std::size_t end = std::min(receivers, (t + 1) * kReceiversPerTask);
    for (std::size_t r = t * kReceiversPerTask; r < end; ++r)
      rays[r] = trace_receiver(source, scene, receiver_positions[r], receiver_normals[r],
                               directions, hash_key(seed, r, kReceiverRaysTag), rows[r]);
  });
  SourceIrradiance out;
  out.receivers = receivers;
  out.sources = source.positions.size();
  out.row_start.assign(1, 0);
  for (std::size_t r = 0; r < receivers; ++r) {
    for (const auto& [vertex, weight] : rows[r]) {
      out.column.push_back(vertex);
      out.value.push_back(weight);
    }
    out.row_start.push_back(out.column.size());
    out.rays_traced += rays[r];
  }
  return out;
}

// ---- The comparison -----------------------------------------------------------------------------

Mesh make_study_floor(glm::vec2 centre, float half_size, float height, int side) {
  if (side < 2) throw Error("shadowfield basis study: a floor needs at least 2 x 2 vertices");
  Mesh mesh;
  mesh.name = "floor";
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const float u = float(i) / float(side - 1), v = float(j) / float(side - 1);
      mesh.positions.emplace_back(centre.x + half_size * (2.0f * u - 1.0f), height,
                                  centre.y + half_size * (2.0f * v - 1.0f));
      mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
      mesh.texcoords0.emplace_back(u, v);
    }
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const auto a = std::uint32_t(j * side + i), b = a + 1, c = a + std::uint32_t(side), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});  // counter-clockwise from +Y
    }
  return mesh;
}

namespace {

struct TestRadiance {
  std::vector<double> values;
  bool sky = false;
};

std::vector<TestRadiance> point_radiances(const ShadowfieldObject& object, const EmbreeScene& scene,
                                          const BoundingSphere& sphere,
                                          const BasisStudySettings& settings, const Context& ctx) {
  std::vector<TestRadiance> out;
  for (double distance : settings.test_light_distances) {
    const float d = float(distance) * sphere.radius;
    const ShadowfieldRadianceSamples samples = shadowfield_radiance_samples(
        object, scene, shadowfield_light_positions(settings.test_lights, sphere.centre, d),
        double(d) * d, ctx);
    for (std::size_t row = 0; row < samples.rows; ++row) {
      TestRadiance r;
      r.values.assign(samples.values.begin() + std::ptrdiff_t(row * samples.vertices),
                      samples.values.begin() + std::ptrdiff_t((row + 1) * samples.vertices));
      out.push_back(std::move(r));
    }
  }
  return out;
}

std::vector<TestRadiance> sky_radiances(const Scene& scene, std::size_t vertices,
                                        const io::EnvMap& sky, const BasisStudySettings& settings,
                                        const Context& ctx, double* noise) {
  std::vector<TestRadiance> out;
  for (std::uint32_t turn = 0; turn < settings.sky_turns; ++turn) {
    io::EnvMap turned = sky;
    const float angle = float(2.0 * kPi * turn / settings.sky_turns);
    turned.set_rotation(glm::mat3(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0))));
    ReferenceSettings reference;
    reference.bounces = 0;
    reference.spp = settings.sky_spp;
    reference.seed = hash_key(settings.seed, turn);
    reference.override_albedo = true;
    reference.albedo = glm::vec3(settings.albedo);
    const ReferenceRenderer renderer(scene, turned, reference, ctx);
    const VertexRadiance radiance = renderer.render_vertices(ctx);
    *noise = std::max(*noise, radiance.relative_rmse);
    TestRadiance r;
    r.sky = true;
    for (std::size_t v = 0; v < vertices; ++v) r.values.push_back(rgb_luminance(radiance.radiance[v]));
    out.push_back(std::move(r));
  }
  return out;
}

struct ErrorSums {
  double radiance_error = 0.0, radiance_norm = 0.0, image_error = 0.0, image_norm = 0.0;
  void add(const ErrorSums& o) {
    radiance_error += o.radiance_error;
    radiance_norm += o.radiance_norm;
    image_error += o.image_error;
    image_norm += o.image_norm;
  }
};

double weighted_distance2(const std::vector<double>& a, const std::vector<double>& b,
                          const std::vector<float>& weights) {
  double sum = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) {
    const double d = a[v] - (b.empty() ? 0.0 : b[v]);
    sum += double(weights[v]) * d * d;
  }
  return sum;
}

double ratio(double error, double norm) {
  return norm > 0.0 ? std::sqrt(error / norm) : 0.0;
}

void check_study(const BasisStudyScene& study, const BasisStudySettings& settings) {
  const Mesh& surface = study.surface;
  if (surface.texcoords0.size() != surface.positions.size())
    throw Error("shadowfield basis study: surface '" + study.name + "' has no TEXCOORD_0");
  if (settings.sizes.empty()) throw Error("shadowfield basis study: no sizes to compare");
  for (std::uint32_t size : settings.sizes)
    if (size == 0) throw Error("shadowfield basis study: a basis needs at least 1 term");
}

ShadowfieldObject study_object(const Mesh& surface, float albedo) {
  ShadowfieldObject object;
  object.positions = surface.positions;
  object.normals = surface.normals;
  object.indices = surface.indices;
  object.albedo.assign(surface.positions.size(), glm::vec3(albedo));
  return object;
}

// Every family at `largest` terms, in the order of SurfaceBasisFamily; object has its PCA basis.
std::vector<SurfaceBasis> study_families(const ShadowfieldObject& object,
                                         const std::vector<glm::vec2>& uv, const glm::vec3& centre,
                                         std::size_t largest) {
  const std::vector<float>& weights = object.vertex_weights;
  std::vector<SurfaceBasis> families;
  families.push_back(sh_surface_basis(object.positions, centre, weights, largest));
  families.push_back(haar_surface_basis(uv, weights, largest));
  families.push_back(cosine_surface_basis(uv, weights, largest));
  families.push_back(pca_surface_basis(object, largest));
  return families;
}

// The summed squared errors and norms: sums[family][size][0 point, 1 sky].
using StudySums = std::vector<std::vector<std::array<ErrorSums, 2>>>;

class ErrorAccumulator {
 public:
  ErrorAccumulator(const std::vector<SurfaceBasis>& families,
                   const std::vector<std::uint32_t>& sizes, const std::vector<float>& weights,
                   const SourceIrradiance& irradiance, std::vector<float> receiver_weights)
      : weights_(weights),
        irradiance_(irradiance),
        receiver_weights_(std::move(receiver_weights)),
        bases_(families.size()),
        sums_(families.size(), std::vector<std::array<ErrorSums, 2>>(sizes.size())) {
    for (std::size_t f = 0; f < families.size(); ++f)
      for (std::uint32_t size : sizes) bases_[f].push_back(prefix(families[f], size));
  }

  // Returns false for an unlit radiance, which has no relative error to speak of.
  bool add(const TestRadiance& r) {
    const double norm = weighted_distance2(r.values, {}, weights_);
    if (!(norm > 0.0)) return false;
    const std::vector<double> image = irradiance_.apply(r.values);
    const double image_norm = weighted_distance2(image, {}, receiver_weights_);
    for (std::size_t f = 0; f < bases_.size(); ++f)
      for (std::size_t s = 0; s < bases_[f].size(); ++s) {
        const std::vector<double> approx = approximated_radiance(bases_[f][s], weights_, r.values);
        ErrorSums& sum = sums_[f][s][r.sky ? 1 : 0];
        sum.radiance_error += weighted_distance2(r.values, approx, weights_);
        sum.radiance_norm += norm;
        sum.image_error += weighted_distance2(image, irradiance_.apply(approx), receiver_weights_);
        sum.image_norm += image_norm;
      }
    return true;
  }
  const StudySums& sums() const { return sums_; }

 private:
  const std::vector<float>& weights_;
  const SourceIrradiance& irradiance_;
  std::vector<float> receiver_weights_;
  std::vector<std::vector<SurfaceBasis>> bases_;
  StudySums sums_;
};

std::vector<BasisStudyRow> study_rows(const std::string& surface, const StudySums& sums,
                                      const std::vector<std::uint32_t>& sizes) {
  const char* kinds[3] = {"point", "sky", "all"};
  const SurfaceBasisFamily order[4] = {SurfaceBasisFamily::SphericalHarmonics,
                                       SurfaceBasisFamily::Haar, SurfaceBasisFamily::FourierCosine,
                                       SurfaceBasisFamily::Pca};
  std::vector<BasisStudyRow> rows;
  for (int kind = 0; kind < 3; ++kind)
    for (std::size_t s = 0; s < sizes.size(); ++s)
      for (std::size_t f = 0; f < sums.size(); ++f) {
        ErrorSums sum;
        if (kind != 1) sum.add(sums[f][s][0]);
        if (kind != 0) sum.add(sums[f][s][1]);
        BasisStudyRow row;
        row.surface = surface;
        row.basis = surface_basis_name(order[f]);
        row.lighting = kinds[kind];
        row.terms = sizes[s];
        row.radiance_error = ratio(sum.radiance_error, sum.radiance_norm);
        row.image_error = ratio(sum.image_error, sum.image_norm);
        rows.push_back(std::move(row));
      }
  return rows;
}

}  // namespace

BasisStudyReport compare_surface_bases(const BasisStudyScene& study, const io::EnvMap& sky,
                                       const BasisStudySettings& settings, const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  check_study(study, settings);
  const std::uint32_t largest = *std::max_element(settings.sizes.begin(), settings.sizes.end());
  Scene scene;
  scene.source = study.name;
  scene.meshes = {study.surface, study.receiver};
  const EmbreeScene rays(scene, ctx);

  ShadowfieldObject object = study_object(study.surface, settings.albedo);
  ShadowfieldBasisSettings pca = settings.pca;
  pca.size = largest;
  const ShadowfieldBasisReport pca_report = bake_surface_basis(object, rays, pca, ctx);
  const BoundingSphere sphere = bounding_sphere(object.positions);

  BasisStudyReport report;
  std::vector<TestRadiance> radiances = point_radiances(object, rays, sphere, settings, ctx);
  std::vector<TestRadiance> sky_lit =
      sky_radiances(scene, object.positions.size(), sky, settings, ctx, &report.sky_noise);
  radiances.insert(radiances.end(), sky_lit.begin(), sky_lit.end());

  ShadowfieldObject receiver;
  receiver.positions = study.receiver.positions;
  receiver.indices = study.receiver.indices;
  const SourceIrradiance irradiance =
      source_irradiance(object, rays, study.receiver.positions, study.receiver.normals,
                        settings.receiver_directions, settings.seed, ctx);
  ErrorAccumulator errors(study_families(object, study.surface.texcoords0, sphere.centre, largest),
                          settings.sizes, object.vertex_weights, irradiance,
                          shadowfield_vertex_weights(receiver));
  for (const TestRadiance& r : radiances)
    if (errors.add(r)) ++(r.sky ? report.sky_lightings : report.point_lightings);

  report.rows = study_rows(study.name, errors.sums(), settings.sizes);
  report.surface_vertices = object.positions.size();
  report.receiver_vertices = study.receiver.positions.size();
  report.pca_energy_kept = pca_report.energy_kept;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace prt::bake
