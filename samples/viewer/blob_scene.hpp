// SPDX-License-Identifier: MIT
// The viewer's side of the runtime: a context, a blob loaded at full validation, its mesh
// (VPOS/VNRM/TRIS sections) and its technique's header (`sh` SHTR or `wavelet` WVLT). Failures
// throw ViewerError with the runtime's own message.
#pragma once

#include <prt/prt.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace prt::view {

// What the viewer reports and exits 1 on.
class ViewerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Borrowed views into the asset's decoded sections (valid while the BlobScene lives).
struct BlobMesh {
  const float* positions = nullptr;  // x,y,z per vertex
  std::uint32_t vertex_count = 0;
  const std::uint32_t* indices = nullptr;  // i0,i1,i2 per triangle
  std::uint32_t triangle_count = 0;
};

// The techniques the viewer shades.
enum class Technique { Sh, Wavelet };

class BlobScene {
 public:
  // Creates a context (messages recorded, not printed; backend limits from the PRT_BACKEND /
  // PRT_SIMD_ISA environment variables as for any prtkit program) and loads `path` with full
  // validation. Throws ViewerError naming the file and quoting the runtime on failure, or when
  // the blob has neither an SHTR nor a WVLT section or its mesh does not match the transfer.
  explicit BlobScene(const std::string& path);
  ~BlobScene();
  BlobScene(const BlobScene&) = delete;
  BlobScene& operator=(const BlobScene&) = delete;

  prt_context* context() const { return context_; }
  const prt_asset* asset() const { return asset_; }
  const BlobMesh& mesh() const { return mesh_; }
  Technique technique() const { return technique_; }
  std::uint32_t vertex_count() const { return mesh_.vertex_count; }
  const prt_sh_info& transfer() const { return transfer_; }           // Technique::Sh
  const prt_wavelet_info& wavelet() const { return wavelet_; }        // Technique::Wavelet
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  prt_context* context_ = nullptr;
  prt_asset* asset_ = nullptr;
  BlobMesh mesh_;
  Technique technique_ = Technique::Sh;
  prt_sh_info transfer_ = prt::sized<prt_sh_info>();
  prt_wavelet_info wavelet_ = prt::sized<prt_wavelet_info>();

  void read_technique();

  void read_mesh();
  [[noreturn]] void fail(const std::string& what) const;
};

}  // namespace prt::view
