# Driven by CTest: builds a consumer project against prtkit and runs it on the golden blob.
#   cmake -DMODE=package|subdir -DSOURCE=<prtkit source> -DWORK=<scratch dir>
#         -DGENERATOR=<generator> -DC_COMPILER=... -DCXX_COMPILER=... -P run_consumer.cmake
# package: configure prtkit (runtime only), build, install into WORK/prefix, then build
#          consumer/package with find_package(prtkit) and, if pkg-config exists, compile the
#          consumer once more with `cc consumer.c $(pkg-config --cflags --libs prtkit)`, as the
#          README says.
# subdir:  build consumer/subdir, which add_subdirectory()s the prtkit source.
# Every step must succeed and every run of the consumer must print what it loaded; the script
# fails otherwise (CTest judges it by its exit code).
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# Runs the consumer on the golden blob and checks what it printed.
function(run_consumer exe what)
  run(${exe} ${golden})
  if(NOT last_output MATCHES "consumer: prtkit [0-9.]+ loaded 4 sections; Y_10\\(up\\) = 0\\.48860")
    message(FATAL_ERROR "${what}: unexpected output: ${last_output}")
  endif()
  message(STATUS "${what}: ${last_output}")
endfunction()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(golden ${SOURCE}/formats/golden/1.0/tiny.prtk)
set(common -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=${C_COMPILER}
           -DCMAKE_CXX_COMPILER=${CXX_COMPILER})

if(MODE STREQUAL "package")
  run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/prtkit-build ${common}
      -DPRT_BUILD_BAKER=OFF -DPRT_BUILD_TESTS=OFF -DPRT_BUILD_SAMPLES=OFF
      -DPRT_BUILD_BENCHMARKS=OFF -DPRT_INSTALL=ON -DCMAKE_INSTALL_PREFIX=${WORK}/prefix)
  run(${CMAKE_COMMAND} --build ${WORK}/prtkit-build -j2)
  run(${CMAKE_COMMAND} --install ${WORK}/prtkit-build)
  run(${CMAKE_COMMAND} -S ${SOURCE}/tests/consumer/package -B ${WORK}/consumer-build ${common}
      -DCMAKE_PREFIX_PATH=${WORK}/prefix)
  run(${CMAKE_COMMAND} --build ${WORK}/consumer-build)
  run_consumer(${WORK}/consumer-build/consumer "find_package")

  find_program(PKG_CONFIG pkg-config)
  if(PKG_CONFIG)
    file(GLOB pc_dirs ${WORK}/prefix/*/pkgconfig ${WORK}/prefix/*/*/pkgconfig)
    set(ENV{PKG_CONFIG_PATH} "${pc_dirs}")
    run(${PKG_CONFIG} --cflags --libs prtkit)
    string(STRIP "${last_output}" flags)
    separate_arguments(flags UNIX_COMMAND "${flags}")
    run(${C_COMPILER} -std=c99 ${SOURCE}/tests/consumer/consumer.c -o ${WORK}/consumer-pc ${flags})
    run_consumer(${WORK}/consumer-pc "pkg-config")
  else()
    message(STATUS "pkg-config: not found, that step is skipped")
  endif()
elseif(MODE STREQUAL "subdir")
  run(${CMAKE_COMMAND} -S ${SOURCE}/tests/consumer/subdir -B ${WORK}/consumer-build ${common}
      -DPRTKIT_SOURCE_DIR=${SOURCE})
  run(${CMAKE_COMMAND} --build ${WORK}/consumer-build -j2)
  run(${WORK}/consumer-build/consumer ${golden})
  message(STATUS "${last_output}")
else()
  message(FATAL_ERROR "MODE must be package or subdir")
endif()
