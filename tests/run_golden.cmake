# One golden-image test: render with a stage at a small size into an EXR (so NaN/Inf can be detected), then compare
# with tests/golden/<stage>/<name>.png. Invoked by CTest as:
#   cmake -DSTAGE=<exe> -DSTAGE_NAME=01_naive -DSCENE=builtin:whitted -DNAME=whitted -DGOLDEN=<png> -DOUT_DIR=<dir>
#         -DCOMPARE=<image_compare exe> [-DARGS="--a|b"] -P run_golden.cmake
string(REPLACE "|" ";" ARGS "${ARGS}")
# With the environment variable RT_UPDATE_GOLDENS=1 (scripts/update-goldens) it writes the reference instead.
if("$ENV{RT_UPDATE_GOLDENS}" STREQUAL "1")
  get_filename_component(golden_dir ${GOLDEN} DIRECTORY)
  file(MAKE_DIRECTORY ${golden_dir})
  execute_process(COMMAND ${STAGE} --scene ${SCENE} --width 160 --height 120 --quiet --out ${GOLDEN} ${ARGS}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${STAGE_NAME} failed to render ${SCENE} (exit ${rc})")
  endif()
  message(STATUS "wrote ${GOLDEN}")
  return()
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
set(actual ${OUT_DIR}/${NAME}.exr)
file(REMOVE ${actual})
execute_process(COMMAND ${STAGE} --scene ${SCENE} --width 160 --height 120 --quiet --out ${actual}
                        --stats ${OUT_DIR}/${NAME}.json ${ARGS}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${STAGE_NAME} failed to render ${SCENE} (exit ${rc})")
endif()
if(NOT EXISTS ${GOLDEN})
  message(FATAL_ERROR "no golden image ${GOLDEN}: render it with scripts/update-goldens ${STAGE_NAME}")
endif()
execute_process(COMMAND ${COMPARE} ${actual} ${GOLDEN} --name ${NAME} --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${STAGE_NAME} ${SCENE} differs from ${GOLDEN}")
endif()
