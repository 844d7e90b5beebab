/* SPDX-License-Identifier: MIT */
/* Headless GL through EGL: surfaceless platform, then EGL devices, then a default-display
 * pbuffer (headless_gl.h). */
#include "headless_gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The few GL values used here (GL/glcorearb.h); GL itself is reached via eglGetProcAddress. */
#define HGL_GL_RENDERER 0x1F01
#define HGL_GL_MAJOR_VERSION 0x821B
#define HGL_GL_MINOR_VERSION 0x821C
typedef const unsigned char* (*hgl_get_string_fn)(unsigned int name);
typedef void (*hgl_get_integerv_fn)(unsigned int name, int* data);

/* Under AddressSanitizer, eglTerminate unloads the Mesa driver and LeakSanitizer then reports
 * Mesa's allocations from an unknown module, which no suppression can match; so sanitizer
 * builds leave the display initialised (the process ends soon after anyway). */
#if defined(__SANITIZE_ADDRESS__)
#define HGL_KEEP_DISPLAY 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HGL_KEEP_DISPLAY 1
#endif
#endif
#ifndef HGL_KEEP_DISPLAY
#define HGL_KEEP_DISPLAY 0
#endif

struct headless_gl {
  EGLDisplay display;
  EGLSurface surface;
  EGLContext context;
  char renderer[160];
};

/* Appends a formatted line to the caller's error buffer (always NUL-terminated). */
typedef struct error_log {
  char* text;
  size_t capacity;
} error_log;

static void log_append(error_log* log, const char* fmt, ...) {
  size_t used;
  va_list args;
  if (!log->text || log->capacity == 0) return;
  used = strlen(log->text);
  if (used + 1 >= log->capacity) return;
  va_start(args, fmt);
  vsnprintf(log->text + used, log->capacity - used, fmt, args);
  va_end(args);
}

static int has_extension(const char* list, const char* name) {
  size_t n = strlen(name);
  const char* p = list;
  if (!list) return 0;
  while ((p = strstr(p, name)) != NULL) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    p += n;
  }
  return 0;
}

void* headless_gl_get_proc(void* user, const char* name) {
  void (*fn)(void) = eglGetProcAddress(name);
  void* address;
  (void)user;
  /* Function-to-object pointer conversion through memcpy (equal sizes on POSIX). */
  memcpy(&address, &fn, sizeof address);
  return address;
}

static void release(headless_gl* gl) {
  if (gl->display == EGL_NO_DISPLAY) return;
  eglMakeCurrent(gl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (gl->context != EGL_NO_CONTEXT) eglDestroyContext(gl->display, gl->context);
  if (gl->surface != EGL_NO_SURFACE) eglDestroySurface(gl->display, gl->surface);
  if (!HGL_KEEP_DISPLAY) eglTerminate(gl->display);
  eglReleaseThread();
  gl->display = EGL_NO_DISPLAY;
  gl->context = EGL_NO_CONTEXT;
  gl->surface = EGL_NO_SURFACE;
}

/* Checks the current context: GL 4.3+, and records GL_RENDERER. */
static int check_current(headless_gl* gl, error_log* log, const char* how) {
  hgl_get_string_fn get_string;
  hgl_get_integerv_fn get_integerv;
  const unsigned char* renderer;
  int major = 0, minor = 0;
  void* p = headless_gl_get_proc(NULL, "glGetString");
  memcpy(&get_string, &p, sizeof p);
  p = headless_gl_get_proc(NULL, "glGetIntegerv");
  memcpy(&get_integerv, &p, sizeof p);
  if (!get_string || !get_integerv) {
    log_append(log, "%s: no glGetString/glGetIntegerv; ", how);
    return 0;
  }
  get_integerv(HGL_GL_MAJOR_VERSION, &major);
  get_integerv(HGL_GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 3)) {
    log_append(log, "%s: GL %d.%d < 4.3; ", how, major, minor);
    return 0;
  }
  renderer = get_string(HGL_GL_RENDERER);
  snprintf(gl->renderer, sizeof gl->renderer, "%s", renderer ? (const char*)renderer : "?");
  return 1;
}

/* Initialises `display` and makes a GL 4.3 core context current on it: without a surface when
 * the display allows it and a pbuffer is not required, else with a 16x16 pbuffer. */
