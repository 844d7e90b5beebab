/* SPDX-License-Identifier: MIT */
/* Bounds-checked reader core (formats/SPEC.md §Validation). Offsets and sizes are checked as
 * integers, overflow-checked, before any pointer into the blob is formed from them. */
#include <prt/format/blob_reader.h>

#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const prt_blob_kind kKinds[] = {
    {PRT_BLOB_TAG_INFO, PRT_BLOB_LAYOUT_VERSION_1, 1u, "text (UTF-8)"},
    {PRT_BLOB_TAG_VPOS, PRT_BLOB_LAYOUT_VERSION_1, 12u, "vertex positions (3 x f32)"},
    {PRT_BLOB_TAG_VNRM, PRT_BLOB_LAYOUT_VERSION_1, 12u, "vertex normals (3 x f32)"},
    {PRT_BLOB_TAG_TRIS, PRT_BLOB_LAYOUT_VERSION_1, 12u, "triangles (3 x u32)"},
    {PRT_BLOB_TAG_SHTR, PRT_BLOB_LAYOUT_VERSION_1, 0u, "sh transfer (element = vertex)"},
    {PRT_BLOB_TAG_WVLT, PRT_BLOB_LAYOUT_VERSION_1, 0u, "wavelet transfer (element = vertex)"},
};

const prt_blob_kind* prt_blob_find_kind(uint32_t tag, uint8_t layout_version) {
  size_t i;
  for (i = 0; i < sizeof kKinds / sizeof kKinds[0]; ++i)
    if (kKinds[i].tag == tag && kKinds[i].layout_version == layout_version) return &kKinds[i];
  return NULL;
}

