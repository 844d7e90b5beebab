/* SPDX-License-Identifier: MIT */
/* Loading a scene (prt_scene.h): the manifest's SCNE section checked in full whatever the
 * validation level (it is small, and every later read trusts it), each object's blob loaded and
 * checked to hold its technique's section, then each technique handed all its objects at once
 * (scene_internal.h). Whatever fails, nothing stays allocated and the message names the object. */
#include <stdio.h>

#include <prt/format/scene_layout.h>

#include "../techniques.h"
#include "scene_internal.h"

#define SCENE_DESC_SIZE_1_0 PRT_SIZE_THROUGH(prt_scene_desc, cloth_lobes)
#define OBJECT_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_scene_object_info, poses)
#define DEFAULT_CLOTH_LOBES 64u
#define MAX_PATH_BYTES 4096u

/* What a load needs besides the manifest's bytes. */
typedef struct load_request {
  const char* function; /* for messages */
  const char* manifest; /* the manifest's path or "<memory>", for messages */
  const char* base_dir; /* blobs' folder; NULL: as the paths are */
  prt_validation validation;
  prt_scene_blob_loader_fn load_blob;
  void* load_blob_user;
  uint32_t cloth_lobes;
} load_request;

static char* copy_string(const prt_allocator* allocator, const uint8_t* bytes, uint32_t size) {
  char* s = (char*)prt_internal_alloc(allocator, (size_t)size + 1, 1);
  if (s) {
    memcpy(s, bytes, size);
    s[size] = '\0';
  }
  return s;
}

static void free_string(const prt_allocator* allocator, char* s) {
  if (s) prt_internal_free(allocator, s, strlen(s) + 1);
}

void prt_scene_destroy(prt_scene* scene) {
  prt_allocator allocator;
  uint32_t i;
  if (!scene) return;
  allocator = scene->allocator;
  for (i = 0; i < scene->group_count; ++i) {
    prt_scene_group* g = &scene->groups[i];
    const prt_scene_hooks* hooks = g->technique->scene;
    if (g->state) {
      hooks->close(&allocator, g->state);
      prt_internal_free(&allocator, g->state, hooks->group_size);
    }
    prt_internal_free(&allocator, g->objects, sizeof *g->objects * (g->count ? g->count : 1));
  }
  for (i = 0; i < scene->object_count; ++i) {
    prt_scene_object* o = &scene->objects[i];
    free_string(&allocator, o->name);
    free_string(&allocator, o->blob);
    prt_asset_destroy(o->asset);
    prt_internal_free(&allocator, o->radiance, sizeof(float) * 3 * (size_t)o->vertex_count);
  }
  prt_internal_free(&allocator, scene->objects, sizeof *scene->objects * scene->object_count);
  prt_internal_free(&allocator, scene, sizeof *scene);
}

/* The SCNE section's bytes and header, checked in full. */
static prt_result read_manifest(prt_context* context, const load_request* req,
                                const prt_asset* manifest, const uint8_t** out_bytes,
                                prt_blob_scne_header* out_header) {
  const prt_asset_section* s;
  uint32_t index;
  char msg[PRT_MESSAGE_CAPACITY / 2];
  prt_blob_status st;
  if (prt_asset_find_section(manifest, PRT_BLOB_TAG_SCNE, &index) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_CORRUPT,
                             "%s: '%s' is not a scene manifest: it has no SCNE section",
                             req->function, req->manifest);
  s = &manifest->sections[index];
  if (s->entry.layout_version != PRT_BLOB_LAYOUT_VERSION_1 || !s->decoded)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_FEATURE,
                             "%s: '%s': SCNE layout version %u is not one this runtime reads",
                             req->function, req->manifest, (unsigned)s->entry.layout_version);
  st = prt_blob_check_content(&s->entry, s->data, 0, msg, sizeof msg);
  if (st == PRT_BLOB_OK && (s->entry.raw_size < PRT_BLOB_SCNE_HEADER_SIZE || !s->data)) {
    st = PRT_BLOB_CORRUPT;
    snprintf(msg, sizeof msg, "the SCNE section is shorter than its header");
  }
  if (st != PRT_BLOB_OK)
    return prt_internal_fail(context, (prt_result)st, "%s: '%s': %s", req->function, req->manifest,
                             msg);
  *out_bytes = s->data;
  prt_blob_scne_read_header(s->data, out_header);
  return PRT_OK;
}