static int make_current(headless_gl* gl, EGLDisplay display, int need_pbuffer, error_log* log,
                        const char* how) {
  static const EGLint kConfig[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT, EGL_NONE};
  static const EGLint kContext[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    4,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  static const EGLint kPbuffer[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
  EGLint major = 0, minor = 0, count = 0;
  EGLConfig config = (EGLConfig)0;
  const char* extensions;
  if (display == EGL_NO_DISPLAY) {
    log_append(log, "%s: no display (0x%x); ", how, (unsigned)eglGetError());
    return 0;
  }
  if (!eglInitialize(display, &major, &minor)) {
    log_append(log, "%s: eglInitialize failed (0x%x); ", how, (unsigned)eglGetError());
    return 0;
  }
  gl->display = display;
  extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) need_pbuffer = 1;
  if (!eglBindAPI(EGL_OPENGL_API) || !eglChooseConfig(display, kConfig, &config, 1, &count) ||
      count < 1) {
    log_append(log, "%s: no pbuffer-capable desktop GL config (0x%x); ", how,
               (unsigned)eglGetError());
    release(gl);
    return 0;
  }
  gl->context = eglCreateContext(display, config, EGL_NO_CONTEXT, kContext);
  if (gl->context == EGL_NO_CONTEXT) {
    log_append(log, "%s: no GL 4.3 core context (0x%x); ", how, (unsigned)eglGetError());
    release(gl);
    return 0;
  }
  if (need_pbuffer) gl->surface = eglCreatePbufferSurface(display, config, kPbuffer);
  if ((need_pbuffer && gl->surface == EGL_NO_SURFACE) ||
      !eglMakeCurrent(display, gl->surface, gl->surface, gl->context)) {
    log_append(log, "%s: cannot make the context current (0x%x); ", how, (unsigned)eglGetError());
    release(gl);
    return 0;
  }
  if (!check_current(gl, log, how)) {
    release(gl);
    return 0;
  }
  return 1;
}

static int try_surfaceless(headless_gl* gl, const char* client_extensions, error_log* log) {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display;
  if (!has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    log_append(log, "surfaceless: EGL_MESA_platform_surfaceless missing; ");
    return 0;
  }
  get_platform_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!get_platform_display) return 0;
  return make_current(
      gl, get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL), 0, log,
      "surfaceless");
}

static int try_devices(headless_gl* gl, const char* client_extensions, error_log* log) {
  PFNEGLQUERYDEVICESEXTPROC query_devices;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display;
  EGLDeviceEXT devices[16];
  EGLint count = 0, i;
  if (!has_extension(client_extensions, "EGL_EXT_platform_device")) {
    log_append(log, "device: EGL_EXT_platform_device missing; ");
    return 0;
  }
  query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  get_platform_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!query_devices || !get_platform_display || !query_devices(16, devices, &count)) {
    log_append(log, "device: eglQueryDevicesEXT failed; ");
    return 0;
  }
  for (i = 0; i < count; ++i) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
    if (make_current(gl, display, 0, log, "device")) return 1;
  }
  if (count == 0) log_append(log, "device: no EGL devices; ");
  return 0;
}

static int try_default_pbuffer(headless_gl* gl, error_log* log) {
  return make_current(gl, eglGetDisplay(EGL_DEFAULT_DISPLAY), 1, log, "default display");
}

/* HEADLESS_GL_PATH=surfaceless|device|pbuffer restricts creation to that one way. */
static int allowed(const char* only, const char* path) {
  return !only || !*only || strcmp(only, path) == 0;
}

headless_gl* headless_gl_create(char* error, size_t error_capacity) {
  error_log log;
  const char* client_extensions;
  const char* only;
  headless_gl* gl = (headless_gl*)calloc(1, sizeof *gl);
  log.text = error;
  log.capacity = error_capacity;
  if (error && error_capacity > 0) error[0] = '\0';
  if (!gl) {
    log_append(&log, "out of memory");
    return NULL;
  }
  gl->display = EGL_NO_DISPLAY;
  gl->context = EGL_NO_CONTEXT;
  gl->surface = EGL_NO_SURFACE;
  /* NULL without EGL_EXT_client_extensions; then only the default display can work. */
  client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  only = getenv("HEADLESS_GL_PATH");
  if ((allowed(only, "surfaceless") && try_surfaceless(gl, client_extensions, &log)) ||
      (allowed(only, "device") && try_devices(gl, client_extensions, &log)) ||
      (allowed(only, "pbuffer") && try_default_pbuffer(gl, &log))) {
    if (error && error_capacity > 0) error[0] = '\0';
    return gl;
  }
  free(gl);
  return NULL;
}

void headless_gl_destroy(headless_gl* gl) {
  if (!gl) return;
  release(gl);
  free(gl);
}

const char* headless_gl_renderer(const headless_gl* gl) {
  return gl ? gl->renderer : "";
}