void prt_blob_tag_string(uint32_t tag, char out[5]) {
  int i;
  for (i = 0; i < 4; ++i) {
    char c = (char)((tag >> (8 * i)) & 0xFFu);
    out[i] = (c >= 0x20 && c <= 0x7E) ? c : '?';
  }
  out[4] = '\0';
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static prt_blob_status
fail(prt_blob_status status, char* msg, size_t cap, const char* fmt, ...) {
  if (msg && cap > 0) {
    va_list args;
    va_start(args, fmt);
    vsnprintf(msg, cap, fmt, args);
    va_end(args);
  }
  return status;
}

/* *sum = a + b; returns 0 on overflow. */
static int add_u64(uint64_t a, uint64_t b, uint64_t* sum) {
  if (a > UINT64_MAX - b) return 0;
  *sum = a + b;
  return 1;
}

/* *product = a * b; returns 0 on overflow. */
static int mul_u64(uint64_t a, uint64_t b, uint64_t* product) {
  if (a != 0 && b > UINT64_MAX / a) return 0;
  *product = a * b;
  return 1;
}

/* *out = x rounded up to a multiple of 16; returns 0 on overflow. */
static int align16_u64(uint64_t x, uint64_t* out) {
  if (x > UINT64_MAX - (PRT_BLOB_ALIGNMENT - 1)) return 0;
  *out = (x + (PRT_BLOB_ALIGNMENT - 1)) & ~(uint64_t)(PRT_BLOB_ALIGNMENT - 1);
  return 1;
}

static int is_zero(const uint8_t* p, size_t n) {
  size_t i;
  for (i = 0; i < n; ++i)
    if (p[i] != 0) return 0;
  return 1;
}

static void decode_header(const uint8_t* b, prt_blob_header* h) {
  h->version_major = prt_le_load_u16(b + PRT_BLOB_OFF_VERSION_MAJOR);
  h->version_minor = prt_le_load_u16(b + PRT_BLOB_OFF_VERSION_MINOR);
  h->header_size = prt_le_load_u32(b + PRT_BLOB_OFF_HEADER_SIZE);
  h->flags = prt_le_load_u32(b + PRT_BLOB_OFF_FLAGS);
  h->total_size = prt_le_load_u64(b + PRT_BLOB_OFF_TOTAL_SIZE);
  h->table_offset = prt_le_load_u64(b + PRT_BLOB_OFF_TABLE_OFFSET);
  h->section_count = prt_le_load_u32(b + PRT_BLOB_OFF_SECTION_COUNT);
  h->checksum = prt_le_load_u32(b + PRT_BLOB_OFF_CHECKSUM);
  memcpy(h->producer, b + PRT_BLOB_OFF_PRODUCER, PRT_BLOB_PRODUCER_SIZE);
}

/* Checks the fixed header against the byte count; on success the section table lies inside the
 * blob, starting at header_size. */
static prt_blob_status check_header(const uint8_t* b, size_t size, prt_blob_header* h, char* msg,
                                    size_t cap) {
  uint64_t table_bytes, table_end;
  if (size < 4) return fail(PRT_BLOB_TRUNCATED, msg, cap, "blob of %zu bytes is too short", size);
  if (b[0] != PRT_BLOB_MAGIC_0 || b[1] != PRT_BLOB_MAGIC_1 || b[2] != PRT_BLOB_MAGIC_2 ||
      b[3] != PRT_BLOB_MAGIC_3)
    return fail(PRT_BLOB_BAD_MAGIC, msg, cap, "not a prtkit blob (magic is not \"PRTK\")");
  if (size < PRT_BLOB_HEADER_SIZE)
    return fail(PRT_BLOB_TRUNCATED, msg, cap,
                "blob of %zu bytes is shorter than its 64-byte header", size);
  decode_header(b, h);
  if (h->version_major != PRT_BLOB_VERSION_MAJOR)
    return fail(PRT_BLOB_UNSUPPORTED_VERSION, msg, cap,
                "format version %u.%u is not supported (this reader reads %u.x)",
                (unsigned)h->version_major, (unsigned)h->version_minor,
                (unsigned)PRT_BLOB_VERSION_MAJOR);
  if (h->header_size < PRT_BLOB_HEADER_SIZE || h->header_size % PRT_BLOB_ALIGNMENT != 0)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "header size %" PRIu32 " is not a multiple of 16 >= 64",
                h->header_size);
  if (h->total_size > (uint64_t)size)
    return fail(PRT_BLOB_TRUNCATED, msg, cap,
                "blob is truncated: header says %" PRIu64 " bytes, %zu present", h->total_size,
                size);
  if (h->total_size < (uint64_t)size)
    return fail(PRT_BLOB_SIZE_MISMATCH, msg, cap,
                "blob has %zu bytes but its header says %" PRIu64 " (extra bytes)", size,
                h->total_size);
  if (h->header_size > h->total_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "header size %" PRIu32 " exceeds the blob size",
                h->header_size);
  if ((h->flags & PRT_BLOB_FLAGS_CRITICAL_MASK & ~PRT_BLOB_FLAGS_KNOWN) != 0)
    return fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                "unknown critical header flags 0x%04" PRIx32,
                h->flags & PRT_BLOB_FLAGS_CRITICAL_MASK);
  if (!is_zero(b + PRT_BLOB_OFF_RESERVED, PRT_BLOB_RESERVED_SIZE))
    return fail(PRT_BLOB_CORRUPT, msg, cap, "reserved header bytes are not zero");
  if (h->section_count > PRT_BLOB_MAX_SECTIONS)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section count %" PRIu32 " exceeds the maximum %u",
                h->section_count, PRT_BLOB_MAX_SECTIONS);
  if (h->table_offset != h->header_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section table offset %" PRIu64 " does not follow the %" PRIu32 "-byte header",
                h->table_offset, h->header_size);
  table_bytes = (uint64_t)h->section_count * PRT_BLOB_SECTION_ENTRY_SIZE; /* < 2^18, no overflow */
  if (!add_u64(h->table_offset, table_bytes, &table_end) || table_end > h->total_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section table (%" PRIu32 " entries) exceeds the blob",
                h->section_count);
  return PRT_BLOB_OK;
}