static prt_result load_blob(prt_context* context, const load_request* req, const char* blob,
                            prt_asset** out_asset) {
  char path[MAX_PATH_BYTES];
  int n;
  if (req->load_blob)
    return req->load_blob(req->load_blob_user, context, blob, req->validation, out_asset);
  n = req->base_dir && req->base_dir[0] ? snprintf(path, sizeof path, "%s/%s", req->base_dir, blob)
                                        : snprintf(path, sizeof path, "%s", blob);
  if (n < 0 || (size_t)n >= sizeof path)
    return prt_internal_fail(context, PRT_ERROR_IO, "the blob's path is too long");
  return prt_asset_load_file(context, path, req->validation, out_asset);
}

/* Fails with the context's current message (the blob loader's) prefixed by the object. */
static prt_result fail_object(prt_context* context, const load_request* req,
                              const prt_scene_object* o, prt_result r, const char* what) {
  return prt_internal_fail(context, r, "%s: '%s', object '%s' (blob '%s'): %s", req->function,
                           req->manifest, o->name, o->blob, what);
}

/* Record i: its strings, its technique and its blob. */
static prt_result open_object(prt_scene* scene, const load_request* req, const uint8_t* bytes,
                              const prt_blob_scne_header* h, uint32_t i) {
  prt_scene_object* o = &scene->objects[i];
  const uint8_t* strings = bytes + prt_blob_scne_strings(h);
  prt_blob_scne_record rec;
  char tag[5];
  uint32_t vpos;
  prt_section_info info;
  prt_result r;
  prt_blob_scne_read_record(bytes, h, i, &rec);
  o->index = i;
  o->node = rec.node;
  memcpy(o->rest, rec.rest, sizeof o->rest);
  o->name = copy_string(&scene->allocator, strings + rec.name_offset, rec.name_size);
  o->blob = copy_string(&scene->allocator, strings + rec.blob_offset, rec.blob_size);
  if (!o->name || !o->blob)
    return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY,
                             "%s: out of memory for object %u's names", req->function, i);
  o->technique = prt_internal_technique_of_tag(rec.technique);
  prt_blob_tag_string(rec.technique, tag);
  if (!o->technique || !o->technique->scene) {
    char what[64];
    snprintf(what, sizeof what, "technique section '%s' is not one this runtime shades", tag);
    return fail_object(scene->context, req, o, PRT_ERROR_UNSUPPORTED_FEATURE, what);
  }
  r = load_blob(scene->context, req, o->blob, &o->asset);
  if (r != PRT_OK || !o->asset) {
    char what[PRT_MESSAGE_CAPACITY / 2];
    snprintf(what, sizeof what, "%s", prt_context_last_message(scene->context));
    return fail_object(scene->context, req, o, r != PRT_OK ? r : PRT_ERROR_IO, what);
  }
  if (!(prt_asset_techniques(o->asset) & (1u << o->technique->technique))) {
    char what[64];
    snprintf(what, sizeof what, "the blob has no '%s' section", tag);
    return fail_object(scene->context, req, o, PRT_ERROR_CORRUPT, what);
  }
  info.struct_size = sizeof info;
  if (prt_asset_find_section(o->asset, PRT_SECTION_VPOS, &vpos) != PRT_OK ||
      prt_asset_get_section_info(o->asset, vpos, &info) != PRT_OK)
    return fail_object(scene->context, req, o, PRT_ERROR_CORRUPT, "the blob has no VPOS mesh");
  o->vertex_count = (uint32_t)info.element_count;
  return PRT_OK;
}

/* The group of `technique`, added when it is the first object of it. */
static prt_scene_group* group_of(prt_scene* scene, const prt_technique_entry* technique,
                                 uint32_t* out_index) {
  uint32_t g;
  for (g = 0; g < scene->group_count; ++g)
    if (scene->groups[g].technique == technique) break;
  if (g == scene->group_count) {
    scene->groups[g].technique = technique;
    scene->group_count++;
  }
  *out_index = g;
  return &scene->groups[g];
}

