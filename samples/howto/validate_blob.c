/* SPDX-License-Identifier: MIT */
/* How to load a blob file with full validation and list its sections, using only the runtime's
 * C API. Usage: validate_blob FILE.prtk   (exit status 0 if the blob is valid, 1 if not)
 *
 * It shows the three things every integration needs: a context with a message callback (the
 * runtime never prints by itself), loading with a validation level, and the section queries. */
#include <prt/prt.h>

#include <stdio.h>

/* Messages from the runtime arrive here; the game decides where they go. */
static void print_message(void* user, prt_result result, prt_severity severity, const char* text) {
  static const char* const kSeverity[] = {"debug", "info", "warning", "error"};
  (void)user;
  fprintf(stderr, "prtkit %s (%s): %s\n", kSeverity[severity & 3], prt_result_string(result), text);
}

static const char* codec_name(prt_codec codec) {
  return codec == PRT_CODEC_ZSTD ? "zstd" : "none";
}

/* The name of the technique whose section this is ("sh", ...), from the runtime's registry; NULL
 * for the mesh sections every technique shares. */
static const char* technique_name(prt_technique technique) {
  prt_technique_info info = {0};
  info.struct_size = sizeof info;
  return prt_technique_get_info(technique, &info) == PRT_OK ? info.name : NULL;
}

int main(int argc, char** argv) {
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_asset_info info = {0};
  prt_result result;
  uint32_t i;

  if (argc != 2) {
    fprintf(stderr, "usage: %s FILE.prtk\n", argv[0]);
    return 2;
  }
  desc.struct_size = sizeof desc; /* every struct that may grow starts with its size */
  desc.message = print_message;   /* NULL allocator: malloc/free */
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;

  result = prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset);
  if (result != PRT_OK) { /* the callback has printed why */
    prt_context_destroy(context);
    return 1;
  }

  info.struct_size = sizeof info;
  prt_asset_get_info(asset, &info);
  printf("%s: prtkit blob format %u.%u, %llu bytes, %u sections, producer \"%.16s\"\n", argv[1],
         (unsigned)info.format_major, (unsigned)info.format_minor,
         (unsigned long long)info.total_size, (unsigned)info.section_count,
         (const char*)info.producer);
  for (i = 0; i < prt_asset_section_count(asset); ++i) {
    prt_section_info s = {0};
    const char* technique;
    char tag[5];
    int k;
    s.struct_size = sizeof s;
    prt_asset_get_section_info(asset, i, &s);
    for (k = 0; k < 4; ++k) tag[k] = (char)((s.tag >> (8 * k)) & 0xFF);
    tag[4] = '\0';
    technique = technique_name(s.technique);
    printf("  %u: '%s' v%u %-8s %-4s %8llu stored %8llu raw %8llu elements%s%s%s%s\n", (unsigned)i,
           tag, (unsigned)s.layout_version,
           (s.flags & PRT_SECTION_FLAG_REQUIRED) ? "required" : "optional", codec_name(s.codec),
           (unsigned long long)s.stored_size, (unsigned long long)s.raw_size,
           (unsigned long long)s.element_count, s.known ? "" : " (unknown kind, skipped)",
           technique ? " (technique " : "", technique ? technique : "", technique ? ")" : "");
  }
  printf("valid (full validation)\n");

  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return 0;
}