void prt_blob_read_section(const void* data, const prt_blob_header* header, uint32_t index,
                           prt_blob_section* s) {
  const uint8_t* e = (const uint8_t*)data + (size_t)header->table_offset +
                     (size_t)index * PRT_BLOB_SECTION_ENTRY_SIZE;
  s->tag = prt_le_load_u32(e + PRT_BLOB_SEC_OFF_TAG);
  s->flags = prt_le_load_u16(e + PRT_BLOB_SEC_OFF_FLAGS);
  s->codec = e[PRT_BLOB_SEC_OFF_CODEC];
  s->layout_version = e[PRT_BLOB_SEC_OFF_LAYOUT_VERSION];
  s->checksum = prt_le_load_u32(e + PRT_BLOB_SEC_OFF_CHECKSUM);
  s->offset = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_OFFSET);
  s->stored_size = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_STORED_SIZE);
  s->raw_size = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_RAW_SIZE);
  s->element_count = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_ELEMENT_COUNT);
}

static int tag_is_printable(uint32_t tag) {
  int i;
  for (i = 0; i < 4; ++i) {
    uint32_t c = (tag >> (8 * i)) & 0xFFu;
    if (c < 0x20 || c > 0x7E) return 0;
  }
  return 1;
}

/* Sizes and counts of one entry, given where it must start (`expected_offset`). */
static prt_blob_status check_entry(const uint8_t* b, const prt_blob_header* h, uint32_t i,
                                   const prt_blob_section* s, uint64_t expected_offset, char* msg,
                                   size_t cap) {
  char name[5];
  const prt_blob_kind* kind = prt_blob_find_kind(s->tag, s->layout_version);
  uint64_t end, bound;
  prt_blob_tag_string(s->tag, name);
  if (!tag_is_printable(s->tag))
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 ": tag is not printable ASCII", i);
  if ((s->flags & ~PRT_BLOB_SECTION_FLAGS_KNOWN) != 0)
    return fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                "section %" PRIu32 " '%s': unknown flags 0x%04x", i, name, (unsigned)s->flags);
  if (prt_le_load_u32(b + h->table_offset + (uint64_t)i * PRT_BLOB_SECTION_ENTRY_SIZE +
                      PRT_BLOB_SEC_OFF_RESERVED) != 0)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 " '%s': reserved field not zero", i,
                name);
  if (s->codec != PRT_BLOB_CODEC_NONE && s->codec != PRT_BLOB_CODEC_ZSTD)
    return fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                "section %" PRIu32 " '%s': unknown codec %u", i, name, (unsigned)s->codec);
  if (!kind && (s->flags & PRT_BLOB_SECTION_REQUIRED))
    return fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                "section %" PRIu32
                " '%s' layout version %u is required but not known to this "
                "reader",
                i, name, (unsigned)s->layout_version);
  if (s->offset != expected_offset)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section %" PRIu32 " '%s': offset %" PRIu64 " is not the expected %" PRIu64
                " (sections are packed in table order at 16-byte alignment)",
                i, name, s->offset, expected_offset);
  if (!add_u64(s->offset, s->stored_size, &end) || end > h->total_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section %" PRIu32 " '%s': %" PRIu64 " bytes at offset %" PRIu64
                " run past the end of the blob",
                i, name, s->stored_size, s->offset);
  if (s->codec == PRT_BLOB_CODEC_NONE && s->stored_size != s->raw_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section %" PRIu32 " '%s': uncompressed but stored size %" PRIu64
                " != raw size %" PRIu64,
                i, name, s->stored_size, s->raw_size);
  if (s->codec == PRT_BLOB_CODEC_ZSTD &&
      (s->stored_size < PRT_BLOB_ZSTD_MIN_FRAME ||
       !mul_u64(s->stored_size, PRT_BLOB_ZSTD_MAX_RATIO, &bound) || s->raw_size > bound))
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section %" PRIu32 " '%s': zstd sizes implausible (stored %" PRIu64 ", raw %" PRIu64
                ")",
                i, name, s->stored_size, s->raw_size);
  if (s->raw_size > (uint64_t)SIZE_MAX)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 " '%s': raw size too large", i,
                name);
  if (kind && kind->element_size != 0) {
    uint64_t expected_raw;
    if (!mul_u64(s->element_count, kind->element_size, &expected_raw) ||
        expected_raw != s->raw_size)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "section %" PRIu32 " '%s': %" PRIu64 " elements of %" PRIu32
                  " bytes do not make %" PRIu64 " raw bytes",
                  i, name, s->element_count, kind->element_size, s->raw_size);
  } else if (s->element_count > s->raw_size) {
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "section %" PRIu32 " '%s': %" PRIu64 " elements cannot fit in %" PRIu64 " bytes", i,
                name, s->element_count, s->raw_size);
  }
  return PRT_BLOB_OK;
}

