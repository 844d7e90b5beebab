// SPDX-License-Identifier: MIT
// Rewrites a blob with every section stored uncompressed (codec none): the same header flags,
// producer, section order, tags, flags, layout versions, element counts and raw bytes, so the
// result decodes to exactly what the input decodes to (formats/golden/README.md):
//   prt_make_raw_golden IN.prtk OUT.prtk
// Only zstd is decoded here, so the output does not depend on the zstd version.
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <prt/format/blob_reader.h>
#include <prt/format/blob_writer.hpp>

namespace {

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The section's raw bytes: the stored bytes, or its one zstd frame decoded.
std::vector<uint8_t> raw_bytes(const std::vector<uint8_t>& blob, const prt_blob_section& s) {
  const uint8_t* stored = blob.data() + s.offset;
  if (s.codec == PRT_BLOB_CODEC_NONE) return std::vector<uint8_t>(stored, stored + s.stored_size);
  std::vector<uint8_t> raw(static_cast<size_t>(s.raw_size));
  const size_t n =
      ZSTD_decompress(raw.data(), raw.size(), stored, static_cast<size_t>(s.stored_size));
  if (ZSTD_isError(n) || n != raw.size())
    throw std::runtime_error("a zstd section does not decode to its raw size");
  return raw;
}

void make_raw(const std::string& in_path, const std::string& out_path) {
  const std::vector<uint8_t> blob = read_file(in_path);
  prt_blob_header h;
  char msg[256] = "";
  if (prt_blob_validate_structure(blob.data(), blob.size(), &h, msg, sizeof msg) != PRT_BLOB_OK ||
      prt_blob_verify_checksums(blob.data(), &h, msg, sizeof msg) != PRT_BLOB_OK)
    throw std::runtime_error(in_path + ": " + msg);
  if (h.header_size != PRT_BLOB_HEADER_SIZE)
    throw std::runtime_error(in_path + ": a header of other than 64 bytes cannot be rewritten");
  prt::format::BlobWriter writer;
  std::array<uint8_t, PRT_BLOB_PRODUCER_SIZE> producer;
  std::copy(std::begin(h.producer), std::end(h.producer), producer.begin());
  writer.set_producer(producer);
  writer.set_flags(h.flags);
  for (uint32_t i = 0; i < h.section_count; ++i) {
    prt_blob_section s;
    prt_blob_read_section(blob.data(), &h, i, &s);
    const std::vector<uint8_t> raw = raw_bytes(blob, s);
    prt::format::SectionOptions options;
    options.required = (s.flags & PRT_BLOB_SECTION_REQUIRED) != 0;
    options.layout_version = s.layout_version;
    writer.add_section(s.tag, raw.data(), raw.size(), s.element_count, options);
  }
  writer.write_file(out_path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.prtk OUT.prtk\n", argv[0]);
    return 2;
  }
  try {
    make_raw(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_make_raw_golden: %s\n", e.what());
    return 1;
  }
  return 0;
}
