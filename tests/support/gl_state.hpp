// SPDX-License-Identifier: MIT
// The GL state a shade call must leave behind, checked through GL itself: no program and no
// buffer bound where the backend binds its own (the generic and the first indexed SSBO and
// uniform buffer bindings), no error raised, and the output buffer's bytes as GL holds them.
// The entry points come from the headless context's loader (GL/glcorearb.h names and values).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "headless_gl.h"

namespace prt_test {

namespace gl_names {
constexpr unsigned kGlCopyReadBuffer = 0x8F36, kGlBufferSize = 0x8764,
                   kGlShaderStorageBufferBinding = 0x90D3, kGlCurrentProgram = 0x8B8D,
                   kGlUniformBufferBinding = 0x8A28;
using BindBufferFn = void (*)(unsigned, unsigned);
using GetErrorFn = unsigned (*)(void);
using GetBufferSubDataFn = void (*)(unsigned, ptrdiff_t, ptrdiff_t, void*);
using GetBufferParameterivFn = void (*)(unsigned, unsigned, int*);
using GetIntegervFn = void (*)(unsigned, int*);
using GetIntegeriVFn = void (*)(unsigned, unsigned, int*);
using GetInteger64vFn = void (*)(unsigned, int64_t*);
}  // namespace gl_names

template <typename Fn>
Fn gl_function(const char* name) {
  void* address = headless_gl_get_proc(nullptr, name);
  Fn fn = nullptr;
  std::memcpy(&fn, &address, sizeof fn);
  return fn;
}

template <typename Fn>
void* as_address(Fn fn) {
  void* address;
  std::memcpy(&address, &fn, sizeof address);
  return address;
}

// Expects the bindings a shade call uses to be back to 0: the current program, the generic SSBO
// binding, and SSBO and uniform buffer bindings 0 to 3.
inline void expect_gl_bindings_cleared() {
  using namespace gl_names;
  auto get_integerv = gl_function<GetIntegervFn>("glGetIntegerv");
  auto get_integeri_v = gl_function<GetIntegeriVFn>("glGetIntegeri_v");
  int value = -1;
  get_integerv(kGlCurrentProgram, &value);
  EXPECT_EQ(value, 0) << "current program";
  value = -1;
  get_integerv(kGlShaderStorageBufferBinding, &value);
  EXPECT_EQ(value, 0) << "generic SSBO binding";
  for (unsigned i = 0; i < 4; ++i) {
    value = -1;
    get_integeri_v(kGlShaderStorageBufferBinding, i, &value);
    EXPECT_EQ(value, 0) << "indexed SSBO binding " << i;
    value = -1;
    get_integeri_v(kGlUniformBufferBinding, i, &value);
    EXPECT_EQ(value, 0) << "indexed uniform buffer binding " << i;
  }
}

// The whole of GL buffer `buffer` as floats, read through GL (bound to GL_COPY_READ_BUFFER for
// the read, unbound after); `bytes` is set to its size in bytes.
inline std::vector<float> read_gl_buffer_floats(unsigned buffer, int* bytes) {
  using namespace gl_names;
  auto bind = gl_function<BindBufferFn>("glBindBuffer");
  auto get_sub_data = gl_function<GetBufferSubDataFn>("glGetBufferSubData");
  auto get_parameter = gl_function<GetBufferParameterivFn>("glGetBufferParameteriv");
  bind(kGlCopyReadBuffer, buffer);
  *bytes = 0;
  get_parameter(kGlCopyReadBuffer, kGlBufferSize, bytes);
  std::vector<uint8_t> raw(static_cast<size_t>(*bytes > 0 ? *bytes : 0));
  if (!raw.empty()) get_sub_data(kGlCopyReadBuffer, 0, ptrdiff_t(raw.size()), raw.data());
  bind(kGlCopyReadBuffer, 0);
  std::vector<float> values(raw.size() / 4);
  if (!values.empty()) std::memcpy(values.data(), raw.data(), 4 * values.size());
  return values;
}

// Leaves GL_INVALID_ENUM pending, as an application's earlier mistake would.
inline void leave_gl_error_pending() {
  gl_function<gl_names::BindBufferFn>("glBindBuffer")(0x1234u, 0);  // not a buffer target
}

// glGetError: the oldest pending error (0 when none), which it clears.
inline unsigned take_gl_error() {
  return gl_function<gl_names::GetErrorFn>("glGetError")();
}

// After a backend call (named in failures by `after`): the bindings cleared and no GL error left
// pending.
inline void expect_gl_state_restored(const std::string& after) {
  SCOPED_TRACE("GL state after " + after);
  expect_gl_bindings_cleared();
  EXPECT_EQ(take_gl_error(), 0u);
}

}  // namespace prt_test
