# prt_unity_build(<target>): with PRT_UNITY_BUILD, the target's C++ sources compile a batch at a
# time, one translation unit per batch, so the headers they share (Eigen, GLM, tinygltf, the
# standard library) are parsed and their templates instantiated once a batch, not once a file.
# File-local names must then differ between a target's files (an anonymous namespace is shared by
# its batch): helpers they have in common live in one header instead.
function(prt_unity_build target)
  if(PRT_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH
                                               UNITY_BUILD_BATCH_SIZE 16)
    # GCC warns of a class with a field of a file-local type unless the class is in the main
    # file; in a batch no file is, though each is still compiled once.
    target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-subobject-linkage>)
  endif()
endfunction()
