// SPDX-License-Identifier: MIT
// Writer of scene manifests (formats/SPEC.md §7.6): a blob whose SCNE section lists the objects
// of a baked scene, each with its technique, name, blob file and rest placement. Used by
// `prt-bake scene` and the golden generator.
//
// Output is deterministic: the same objects and options give byte-identical blobs.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <prt/format/scene_layout.h>

namespace prt::format {

// The column-major 4 x 4 identity: the rest placement of an object without a node.
constexpr std::array<float, 16> kSceneIdentity = {1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f,
                                                  0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};

struct SceneManifestObject {
  // The tag of the technique section its blob holds (e.g. PRT_BLOB_TAG_SHTR): four printable
  // ASCII characters; a tag no runtime knows is valid here (the runtime refuses it at load).
  std::uint32_t technique_tag = 0;
  std::string name;  // 1..255 bytes of UTF-8 without NUL
  // 1..1024 bytes of UTF-8: a '/'-separated path relative to the manifest's folder, without NUL,
  // '\', ':', a leading '/' or a component that is empty, "." or "..".
  std::string blob;
  std::uint32_t node = PRT_BLOB_SCNE_NO_NODE;   // the glTF node
  std::array<float, 16> rest = kSceneIdentity;  // column-major world matrix at rest: finite,
                                                // last row 0 0 0 1
};

struct SceneManifestOptions {
  std::string producer;  // the header's producer (BlobWriter::set_producer); empty: zero bytes
  std::string info;      // the text of an INFO section (UTF-8); empty: no INFO section
};

// The manifest blob: INFO (when options.info is not empty), then SCNE (required, uncompressed),
// its strings concatenated in record order, each record's name then its blob path. Throws
// std::invalid_argument, naming the object and field, for objects full validation would refuse
// (more than PRT_BLOB_SCNE_MAX_OBJECTS, a bad tag, name, path or rest matrix) and for an INFO
// text that is not UTF-8. Names are not checked to be distinct (the baker makes them so).
std::vector<std::uint8_t> write_scene_manifest(const std::vector<SceneManifestObject>& objects,
                                               const SceneManifestOptions& options = {});

}  // namespace prt::format