/* Index of the known section with this tag, or -1. */
static long find_known(const void* data, const prt_blob_header* h, uint32_t tag,
                       prt_blob_section* out) {
  uint32_t i;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_read_section(data, h, i, out);
    if (out->tag == tag && prt_blob_find_kind(out->tag, out->layout_version)) return (long)i;
  }
  return -1;
}

/* Relations between kinds: TRIS, VNRM, SHTR and WVLT need VPOS; VNRM, SHTR and WVLT have one
 * element per vertex. */
static prt_blob_status check_dependencies(const void* data, const prt_blob_header* h, char* msg,
                                          size_t cap) {
  prt_blob_section vpos, other;
  int has_vpos = find_known(data, h, PRT_BLOB_TAG_VPOS, &vpos) >= 0;
  if (find_known(data, h, PRT_BLOB_TAG_TRIS, &other) >= 0 && !has_vpos)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "section 'TRIS' needs a 'VPOS' section");
  if (find_known(data, h, PRT_BLOB_TAG_VNRM, &other) >= 0) {
    if (!has_vpos) return fail(PRT_BLOB_CORRUPT, msg, cap, "section 'VNRM' needs a 'VPOS' section");
    if (other.element_count != vpos.element_count)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'VNRM' has %" PRIu64 " normals for %" PRIu64 " vertices", other.element_count,
                  vpos.element_count);
  }
  if (find_known(data, h, PRT_BLOB_TAG_SHTR, &other) >= 0) {
    if (!has_vpos) return fail(PRT_BLOB_CORRUPT, msg, cap, "section 'SHTR' needs a 'VPOS' section");
    if (other.element_count != vpos.element_count)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'SHTR' has %" PRIu64 " transfer vectors for %" PRIu64 " vertices",
                  other.element_count, vpos.element_count);
  }
  if (find_known(data, h, PRT_BLOB_TAG_WVLT, &other) >= 0) {
    if (!has_vpos) return fail(PRT_BLOB_CORRUPT, msg, cap, "section 'WVLT' needs a 'VPOS' section");
    if (other.element_count != vpos.element_count)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'WVLT' has %" PRIu64 " transfer rows for %" PRIu64 " vertices",
                  other.element_count, vpos.element_count);
  }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_validate_structure(const void* data, size_t size, prt_blob_header* header,
                                            char* msg, size_t cap) {
  const uint8_t* b = (const uint8_t*)data;
  prt_blob_header h;
  prt_blob_status st;
  uint64_t expected_offset = 0, end;
  uint32_t i, j;
  if (!data && size > 0) return fail(PRT_BLOB_INVALID_ARGUMENT, msg, cap, "blob pointer is NULL");
  if (!data) return fail(PRT_BLOB_TRUNCATED, msg, cap, "blob is empty");
  st = check_header(b, size, &h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  /* The table ends inside the blob (check_header), so this cannot overflow. */
  end = h.table_offset + (uint64_t)h.section_count * PRT_BLOB_SECTION_ENTRY_SIZE;
  for (i = 0; i < h.section_count; ++i) {
    prt_blob_section s;
    prt_blob_read_section(data, &h, i, &s);
    if (!align16_u64(end, &expected_offset))
      return fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 ": offset overflows", i);
    st = check_entry(b, &h, i, &s, expected_offset, msg, cap);
    if (st != PRT_BLOB_OK) return st;
    end = s.offset + s.stored_size; /* checked in check_entry */
    for (j = 0; j < i; ++j) {
      const uint8_t* earlier = b + h.table_offset + (uint64_t)j * PRT_BLOB_SECTION_ENTRY_SIZE;
      if (prt_le_load_u32(earlier + PRT_BLOB_SEC_OFF_TAG) == s.tag) {
        char name[5];
        prt_blob_tag_string(s.tag, name);
        return fail(PRT_BLOB_CORRUPT, msg, cap,
                    "sections %" PRIu32 " and %" PRIu32 " have the same tag '%s'", j, i, name);
      }
    }
  }
  if (!align16_u64(end, &expected_offset) || expected_offset != h.total_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "blob size %" PRIu64 " is not the end of its last section padded to 16 (%" PRIu64
                ")",
                h.total_size, expected_offset);
  st = check_dependencies(data, &h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if (header) *header = h;
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_verify_checksums(const void* data, const prt_blob_header* h, char* msg,
                                          size_t cap) {
  static const uint8_t kZeros[4] = {0, 0, 0, 0};
  const uint8_t* b = (const uint8_t*)data;
  size_t table_bytes = (size_t)h->section_count * PRT_BLOB_SECTION_ENTRY_SIZE;
  uint32_t crc, i;
  uint64_t end;
  crc = prt_crc32c(0, b, PRT_BLOB_OFF_CHECKSUM);
  crc = prt_crc32c(crc, kZeros, 4);
  crc = prt_crc32c(crc, b + PRT_BLOB_OFF_CHECKSUM + 4, h->header_size - PRT_BLOB_OFF_CHECKSUM - 4);
  crc = prt_crc32c(crc, b + h->table_offset, table_bytes);
  if (crc != h->checksum)
    return fail(PRT_BLOB_CHECKSUM_MISMATCH, msg, cap,
                "header checksum mismatch (stored 0x%08" PRIx32 ", computed 0x%08" PRIx32 ")",
                h->checksum, crc);
  end = h->table_offset + table_bytes;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_section s;
    char name[5];
    prt_blob_read_section(data, h, i, &s);
    prt_blob_tag_string(s.tag, name);
    if (!is_zero(b + end, (size_t)(s.offset - end)))
      return fail(PRT_BLOB_CORRUPT, msg, cap, "padding before section %" PRIu32 " '%s' is not zero",
                  i, name);
    crc = prt_crc32c(0, b + s.offset, (size_t)s.stored_size);
    if (crc != s.checksum)
      return fail(PRT_BLOB_CHECKSUM_MISMATCH, msg, cap,
                  "section %" PRIu32 " '%s': checksum mismatch (stored 0x%08" PRIx32
                  ", computed 0x%08" PRIx32 ")",
                  i, name, s.checksum, crc);
    end = s.offset + s.stored_size;
  }
  if (!is_zero(b + end, (size_t)(h->total_size - end)))
    return fail(PRT_BLOB_CORRUPT, msg, cap, "padding after the last section is not zero");
  return PRT_BLOB_OK;
}

/* Length of the well-formed UTF-8 sequence at p (n bytes left), or 0 if it is malformed. */
static size_t utf8_sequence_length(const uint8_t* p, size_t n) {
  uint32_t cp;
  size_t len, k;
  if (p[0] < 0x80) return 1;
  if (p[0] >= 0xC2 && p[0] <= 0xDF)
    len = 2, cp = p[0] & 0x1Fu;
  else if (p[0] >= 0xE0 && p[0] <= 0xEF)
    len = 3, cp = p[0] & 0x0Fu;
  else if (p[0] >= 0xF0 && p[0] <= 0xF4)
    len = 4, cp = p[0] & 0x07u;
  else
    return 0;
  if (len > n) return 0;
  for (k = 1; k < len; ++k) {
    if ((p[k] & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (p[k] & 0x3Fu);
  }
  if ((len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) || cp > 0x10FFFF ||
      (cp >= 0xD800 && cp <= 0xDFFF))
    return 0; /* overlong, out of range or a surrogate */
  return len;
}

static float load_f32(const uint8_t* p) {
  uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* The `sh` transfer section (SPEC.md, `sh` layout): header fields, exact size, zero padding,
 * finite offsets and finite non-negative scales. Quantised values need no check (any is valid). */
static prt_blob_status check_shtr(const prt_blob_section* s, const uint8_t* p, size_t n,
                                  uint64_t vertex_count, char* msg, size_t cap) {
  uint32_t order, vertices, channels, bits, coefficients, j;
  uint64_t params_end, payload_end, expected;
  if (n < PRT_BLOB_SHTR_HEADER_SIZE)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': %zu bytes cannot hold the 32-byte header", n);
  order = prt_le_load_u32(p);
  vertices = prt_le_load_u32(p + 4);
  channels = prt_le_load_u32(p + 8);
  bits = prt_le_load_u32(p + 12);
  if (order < 1 || order > PRT_BLOB_SHTR_MAX_ORDER)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': order %" PRIu32 " is not in 1..16", order);
  if (channels != 1 && channels != 3)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': %" PRIu32 " channels (must be 1 or 3)",
                channels);
  if (bits != 8 && bits != 16)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': %" PRIu32 " bits (must be 8 or 16)", bits);
  if (prt_le_load_u32(p + 24) != 0 || prt_le_load_u32(p + 28) != 0)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': reserved header fields are not zero");
  if ((uint64_t)vertices != vertex_count || (uint64_t)vertices != s->element_count)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "'SHTR': header says %" PRIu32 " vertices, element count %" PRIu64
                ", 'VPOS' has %" PRIu64,
                vertices, s->element_count, vertex_count);
  /* order <= 16, channels <= 3, vertices < 2^32: no overflow in 64 bits. */
  coefficients = channels * order * order;
  params_end = PRT_BLOB_SHTR_HEADER_SIZE + 8u * (uint64_t)coefficients;
  payload_end = params_end + (uint64_t)vertices * coefficients * (bits / 8u);
  expected = (payload_end + 3u) & ~(uint64_t)3u;
  if ((uint64_t)n != expected)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': %zu raw bytes, the header implies %" PRIu64, n,
                expected);
  if (!is_zero(p + payload_end, (size_t)(expected - payload_end)))
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': padding is not zero");
  for (j = 0; j < coefficients; ++j) {
    float offset = load_f32(p + PRT_BLOB_SHTR_HEADER_SIZE + 8u * j);
    float scale = load_f32(p + PRT_BLOB_SHTR_HEADER_SIZE + 8u * j + 4u);
    if (offset != offset || scale != scale || offset - offset != 0.0f || scale - scale != 0.0f)
      return fail(PRT_BLOB_NON_FINITE, msg, cap,
                  "'SHTR': offset or scale of coefficient %" PRIu32 " is not finite", j);
    if (scale < 0.0f)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'SHTR': scale of coefficient %" PRIu32 " is negative", j);
  }
  return PRT_BLOB_OK;
}

static int f32_is_finite(float f) {
  return f == f && f - f == 0.0f;
}

/* Band and vertex scales of a WVLT section: finite and >= 0. */
static prt_blob_status check_wvlt_scales(const uint8_t* p, const prt_blob_wvlt_layout* l,
                                         uint32_t vertices, char* msg, size_t cap) {
  uint32_t k, v, c;
  for (k = 0; k < l->bands; ++k) {
    float scale = load_f32(p + l->band_scale + 4u * k);
    if (!f32_is_finite(scale))
      return fail(PRT_BLOB_NON_FINITE, msg, cap, "'WVLT': band scale %" PRIu32 " is not finite", k);
    if (scale < 0.0f)
      return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': band scale %" PRIu32 " is negative", k);
  }
  for (v = 0; v < vertices; ++v)
    for (c = 0; c < 3; ++c) {
      float scale = load_f32(p + l->vertex_scale + 12u * (uint64_t)v + 4u * c);
      if (!f32_is_finite(scale))
        return fail(PRT_BLOB_NON_FINITE, msg, cap,
                    "'WVLT': vertex %" PRIu32 " scale %" PRIu32 " is not finite", v, c);
      if (scale < 0.0f)
        return fail(PRT_BLOB_CORRUPT, msg, cap,
                    "'WVLT': vertex %" PRIu32 " scale %" PRIu32 " is negative", v, c);
    }
  return PRT_BLOB_OK;
}

/* One block's pairs: indices strictly increasing, values in -127..127 and not 0. */
static prt_blob_status check_wvlt_block(const uint8_t* pairs, uint32_t count, uint32_t v,
                                        uint32_t k, char* msg, size_t cap) {
  uint32_t i;
  for (i = 0; i < count; ++i) {
    uint8_t value = pairs[2u * i + 1u];
    if (i > 0 && pairs[2u * i] <= pairs[2u * i - 2u])
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'WVLT': vertex %" PRIu32 " block %" PRIu32
                  ": index %u follows %u (indices must strictly increase)",
                  v, k, (unsigned)pairs[2u * i], (unsigned)pairs[2u * i - 2u]);
    if (value == 0u || value == 0x80u)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'WVLT': vertex %" PRIu32 " block %" PRIu32 " index %u: value %d is not allowed",
                  v, k, (unsigned)pairs[2u * i], value == 0u ? 0 : -128);
  }
  return PRT_BLOB_OK;
}

