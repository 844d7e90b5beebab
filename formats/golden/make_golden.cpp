// SPDX-License-Identifier: MIT
// Writes the format-1.0 golden blob formats/golden/1.0/tiny.prtk (see README.md beside this file):
//   prt_make_golden formats/golden/1.0/tiny.prtk
// The inputs are spelled out here so the decode test can restate them by hand. The checked-in
// file is frozen: regenerate it only when deliberately replacing the golden blob.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <prt/format/blob_writer.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.prtk\n", argv[0]);
    return 2;
  }
  using namespace prt::format;
  try {
    // A 3 x 3 grid of vertices in the z = 0 plane, 0.5 apart: vertex k at (0.5 (k%3), 0.5 (k/3),
    // 0).
    std::vector<float> positions;
    for (int k = 0; k < 9; ++k)
      positions.insert(positions.end(), {0.5f * (k % 3), 0.5f * (k / 3), 0.0f});
    // Every normal is +z: repetitive, so zstd pays for this section.
    std::vector<float> normals;
    for (int k = 0; k < 9; ++k) normals.insert(normals.end(), {0.0f, 0.0f, 1.0f});
    // Two counter-clockwise triangles per grid cell.
    std::vector<uint32_t> triangles;
    for (uint32_t j = 0; j < 2; ++j)
      for (uint32_t i = 0; i < 2; ++i) {
        const uint32_t v = 3 * j + i;
        triangles.insert(triangles.end(), {v, v + 1, v + 4, v, v + 4, v + 3});
      }
    const std::string info = "prtkit golden blob 1.0: 3x3 grid";

    SectionOptions required;
    required.required = true;
    SectionOptions packed;
    packed.compression = Compression::kZstd;
    packed.zstd_level = 19;

    BlobWriter writer;
    writer.set_producer("prtkit-golden");
    writer.add_section(PRT_BLOB_TAG_INFO, info.data(), info.size(), info.size());
    writer.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * sizeof(float), 9,
                       required);
    writer.add_section(PRT_BLOB_TAG_VNRM, normals.data(), normals.size() * sizeof(float), 9,
                       packed);
    writer.add_section(PRT_BLOB_TAG_TRIS, triangles.data(), triangles.size() * sizeof(uint32_t), 8,
                       required);
    writer.write_file(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_make_golden: %s\n", e.what());
    return 1;
  }
  return 0;
}
