# Tests every GPU stage gets, run as scripts (tests/run_gpu_case.cmake), labelled "gpu" and "gpu-<stage>":
#   gpu.<stage>.egl_and_osmesa_agree   the two headless backends render the same image (threshold 0)
#   gpu.<stage>.window_screenshot      under xvfb-run, --window --frames 3 --screenshot opens a GLFW window, renders,
#                                      saves the frame and exits 0; the screenshot equals the headless image, also
#                                      with --exposure -1.5
#   gpu.<stage>.viewer                 under xvfb-run with xdotool (viewer_session.sh): the window as opened equals the
#                                      headless image; key 1 turns shadows off (equal to a headless --effects run
#                                      without shadows, and unlike before); a left drag orbits (the image changes)
function(rt_add_gpu_tests stage)
  set(out ${CMAKE_BINARY_DIR}/test-output/gpu/${stage})
  set(script ${CMAKE_CURRENT_SOURCE_DIR}/run_gpu_case.cmake)
  add_test(NAME gpu.${stage}.egl_and_osmesa_agree
           COMMAND ${CMAKE_COMMAND} -DMODE=backends -DEXE=$<TARGET_FILE:${stage}> -DOUT_DIR=${out}
                   -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
  set_tests_properties(gpu.${stage}.egl_and_osmesa_agree PROPERTIES LABELS "gpu;gpu-${stage}")
  find_program(RT_XVFB_RUN xvfb-run)
  if(RT_XVFB_RUN)
    add_test(NAME gpu.${stage}.window_screenshot
             COMMAND ${CMAKE_COMMAND} -DMODE=window -DEXE=$<TARGET_FILE:${stage}> -DOUT_DIR=${out}
                     -DXVFB_RUN=${RT_XVFB_RUN} -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
    # One X server at a time: two `xvfb-run -a` started together can pick the same display number.
    set_tests_properties(gpu.${stage}.window_screenshot PROPERTIES LABELS "gpu;gpu-${stage}" RESOURCE_LOCK xvfb)
    find_program(RT_XDOTOOL xdotool)
    if(RT_XDOTOOL)
      add_test(NAME gpu.${stage}.viewer
               COMMAND ${CMAKE_COMMAND} -DMODE=viewer -DEXE=$<TARGET_FILE:${stage}> -DOUT_DIR=${out}
                       -DXVFB_RUN=${RT_XVFB_RUN} -DSESSION=${CMAKE_CURRENT_SOURCE_DIR}/viewer_session.sh
                       -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
      set_tests_properties(gpu.${stage}.viewer PROPERTIES LABELS "gpu;gpu-${stage}" TIMEOUT 300 RESOURCE_LOCK xvfb)
    else()
      message(WARNING "xdotool not found (scripts/setup installs it): no viewer test for ${stage}")
    endif()
  else()
    message(WARNING "xvfb-run not found (scripts/setup installs it): no window test for ${stage}")
  endif()
endfunction()

foreach(stage IN LISTS RT_GPU_STAGES)
  rt_add_gpu_tests(${stage})
endforeach()