/* Row starts, block counts and pairs of a WVLT section (sizes already checked). */
static prt_blob_status check_wvlt_rows(const uint8_t* p, const prt_blob_wvlt_layout* l,
                                       uint32_t vertices, uint32_t pair_count, char* msg,
                                       size_t cap) {
  uint32_t v, k;
  if (prt_le_load_u32(p + l->row_start) != 0)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': row start of vertex 0 is not 0");
  for (v = 0; v < vertices; ++v) {
    const uint32_t start = prt_le_load_u32(p + l->row_start + 4u * (uint64_t)v);
    const uint32_t end = prt_le_load_u32(p + l->row_start + 4u * ((uint64_t)v + 1u));
    const uint8_t* counts = p + l->counts + 2u * (uint64_t)v * l->blocks;
    uint64_t at = start; /* <= pair_count: checked for the previous vertex (or 0) */
    if (end < start || end > pair_count)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'WVLT': row starts of vertex %" PRIu32 " (%" PRIu32 " .. %" PRIu32
                  ") are not increasing within the %" PRIu32 " pairs",
                  v, start, end, pair_count);
    for (k = 0; k < l->blocks; ++k) {
      const uint32_t count = prt_le_load_u16(counts + 2u * k);
      prt_blob_status st;
      if (count > PRT_BLOB_WVLT_BLOCK)
        return fail(PRT_BLOB_CORRUPT, msg, cap,
                    "'WVLT': vertex %" PRIu32 " block %" PRIu32 " counts %" PRIu32
                    " non-zeros (at most 256)",
                    v, k, count);
      if (at + count > end)
        return fail(PRT_BLOB_CORRUPT, msg, cap,
                    "'WVLT': vertex %" PRIu32 " block %" PRIu32
                    ": block counts exceed the row's %" PRIu32 " pairs",
                    v, k, end - start);
      st = check_wvlt_block(p + l->pairs + 2u * at, count, v, k, msg, cap);
      if (st != PRT_BLOB_OK) return st;
      at += count;
    }
    if (at != end)
      return fail(PRT_BLOB_CORRUPT, msg, cap,
                  "'WVLT': vertex %" PRIu32 ": block counts sum to %" PRIu64
                  " but the row has %" PRIu32 " pairs",
                  v, at - start, end - start);
  }
  return PRT_BLOB_OK;
}