/* Each technique's objects handed to its open hook, then every object's radiance buffer. */
static prt_result open_groups(prt_scene* scene, const load_request* req) {
  char msg[PRT_MESSAGE_CAPACITY / 2];
  uint32_t i, g;
  for (i = 0; i < scene->object_count; ++i)
    group_of(scene, scene->objects[i].technique, &scene->objects[i].group)->count++;
  for (g = 0; g < scene->group_count; ++g) {
    prt_scene_group* group = &scene->groups[g];
    const prt_scene_hooks* hooks = group->technique->scene;
    uint32_t n = 0;
    prt_result r;
    group->objects = (prt_scene_object**)prt_internal_alloc(
        &scene->allocator, sizeof *group->objects * group->count, 16);
    group->state = prt_internal_alloc(&scene->allocator, hooks->group_size, 16);
    if (group->state) memset(group->state, 0, hooks->group_size); /* close reads it as empty */
    if (!group->objects || !group->state)
      return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY,
                               "%s: out of memory for the '%s' objects", req->function,
                               group->technique->name);
    for (i = 0; i < scene->object_count; ++i)
      if (scene->objects[i].group == g) group->objects[n++] = &scene->objects[i];
    msg[0] = '\0';
    r = hooks->open(scene->context, &scene->allocator, &scene->options, group->state,
                    group->objects, group->count, msg, sizeof msg);
    if (r != PRT_OK)
      return prt_internal_fail(scene->context, r, "%s: '%s': %s", req->function, req->manifest,
                               msg);
  }
  for (i = 0; i < scene->object_count; ++i) {
    prt_scene_object* o = &scene->objects[i];
    const size_t bytes = sizeof(float) * 3 * (size_t)o->vertex_count;
    o->radiance = (float*)prt_internal_alloc(&scene->allocator, bytes, 16);
    if (!o->radiance)
      return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY,
                               "%s: out of memory for object '%s''s radiance", req->function,
                               o->name);
    memset(o->radiance, 0, bytes);
  }
  return PRT_OK;
}

static prt_result build(prt_context* context, const load_request* req, const prt_asset* manifest,
                        prt_scene* scene) {
  const uint8_t* bytes;
  prt_blob_scne_header h;
  uint32_t i;
  prt_result r = read_manifest(context, req, manifest, &bytes, &h);
  if (r != PRT_OK) return r;
  if (h.objects > 0) {
    scene->objects = (prt_scene_object*)prt_internal_alloc(&scene->allocator,
                                                           sizeof *scene->objects * h.objects, 16);
    if (!scene->objects)
      return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory for %u objects",
                               req->function, (unsigned)h.objects);
    memset(scene->objects, 0, sizeof *scene->objects * h.objects);
    scene->object_count = h.objects;
  }
  for (i = 0; i < h.objects; ++i) {
    r = open_object(scene, req, bytes, &h, i);
    if (r != PRT_OK) return r;
  }
  return open_groups(scene, req);
}

static prt_result load(prt_context* context, const load_request* req, const prt_asset* manifest,
                       prt_scene** out_scene) {
  prt_scene* scene = (prt_scene*)prt_internal_alloc(&context->allocator, sizeof *scene, 16);
  prt_result r;
  if (!scene)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory", req->function);
  memset(scene, 0, sizeof *scene);
  scene->context = context;
  scene->allocator = context->allocator;
  scene->options.cloth_lobes = req->cloth_lobes;
  r = build(context, req, manifest, scene);
  if (r != PRT_OK) {
    prt_scene_destroy(scene);
    return r;
  }
  *out_scene = scene;
  return PRT_OK;
}

