/* SPDX-License-Identifier: MIT */
/* Private to the runtime: what the shadowfield GL backend (shadowfield_gl.c) and its compute
 * shader (shadowfield_gl_glsl.c) share: the layout of an instance's record in the frame buffer,
 * in 32-bit words (a float, or a uint stored by its bits), which the shader reads by these
 * offsets, and the shader's stages. */
#ifndef PRT_RUNTIME_SHADOWFIELD_GL_INTERNAL_H
#define PRT_RUNTIME_SHADOWFIELD_GL_INTERNAL_H

#include "shadowfield_scene.h"

/* The record of one instance: a header, then one pair block per other instance that affects it.
 * Offsets marked (u) are uints; buffer offsets count floats. */
#define PRT_SF_GL_VERTICES 0u     /* (u) the object's vertex count */
#define PRT_SF_GL_TERMS 1u        /* (u) BRDF terms K */
#define PRT_SF_GL_GLOSSY 2u       /* (u) 1: g read from the g table */
#define PRT_SF_GL_BRDF_GRID 3u    /* (u) G */
#define PRT_SF_GL_POSITIONS 4u    /* (u) offsets in the object buffer */
#define PRT_SF_GL_NORMALS 5u      /* (u) */
#define PRT_SF_GL_ALBEDO 6u       /* (u) */
#define PRT_SF_GL_TRANSFER 7u     /* (u) */
#define PRT_SF_GL_G_TABLE 8u      /* (u) */
#define PRT_SF_GL_INCIDENT 9u     /* (u) the instance's passes in the incident buffer */
#define PRT_SF_GL_OUTPUT 10u      /* (u) the instance's first float in the radiance buffer */
#define PRT_SF_GL_PAIR_COUNT 11u  /* (u) */
#define PRT_SF_GL_ROTATION 12u    /* 9 floats, row-major */
#define PRT_SF_GL_TRANSLATION 21u /* 3 */
#define PRT_SF_GL_SCALE 24u
#define PRT_SF_GL_EYE 25u /* 3 */
/* A source's basis projection and the field it casts from it: */
#define PRT_SF_GL_SRF 28u            /* (u) the object's SRF in the object buffer */
#define PRT_SF_GL_BASIS 29u          /* (u) basis functions N (0: no field) */
#define PRT_SF_GL_OWN_FIELD 30u      /* (u) the instance's field in the field buffer */
#define PRT_SF_GL_FIELD_POINTS 31u   /* (u) SRF points */
#define PRT_SF_GL_BASIS_VALUES 32u   /* (u) B (N x V) in the object buffer */
#define PRT_SF_GL_VERTEX_WEIGHTS 33u /* (u) W (V) */
#define PRT_SF_GL_BASIS_INVERSE 34u  /* (u) A^-1 (N x N) */
#define PRT_SF_GL_PROBE_COUNT 35u    /* (u) bounce probes this frame (0: bounces per vertex) */
#define PRT_SF_GL_LIGHT 36u          /* the light in the instance's frame, [3 i + c] */
#define PRT_SF_GL_PRODUCT (PRT_SF_GL_LIGHT + 3u * PRT_SF_MAX_COEFFS) /* light_product, 3 n^4 */
/* Bounce probes, in the probe buffer: the object's probe positions (3 a probe) and vertex
 * lookups (16 words a vertex: 8 probe indices (u), 8 weights, unused ones weight 0), and the
 * instance's probe light ([p 3 n^2 + 3 i + c]). */
#define PRT_SF_GL_PROBE_POSITIONS (PRT_SF_GL_PRODUCT + 3u * PRT_SF_MAX_COEFFS * PRT_SF_MAX_COEFFS)
#define PRT_SF_GL_PROBE_LOOKUPS (PRT_SF_GL_PROBE_POSITIONS + 1u)
#define PRT_SF_GL_PROBE_LIGHT (PRT_SF_GL_PROBE_POSITIONS + 2u)
#define PRT_SF_GL_HEADER (PRT_SF_GL_PROBE_POSITIONS + 3u)

/* A pair block, from its first word. A grid is centre (3), radius, inner, outer, shells (u),
 * face size (u). */
#define PRT_SF_GL_OCCLUDES 0u     /* (u) */
#define PRT_SF_GL_LIGHTS 1u       /* (u) */
#define PRT_SF_GL_TO_OTHER 2u     /* 9 */
#define PRT_SF_GL_OFFSET 11u      /* 3 */
#define PRT_SF_GL_OOF_GRID 14u    /* 8 */
#define PRT_SF_GL_OOF 22u         /* (u) the other's OOF in the object buffer */
#define PRT_SF_GL_SRF_GRID 23u    /* 8 */
#define PRT_SF_GL_FIELD 31u       /* (u) the other's source field in the field buffer */
#define PRT_SF_GL_FIELD_PLANE 32u /* (u) floats per colour plane of that field */
#define PRT_SF_GL_SH_ROTATION 33u /* PRT_SF_ROTATION_FLOATS */
#define PRT_SF_GL_PAIR_FLOATS (PRT_SF_GL_SH_ROTATION + PRT_SF_ROTATION_FLOATS)
#define PRT_SF_GL_GRID_FLOATS 8u