/* The `wavelet` transfer section (SPEC.md §7.2): every header field, the exact size, zero
 * padding, finite non-negative scales, row starts, block counts, indices and values. */
static prt_blob_status check_wvlt(const prt_blob_section* s, const uint8_t* p, size_t n,
                                  uint64_t vertex_count, char* msg, size_t cap) {
  prt_blob_wvlt_layout l;
  uint32_t param, size, vertices, quantizer, pair_count;
  prt_blob_status st;
  if (n < PRT_BLOB_WVLT_HEADER_SIZE)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': %zu bytes cannot hold the 32-byte header", n);
  param = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PARAM);
  size = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_SIZE);
  vertices = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_VERTICES);
  quantizer = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_QUANTIZER);
  pair_count = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PAIR_COUNT);
  if (param != PRT_BLOB_WVLT_PARAM_CUBE && param != PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': param %" PRIu32 " is not 0 or 1", param);
  if (!prt_blob_wvlt_layout_of(param, size, vertices, pair_count, &l))
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "'WVLT': face size %" PRIu32 " is not a power of two in 16..128", size);
  if (quantizer > 1u)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': quantizer %" PRIu32 " is not 0 or 1",
                quantizer);
  if (prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_RESERVED) != 0)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': reserved header field is not zero");
  if ((uint64_t)vertices != vertex_count || (uint64_t)vertices != s->element_count)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "'WVLT': header says %" PRIu32 " vertices, element count %" PRIu64
                ", 'VPOS' has %" PRIu64,
                vertices, s->element_count, vertex_count);
  if ((uint64_t)n != l.raw_size)
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': %zu raw bytes, the header implies %" PRIu64, n,
                l.raw_size);
  if (!is_zero(p + l.payload_end, (size_t)(l.raw_size - l.payload_end)))
    return fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': padding is not zero");
  if (prt_le_load_u32(p + l.row_start + 4u * (uint64_t)vertices) != pair_count)
    return fail(PRT_BLOB_CORRUPT, msg, cap,
                "'WVLT': the last row start is not the pair count %" PRIu32, pair_count);
  st = check_wvlt_scales(p, &l, vertices, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  return check_wvlt_rows(p, &l, vertices, pair_count, msg, cap);
}

