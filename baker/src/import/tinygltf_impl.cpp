// SPDX-License-Identifier: MIT
// The one tinygltf implementation TU, with Draco (KHR_draco_mesh_compression). It links the
// shared draco::draco: libdraco embeds its own tinygltf, and the static library would clash
// with it. stb's implementation comes from libstb.so.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
