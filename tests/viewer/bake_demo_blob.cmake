# Test fixture: the demo scene and sky, baked with `sh` at a small order and with `wavelet` on a
# small cube, for the viewer tests.
# cmake -DPRT_BAKE=... -DOUT=... -P bake_demo_blob.cmake
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${PRT_BAKE} demo-scene ${OUT} --sky-width 128 RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "prt-bake demo-scene failed (${status})")
endif()
execute_process(COMMAND ${PRT_BAKE} bake sh ${OUT}/demo_scene.glb --order 4 --rays 64
                        -o ${OUT}/demo_sh4.prtk RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "prt-bake bake sh failed (${status})")
endif()
execute_process(COMMAND ${PRT_BAKE} bake wavelet ${OUT}/demo_scene.glb --cube 16
                        --keep 200 -o ${OUT}/demo_wavelet16.prtk RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "prt-bake bake wavelet failed (${status})")
endif()
