# The cases of gpu_tests.cmake. MODE selects one; EXE is the stage, OUT_DIR a scratch folder, COMPARE image_compare.
file(MAKE_DIRECTORY ${OUT_DIR})
set(size --scene builtin:whitted --width 96 --height 72 --quiet)

function(render name)   # render(<name> args...): renders, fails the test on a non-zero exit
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} failed (exit ${rc}):\n${out}\n${err}")
  endif()
endfunction()

function(same_image actual expected name)   # threshold 0: not one pixel may differ
  execute_process(COMMAND ${COMPARE} ${actual} ${expected} --threshold 0 --fail-fraction 0 --name ${name}
                          --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: ${actual} differs from ${expected}")
  endif()
endfunction()

if(MODE STREQUAL "backends")
  file(REMOVE ${OUT_DIR}/egl.png ${OUT_DIR}/osmesa.png)
  render(egl ${EXE} ${size} --backend egl --out ${OUT_DIR}/egl.png --stats ${OUT_DIR}/egl.json)
  render(osmesa ${EXE} ${size} --backend osmesa --out ${OUT_DIR}/osmesa.png --stats ${OUT_DIR}/osmesa.json)
  file(READ ${OUT_DIR}/osmesa.json json)
  string(JSON backend GET "${json}" backend)
  if(NOT backend STREQUAL "osmesa")
    message(FATAL_ERROR "--backend osmesa ran on '${backend}'")
  endif()
  same_image(${OUT_DIR}/osmesa.png ${OUT_DIR}/egl.png egl_vs_osmesa)

elseif(MODE STREQUAL "window")
  file(REMOVE ${OUT_DIR}/screenshot.png ${OUT_DIR}/headless.png)
  render(headless ${EXE} ${size} --out ${OUT_DIR}/headless.png)
  render(window ${XVFB_RUN} -a ${EXE} ${size} --window --frames 3 --screenshot ${OUT_DIR}/screenshot.png)
  if(NOT EXISTS ${OUT_DIR}/screenshot.png)
    message(FATAL_ERROR "--screenshot wrote nothing")
  endif()
  same_image(${OUT_DIR}/screenshot.png ${OUT_DIR}/headless.png window_vs_headless)

else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