/* The shader's stages (its `stage` uniform). */
#define PRT_SF_GL_STAGE_DIRECT 0u
#define PRT_SF_GL_STAGE_BOUNCE 1u
#define PRT_SF_GL_STAGE_OUTPUT 2u
#define PRT_SF_GL_STAGE_CAST 3u    /* one invocation per SRF point and coefficient */
#define PRT_SF_GL_STAGE_PROJECT 4u /* one invocation per basis function, term and colour */
#define PRT_SF_GL_STAGE_WEIGHTS 5u /* the same */
#define PRT_SF_GL_STAGE_PROBES 6u  /* one invocation per bounce probe: its light */

/* Vertices per work group. */
#define PRT_SF_GL_LOCAL_SIZE 64u
/* Scratch floats per invocation: 7 rows of order^2 (shadowfield_gl_glsl.c) and a lookup's 8
 * indices and 8 weights. */
#define PRT_SF_GL_SCRATCH_FLOATS(order) (7u * (order) * (order) + 16u)

/* The compute shader's body; it follows a header the backend writes: the #version line,
 * LOCAL_SIZE and every PRT_SF_GL_* record offset above without its prefix. */
extern const char prt_sf_gl_shader_source[];

/* ---- What the backend's two files share (shadowfield_gl.c creates, shadowfield_gl_frame.c
 * runs a frame). ---- */
#include "../gl_functions.h"

/* The buffers, by their binding in the shader. */
enum {
  PRT_SF_GL_BUFFER_OBJECTS = 0,  /* every object's vertices, transfer, g table and OOF (or its
                                    log field with the log-space product) */
  PRT_SF_GL_BUFFER_GAUNT = 1,    /* the triple-product tensor, then the exponential's rule */
  PRT_SF_GL_BUFFER_FIELDS = 2,   /* every source's field of the last projected pass */
  PRT_SF_GL_BUFFER_INCIDENT = 3, /* every instance's light per pass, vertex and term */
  PRT_SF_GL_BUFFER_RADIANCE = 4, /* every instance's outgoing radiance */
  PRT_SF_GL_BUFFER_FRAME = 5,    /* every instance's record of the frame */
  PRT_SF_GL_BUFFER_SCRATCH = 6,  /* each invocation's SH vectors (shadowfield_gl_glsl.c) */
  PRT_SF_GL_BUFFER_PROBES = 7,   /* bounce probes: layouts and light (laid out per spacing) */
  PRT_SF_GL_BUFFER_COUNT = 8
};
enum {
  PRT_SF_GL_UNIFORM_RECORD = 0,
  PRT_SF_GL_UNIFORM_STAGE = 1,
  PRT_SF_GL_UNIFORM_PASS = 2,
  PRT_SF_GL_UNIFORM_FIRST_VERTEX = 3,
  PRT_SF_GL_UNIFORM_ORDER = 4
};

/* Vertices per dispatch: each has its scratch rows, so this bounds the scratch buffer. */
#define PRT_SF_GL_CHUNK_VERTICES 16384u

/* Where an object's arrays start in the object buffer (floats). */
typedef struct prt_sf_gl_object {
  uint32_t positions, normals, albedo, transfer, g_table, oof, srf;
  uint32_t basis, vertex_weights, basis_inverse;
  uint32_t probe_positions, probe_lookups; /* in the probe buffer */
} prt_sf_gl_object;

/* Where an instance's arrays start: incident and field (floats), radiance (vertices), and its
 * record in the frame buffer (floats, set per frame). */
typedef struct prt_sf_gl_instance {
  uint32_t incident, field, radiance_vertex, record;
  uint32_t probe_light; /* in the probe buffer */
} prt_sf_gl_instance;

struct prt_gl_shadowfield {
  prt_allocator allocator; /* the scene's context's */
  prt_gl_functions gl;
  prt_shadowfield_scene* scene;
  uint32_t object_count, instance_count; /* the scene's when created */
  prt_shadowfield_product product;       /* the scene's when created */
  prt_GLuint program;
  prt_GLuint buffers[PRT_SF_GL_BUFFER_COUNT];
  prt_sf_gl_object* objects;
  prt_sf_gl_instance* instances;
  uint32_t radiance_vertices;
  float* frame;               /* the records, uploaded to PRT_SF_GL_BUFFER_FRAME */
  size_t frame_capacity;      /* floats in `frame` */
  size_t frame_buffer_floats; /* floats in PRT_SF_GL_BUFFER_FRAME */
  /* The probe spacing whose layouts the probe buffer holds (-1 before the first). */
  float probe_spacing;
};

/* glBufferSubData of `count` floats at float `at` of the buffer bound to the SSBO target. */
void prt_sf_gl_upload(const prt_gl_functions* gl, uint32_t at, const float* values, uint64_t count);

#endif /* PRT_RUNTIME_SHADOWFIELD_GL_INTERNAL_H */