prt_blob_status prt_blob_check_content(const prt_blob_section* s, const void* raw,
                                       uint64_t vertex_count, char* msg, size_t cap) {
  const uint8_t* p = (const uint8_t*)raw;
  size_t n = (size_t)s->raw_size, i;
  char name[5];
  if (!prt_blob_find_kind(s->tag, s->layout_version)) return PRT_BLOB_OK;
  if (n > 0 && !raw) return fail(PRT_BLOB_INVALID_ARGUMENT, msg, cap, "section bytes are NULL");
  prt_blob_tag_string(s->tag, name);
  if (s->tag == PRT_BLOB_TAG_INFO) {
    for (i = 0; i < n;) {
      size_t len = utf8_sequence_length(p + i, n - i);
      if (len == 0) return fail(PRT_BLOB_CORRUPT, msg, cap, "'INFO' is not UTF-8 (byte %zu)", i);
      i += len;
    }
  } else if (s->tag == PRT_BLOB_TAG_VPOS || s->tag == PRT_BLOB_TAG_VNRM) {
    for (i = 0; i + 4 <= n; i += 4) {
      uint32_t bits = prt_le_load_u32(p + i);
      if ((bits & 0x7F800000u) == 0x7F800000u) /* exponent all ones: Inf or NaN */
        return fail(PRT_BLOB_NON_FINITE, msg, cap, "'%s': float %zu (element %zu) is not finite",
                    name, i / 4, i / 12);
    }
  } else if (s->tag == PRT_BLOB_TAG_TRIS) {
    for (i = 0; i + 4 <= n; i += 4) {
      uint32_t index = prt_le_load_u32(p + i);
      if ((uint64_t)index >= vertex_count)
        return fail(PRT_BLOB_INDEX_OUT_OF_RANGE, msg, cap,
                    "'TRIS': index %" PRIu32
                    " of triangle %zu is not below the vertex count %" PRIu64,
                    index, i / 12, vertex_count);
    }
  } else if (s->tag == PRT_BLOB_TAG_SHTR) {
    return check_shtr(s, p, n, vertex_count, msg, cap);
  } else if (s->tag == PRT_BLOB_TAG_WVLT) {
    return check_wvlt(s, p, n, vertex_count, msg, cap);
  }
  return PRT_BLOB_OK;
}