/* The request of a load call, from its desc; PRT_ERROR_INVALID_ARGUMENT for a bad desc. */
static prt_result make_request(const prt_scene_desc* desc, const char* function,
                               load_request* req) {
  memset(req, 0, sizeof *req);
  req->function = function;
  req->cloth_lobes = DEFAULT_CLOTH_LOBES;
  if (!desc) return PRT_OK;
  if (!prt_internal_struct_size_ok(desc, SCENE_DESC_SIZE_1_0) ||
      (desc->validation != PRT_VALIDATE_QUICK && desc->validation != PRT_VALIDATE_FULL) ||
      desc->cloth_lobes > PRT_CLOTH_MAX_LOBES)
    return PRT_ERROR_INVALID_ARGUMENT;
  req->validation = desc->validation;
  req->load_blob = desc->load_blob;
  req->load_blob_user = desc->load_blob_user;
  req->base_dir = desc->base_dir;
  if (desc->cloth_lobes > 0) req->cloth_lobes = desc->cloth_lobes;
  return PRT_OK;
}

prt_result prt_scene_load_memory(prt_context* context, const void* data, size_t size,
                                 const prt_scene_desc* desc, prt_scene** out_scene) {
  load_request req;
  prt_asset* manifest = NULL;
  prt_result r;
  if (out_scene) *out_scene = NULL;
  if (!context || !out_scene || (!data && size > 0) ||
      make_request(desc, "prt_scene_load_memory", &req) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_load_memory: invalid argument");
  req.manifest = "<memory>";
  r = prt_asset_load_memory(context, data, size, req.validation, &manifest);
  if (r != PRT_OK) return r;
  r = load(context, &req, manifest, out_scene);
  prt_asset_destroy(manifest);
  return r;
}

prt_result prt_scene_load_file(prt_context* context, const char* path, const prt_scene_desc* desc,
                               prt_scene** out_scene) {
  load_request req;
  prt_asset* manifest = NULL;
  char folder[MAX_PATH_BYTES];
  const char* slash;
  prt_result r;
  if (out_scene) *out_scene = NULL;
  if (!context || !path || !out_scene || make_request(desc, "prt_scene_load_file", &req) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_load_file: invalid argument");
  slash = strrchr(path, '/');
  if ((size_t)(slash ? slash - path : 0) + 2 > sizeof folder)
    return prt_internal_fail(context, PRT_ERROR_IO, "prt_scene_load_file: path too long");
  if (!slash) {
    folder[0] = '\0';
  } else if (slash == path) {
    strcpy(folder, "/");
  } else {
    memcpy(folder, path, (size_t)(slash - path));
    folder[slash - path] = '\0';
  }
  req.manifest = path;
  if (!req.base_dir) req.base_dir = folder;
  r = prt_asset_load_file(context, path, req.validation, &manifest);
  if (r != PRT_OK) return r;
  r = load(context, &req, manifest, out_scene);
  prt_asset_destroy(manifest);
  return r;
}

uint32_t prt_scene_object_count(const prt_scene* scene) {
  return scene ? scene->object_count : 0;
}

prt_result prt_scene_get_object(const prt_scene* scene, uint32_t index,
                                prt_scene_object_info* out) {
  prt_scene_object_info info;
  const prt_scene_object* o;
  if (!scene || !out || !prt_internal_struct_size_ok(out, OBJECT_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (index >= scene->object_count) return PRT_ERROR_NOT_FOUND;
  o = &scene->objects[index];
  memset(&info, 0, sizeof info);
  info.struct_size = sizeof info;
  info.name = o->name;
  info.blob = o->blob;
  info.technique = o->technique->technique;
  info.node = o->node;
  memcpy(info.rest_transform, o->rest, sizeof info.rest_transform);
  info.asset = o->asset;
  info.vertex_count = o->vertex_count;
  info.moves = o->technique->scene->place != NULL;
  info.poses = o->technique->scene->pose != NULL;
  prt_internal_write_struct(out, &info, sizeof info);
  return PRT_OK;
}

prt_result prt_scene_find_object(const prt_scene* scene, const char* name, uint32_t* out_index) {
  uint32_t i;
  if (!scene || !name || !out_index) return PRT_ERROR_INVALID_ARGUMENT;
  for (i = 0; i < scene->object_count; ++i)
    if (strcmp(scene->objects[i].name, name) == 0) {
      *out_index = i;
      return PRT_OK;
    }
  return PRT_ERROR_NOT_FOUND;
}
