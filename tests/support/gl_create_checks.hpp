// SPDX-License-Identifier: MIT
// The refusals every technique's GL shader creation makes, checked the same way for each: an
// entry point the loader cannot give, a context older than GL 4.3, and buffers larger than the
// context's SSBO limit are PRT_ERROR_UNSUPPORTED_BACKEND, leave the shader null and say why in
// the context's message. Each technique's GL test gives how to create its shader.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>
#include <string>

#include "support/gl_test_util.hpp"

namespace prt_test {

// Creates the technique's shader for its asset in `context` through `loader`; the result, and
// whether the out-pointer was left null.
using TryCreateShader = std::function<prt_result(prt_context* context, prt_gl_loader_fn loader,
                                                 void* user, bool* shader_null)>;

inline void expect_refused(const TryCreateShader& create, prt_context* context,
                           prt_gl_loader_fn loader, void* user, const std::string& named) {
  bool shader_null = false;
  EXPECT_EQ(create(context, loader, user, &shader_null), PRT_ERROR_UNSUPPORTED_BACKEND) << named;
  EXPECT_TRUE(shader_null) << named;
  const std::string message = prt_context_last_message(context);
  EXPECT_NE(message.find(named), std::string::npos) << message;
}

// Each entry point in `names` hidden from the real loader in turn: refused, and named.
inline void expect_refused_without_entry_points(const TryCreateShader& create, prt_context* context,
                                                headless_gl* gl,
                                                std::initializer_list<const char*> names) {
  for (const char* name : names) {
    LoaderOverride loader;
    loader.gl = gl;
    loader.hidden = name;
    expect_refused(create, context, LoaderOverride::get, &loader, name);
  }
}

// A loader that answers GL 3.3: refused, naming the version.
inline void expect_refused_below_gl_43(const TryCreateShader& create, prt_context* context) {
  char lie[] = "version";
  expect_refused(create, context, lying_loader, lie, "3.3");
}

// A loader that answers a 1024-byte GL_MAX_SHADER_STORAGE_BLOCK_SIZE, for an asset whose
// buffers need more: refused, naming the limit.
inline void expect_refused_above_ssbo_limit(const TryCreateShader& create, prt_context* context) {
  char lie[] = "ssbo";
  expect_refused(create, context, lying_loader, lie, "1024");
}

}  // namespace prt_test
