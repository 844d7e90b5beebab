// SPDX-License-Identifier: MIT
// Blob writer: lays sections out canonically (formats/SPEC.md §Layout) and fills every checksum.
#include <prt/format/blob_writer.hpp>

#include <zstd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <prt/format/blob_reader.h>

namespace prt::format {
namespace {

std::string tag_name(uint32_t tag) {
  char name[5];
  prt_blob_tag_string(tag, name);
  return name;
}

bool tag_is_printable(uint32_t tag) {
  for (int i = 0; i < 4; ++i) {
    const uint32_t c = (tag >> (8 * i)) & 0xFFu;
    if (c < 0x20 || c > 0x7E) return false;
  }
  return true;
}

uint64_t align16(uint64_t x) {
  return (x + PRT_BLOB_ALIGNMENT - 1) & ~uint64_t{PRT_BLOB_ALIGNMENT - 1};
}

// One zstd frame with the content size recorded and no zstd checksum (the section CRC covers it).
std::vector<uint8_t> zstd_compress(const void* data, size_t size, int level) {
  std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> cctx(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!cctx) throw std::runtime_error("zstd: cannot create a compression context");
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_contentSizeFlag, 1);
  ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_checksumFlag, 0);
  std::vector<uint8_t> out(ZSTD_compressBound(size));
  const size_t n = ZSTD_compress2(cctx.get(), out.data(), out.size(), data, size);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

void check_sizes(uint32_t tag, uint8_t layout_version, size_t size, uint64_t element_count) {
  const prt_blob_kind* kind = prt_blob_find_kind(tag, layout_version);
  if (kind && kind->element_size != 0) {  // 0: variable size, checked at full validation
    if (element_count > UINT64_MAX / kind->element_size ||
        element_count * kind->element_size != size)
      throw std::invalid_argument("blob section '" + tag_name(tag) +
                                  "': " + std::to_string(element_count) + " elements of " +
                                  std::to_string(kind->element_size) +
                                  " bytes != " + std::to_string(size) + " bytes");
  } else if (element_count > size) {
    throw std::invalid_argument("blob section '" + tag_name(tag) +
                                "': " + std::to_string(element_count) + " elements in " +
                                std::to_string(size) + " bytes");
  }
}

}  // namespace

void BlobWriter::set_producer(std::string_view name) {
  producer_.fill(0);
  std::copy_n(name.begin(), std::min(name.size(), producer_.size()), producer_.begin());
}

void BlobWriter::add_section(uint32_t tag, const void* data, size_t size, uint64_t element_count,
                             const SectionOptions& options) {
  if (!tag_is_printable(tag))
    throw std::invalid_argument("blob section tag must be four printable ASCII characters");
  for (const Section& s : sections_)
    if (s.tag == tag)
      throw std::invalid_argument("blob section '" + tag_name(tag) + "' added twice");
  if (sections_.size() >= PRT_BLOB_MAX_SECTIONS)
    throw std::invalid_argument("blob: too many sections");
  if (size > 0 && data == nullptr) throw std::invalid_argument("blob section data is null");
  check_sizes(tag, options.layout_version, size, element_count);

  Section s{};
  s.tag = tag;
  s.flags = options.required ? PRT_BLOB_SECTION_REQUIRED : 0;
  s.codec = PRT_BLOB_CODEC_NONE;
  s.layout_version = options.layout_version;
  s.raw_size = size;
  s.element_count = element_count;
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (options.compression == Compression::kZstd && size > 0) {
    std::vector<uint8_t> packed = zstd_compress(data, size, options.zstd_level);
    if (packed.size() < size) {  // keep raw when zstd does not pay
      s.codec = PRT_BLOB_CODEC_ZSTD;
      s.stored = std::move(packed);
    }
  }
  if (s.codec == PRT_BLOB_CODEC_NONE) s.stored.assign(bytes, bytes + size);
  s.checksum = prt_crc32c(0, s.stored.data(), s.stored.size());
  sections_.push_back(std::move(s));
}

