# Runs `prt-bake inspect` on broken files written here and checks the exit code and message.
# Inputs: PRT_BAKE (the executable), SCRATCH (a folder it may write), PRT_SHARED_DIR.
file(REMOVE_RECURSE ${SCRATCH})
file(MAKE_DIRECTORY ${SCRATCH})

function(expect_failure file pattern)
  execute_process(COMMAND ${PRT_BAKE} inspect ${ARGN} ${file}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "prt-bake inspect ${file} exited 0 on broken input:\n${out}${err}")
  endif()
  string(REGEX MATCH "${pattern}" found "${err}")
  if(NOT found)
    message(FATAL_ERROR "prt-bake inspect ${file}: stderr does not match '${pattern}':\n${err}")
  endif()
  message(STATUS "ok (exit ${rc}): ${err}")
endfunction()

# A glTF whose external buffer is missing.
file(WRITE ${SCRATCH}/missing_buffer.gltf [=[
{"asset": {"version": "2.0"},
 "buffers": [{"uri": "missing.bin", "byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
]=])
expect_failure(${SCRATCH}/missing_buffer.gltf "missing_buffer\\.gltf: buffer 0 .*missing\\.bin.*missing")

# Text that is not an image, named .hdr, given as the environment of a good scene.
file(WRITE ${SCRATCH}/triangle.obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
file(WRITE ${SCRATCH}/not_an_image.hdr "this is not a Radiance file\n")
expect_failure(${SCRATCH}/triangle.obj "not_an_image\\.hdr: not a Radiance \\.hdr image"
               --env ${SCRATCH}/not_an_image.hdr)

# An OBJ face that uses a vertex that does not exist.
file(WRITE ${SCRATCH}/bad_index.obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
expect_failure(${SCRATCH}/bad_index.obj "bad_index\\.obj:4: face vertex index 7 is out of range")

# The good scene inspects fine.
execute_process(COMMAND ${PRT_BAKE} inspect ${SCRATCH}/triangle.obj
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "triangles: *1")
  message(FATAL_ERROR "prt-bake inspect triangle.obj failed (${rc}):\n${out}${err}")
endif()
