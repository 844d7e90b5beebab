// SPDX-License-Identifier: MIT
// Writes the format-1.0 golden scene manifest formats/golden/1.0/scene_quads.prts (see README.md
// beside this file), which lists the golden technique blobs of the same folder:
//   prt_make_scene_golden formats/golden/1.0/scene_quads.prts
// The inputs are spelled out here so the tests can restate them by hand. Nothing is compressed,
// so the bytes do not depend on the zstd version: CTest regenerates the file and compares it byte
// for byte. The checked-in file is frozen: regenerate it only when deliberately replacing it.
#include <cstdio>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <prt/format/blob_layout.h>
#include <prt/format/scene_writer.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.prts\n", argv[0]);
    return 2;
  }
  using namespace prt::format;
  try {
    // One object per technique, without a node, at rest where it was baked (identity).
    const struct {
      const char* name;
      uint32_t tag;
    } blobs[] = {
        {"sh_quad", PRT_BLOB_TAG('S', 'H', 'T', 'R')},
        {"wavelet_quad", PRT_BLOB_TAG('W', 'V', 'L', 'T')},
        {"cloth_quad", PRT_BLOB_TAG('C', 'L', 'T', 'H')},
        {"shadowfield_quad", PRT_BLOB_TAG('S', 'F', 'L', 'D')},
        {"pose_hinge", PRT_BLOB_TAG('P', 'S', 'T', 'R')},
    };
    std::vector<SceneManifestObject> objects;
    for (const auto& b : blobs) {
      SceneManifestObject o;
      o.technique_tag = b.tag;
      o.name = b.name;
      o.blob = std::string(b.name) + ".prtk";
      objects.push_back(o);
    }
    SceneManifestOptions options;
    options.producer = "prtkit-golden";
    options.info = "prtkit golden scene manifest 1.0: the technique blobs of golden/1.0";
    const std::vector<uint8_t> blob = write_scene_manifest(objects, options);
    std::ofstream out(argv[1], std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(blob.data()), std::streamsize(blob.size()));
    if (!out.flush()) throw std::runtime_error(std::string("cannot write ") + argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_make_scene_golden: %s\n", e.what());
    return 1;
  }
  return 0;
}