std::vector<uint8_t> BlobWriter::finish() const {
  const uint64_t table_offset = PRT_BLOB_HEADER_SIZE;
  const uint64_t table_end =
      table_offset + sections_.size() * uint64_t{PRT_BLOB_SECTION_ENTRY_SIZE};
  std::vector<uint64_t> offsets;
  uint64_t end = table_end;
  for (const Section& s : sections_) {
    offsets.push_back(align16(end));
    end = offsets.back() + s.stored.size();
  }
  std::vector<uint8_t> blob(align16(end), 0);  // zero padding everywhere

  uint8_t* h = blob.data();
  h[0] = PRT_BLOB_MAGIC_0, h[1] = PRT_BLOB_MAGIC_1, h[2] = PRT_BLOB_MAGIC_2,
  h[3] = PRT_BLOB_MAGIC_3;
  prt_le_store_u16(h + PRT_BLOB_OFF_VERSION_MAJOR, PRT_BLOB_VERSION_MAJOR);
  prt_le_store_u16(h + PRT_BLOB_OFF_VERSION_MINOR, PRT_BLOB_VERSION_MINOR);
  prt_le_store_u32(h + PRT_BLOB_OFF_HEADER_SIZE, PRT_BLOB_HEADER_SIZE);
  prt_le_store_u32(h + PRT_BLOB_OFF_FLAGS, flags_);
  prt_le_store_u64(h + PRT_BLOB_OFF_TOTAL_SIZE, blob.size());
  prt_le_store_u64(h + PRT_BLOB_OFF_TABLE_OFFSET, table_offset);
  prt_le_store_u32(h + PRT_BLOB_OFF_SECTION_COUNT, static_cast<uint32_t>(sections_.size()));
  std::memcpy(h + PRT_BLOB_OFF_PRODUCER, producer_.data(), producer_.size());

  for (size_t i = 0; i < sections_.size(); ++i) {
    const Section& s = sections_[i];
    uint8_t* e = blob.data() + table_offset + i * PRT_BLOB_SECTION_ENTRY_SIZE;
    prt_le_store_u32(e + PRT_BLOB_SEC_OFF_TAG, s.tag);
    prt_le_store_u16(e + PRT_BLOB_SEC_OFF_FLAGS, s.flags);
    e[PRT_BLOB_SEC_OFF_CODEC] = s.codec;
    e[PRT_BLOB_SEC_OFF_LAYOUT_VERSION] = s.layout_version;
    prt_le_store_u32(e + PRT_BLOB_SEC_OFF_CHECKSUM, s.checksum);
    prt_le_store_u64(e + PRT_BLOB_SEC_OFF_OFFSET, offsets[i]);
    prt_le_store_u64(e + PRT_BLOB_SEC_OFF_STORED_SIZE, s.stored.size());
    prt_le_store_u64(e + PRT_BLOB_SEC_OFF_RAW_SIZE, s.raw_size);
    prt_le_store_u64(e + PRT_BLOB_SEC_OFF_ELEMENT_COUNT, s.element_count);
    if (!s.stored.empty()) std::memcpy(blob.data() + offsets[i], s.stored.data(), s.stored.size());
  }

  // Header checksum: header with its checksum field as zero (it is zero now), then the table.
  const uint32_t crc = prt_crc32c(prt_crc32c(0, h, PRT_BLOB_HEADER_SIZE), h + table_offset,
                                  static_cast<size_t>(table_end - table_offset));
  prt_le_store_u32(h + PRT_BLOB_OFF_CHECKSUM, crc);

  // Self-check of the relations between kinds (e.g. 'TRIS' needs 'VPOS'); kinds this reader core
  // does not know yet are the caller's business.
  char msg[256];
  const prt_blob_status st =
      prt_blob_validate_structure(blob.data(), blob.size(), nullptr, msg, sizeof msg);
  if (st != PRT_BLOB_OK && st != PRT_BLOB_UNSUPPORTED_FEATURE)
    throw std::invalid_argument(std::string("blob writer: ") + msg);
  return blob;
}

void BlobWriter::write_file(const std::string& path) const {
  const std::vector<uint8_t> blob = finish();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot open '" + path + "' for writing");
  const bool ok = std::fwrite(blob.data(), 1, blob.size(), f) == blob.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace prt::format
