// SPDX-License-Identifier: MIT
#include <prt/format/scene_writer.hpp>

#include <cstring>
#include <stdexcept>

#include <prt/format/blob_reader.h>
#include <prt/format/blob_writer.hpp>

namespace prt::format {
namespace {

// The sizes that must fit their u32 fields before anything is laid out; the rest of the rules is
// the reader's own check, run on the finished blob.
void check_sizes(const std::vector<SceneManifestObject>& objects) {
  if (objects.size() > PRT_BLOB_SCNE_MAX_OBJECTS)
    throw std::invalid_argument("scene manifest: " + std::to_string(objects.size()) +
                                " objects (must be at most " +
                                std::to_string(PRT_BLOB_SCNE_MAX_OBJECTS) + ")");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const SceneManifestObject& o = objects[i];
    const std::string object = "scene manifest: object " + std::to_string(i) + ": ";
    if (o.name.empty() || o.name.size() > PRT_BLOB_SCNE_MAX_NAME)
      throw std::invalid_argument(object + "name size " + std::to_string(o.name.size()) +
                                  " (must be 1.." + std::to_string(PRT_BLOB_SCNE_MAX_NAME) + ")");
    if (o.blob.empty() || o.blob.size() > PRT_BLOB_SCNE_MAX_PATH)
      throw std::invalid_argument(object + "blob path size " + std::to_string(o.blob.size()) +
                                  " (must be 1.." + std::to_string(PRT_BLOB_SCNE_MAX_PATH) + ")");
  }
}

void store_u32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
  prt_le_store_u32(bytes.data() + at, v);
}

// The SCNE section's bytes: header, records, then the string table.
std::vector<std::uint8_t> scne_bytes(const std::vector<SceneManifestObject>& objects) {
  std::string strings;
  for (const SceneManifestObject& o : objects) strings += o.name + o.blob;
  prt_blob_scne_header h;
  h.objects = static_cast<std::uint32_t>(objects.size());
  h.record_size = PRT_BLOB_SCNE_RECORD_SIZE;
  h.string_size = static_cast<std::uint32_t>(strings.size());  // <= 65536 * (255 + 1024)
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(prt_blob_scne_raw_size(&h)), 0);
  store_u32(bytes, PRT_BLOB_SCNE_OFF_OBJECTS, h.objects);
  store_u32(bytes, PRT_BLOB_SCNE_OFF_RECORD_SIZE, h.record_size);
  store_u32(bytes, PRT_BLOB_SCNE_OFF_STRING_SIZE, h.string_size);
  std::uint32_t offset = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const SceneManifestObject& o = objects[i];
    const std::size_t r = PRT_BLOB_SCNE_HEADER_SIZE + i * PRT_BLOB_SCNE_RECORD_SIZE;
    const auto name_size = static_cast<std::uint32_t>(o.name.size());
    const auto blob_size = static_cast<std::uint32_t>(o.blob.size());
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_TECHNIQUE, o.technique_tag);
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_NAME_OFFSET, offset);
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_NAME_SIZE, name_size);
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_BLOB_OFFSET, offset + name_size);
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_BLOB_SIZE, blob_size);
    store_u32(bytes, r + PRT_BLOB_SCNE_REC_NODE, o.node);
    for (std::size_t k = 0; k < 16; ++k) {
      std::uint32_t bits;
      std::memcpy(&bits, &o.rest[k], sizeof bits);
      store_u32(bytes, r + PRT_BLOB_SCNE_REC_REST + 4 * k, bits);
    }
    offset += name_size + blob_size;
  }
  if (!strings.empty())
    std::memcpy(bytes.data() + prt_blob_scne_strings(&h), strings.data(), strings.size());
  return bytes;
}

// Full validation of the finished blob (every section is stored as is), so that the writer
// refuses exactly what readers refuse, in their words.
void check_blob(const std::vector<std::uint8_t>& blob) {
  char msg[256] = "";
  prt_blob_header header;
  if (prt_blob_validate_structure(blob.data(), blob.size(), &header, msg, sizeof msg) !=
      PRT_BLOB_OK)
    throw std::logic_error(std::string("scene manifest: ") + msg);
  for (std::uint32_t i = 0; i < header.section_count; ++i) {
    prt_blob_section s;
    prt_blob_read_section(blob.data(), &header, i, &s);
    if (prt_blob_check_content(&s, blob.data() + s.offset, 0, msg, sizeof msg) != PRT_BLOB_OK)
      throw std::invalid_argument(std::string("scene manifest: ") + msg);
  }
}

}  // namespace

std::vector<std::uint8_t> write_scene_manifest(const std::vector<SceneManifestObject>& objects,
                                               const SceneManifestOptions& options) {
  check_sizes(objects);
  const std::vector<std::uint8_t> scne = scne_bytes(objects);
  SectionOptions required;
  required.required = true;  // a reader that does not know SCNE cannot load the scene
  BlobWriter writer;
  writer.set_producer(options.producer);
  if (!options.info.empty())
    writer.add_section(PRT_BLOB_TAG_INFO, options.info.data(), options.info.size(),
                       options.info.size());
  writer.add_section(PRT_BLOB_TAG_SCNE, scne.data(), scne.size(), objects.size(), required);
  std::vector<std::uint8_t> blob = writer.finish();
  check_blob(blob);
  return blob;
}

}  // namespace prt::format
