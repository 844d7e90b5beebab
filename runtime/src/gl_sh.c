/* SPDX-License-Identifier: MIT */
/* The GL backend of `sh` shading (prt_gl.h). */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_sh_create(const prt_asset* asset, prt_gl_loader_fn loader, void* loader_user,
                            prt_gl_sh_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
void prt_gl_sh_destroy(prt_gl_sh_shader* shader) {
  (void)shader;
}
prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb, uint32_t first_vertex,
                           uint32_t vertex_count) {
  (void)shader, (void)light_rgb, (void)first_vertex, (void)vertex_count;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader) {
  (void)shader;
  return 0;
}
prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex, uint32_t vertex_count,
                          float* out_rgb) {
  (void)shader, (void)first_vertex, (void)vertex_count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#endif
