# One golden-image test: render with a stage at a small size into an EXR (so NaN/Inf can be detected), then compare
# with tests/golden/<stage>/<name>.png. Invoked by CTest as:
#   cmake -DSTAGE=<exe> -DSTAGE_NAME=01_naive -DSCENE=builtin:whitted -DNAME=whitted -DGOLDEN=<png> -DOUT_DIR=<dir>
#         -DCOMPARE=<image_compare exe> -DOWN_REFERENCE=1 [-DARGS="--a|b"] -P run_golden.cmake
# OWN_REFERENCE=0: GOLDEN belongs to another test (agree.*, far_like_whitted.*). With "--frames N" in ARGS the
# stage writes N numbered images and the last one is compared.
string(REPLACE "|" ";" ARGS "${ARGS}")
set(update OFF)
if("$ENV{RT_UPDATE_GOLDENS}" STREQUAL "1")
  set(update ON)
  if(NOT OWN_REFERENCE)
    message(FATAL_ERROR "RT_UPDATE_GOLDENS=1: this test compares ${STAGE_NAME} with ${GOLDEN}, another test's "
                        "reference; it refuses to run in update mode (update that stage with scripts/update-goldens)")
  endif()
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
set(ext exr)   # float, so NaN/Inf can be detected; a PNG when it becomes the reference
if(update)
  set(ext png)
endif()
set(image ${OUT_DIR}/${NAME}.${ext})  # what the stage is told to write
set(actual ${image})                 # the frame compared
list(FIND ARGS --frames frames_at)
if(frames_at GREATER_EQUAL 0)
  math(EXPR frames_at "${frames_at} + 1")
  list(GET ARGS ${frames_at} frames)
  math(EXPR last "${frames} - 1")
  string(LENGTH "${last}" digits)
  while(digits LESS 4)                   # frame_path's %04d: <name>_0002.exr
    string(PREPEND last "0")
    math(EXPR digits "${digits} + 1")
  endwhile()
  set(actual ${OUT_DIR}/${NAME}_${last}.${ext})
endif()
file(REMOVE ${actual})
execute_process(COMMAND ${STAGE} --scene ${SCENE} --width 160 --height 120 --quiet --out ${image}
                        --stats ${OUT_DIR}/${NAME}.json ${ARGS}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${STAGE_NAME} failed to render ${SCENE} (exit ${rc})")
endif()
# With the environment variable RT_UPDATE_GOLDENS=1 (scripts/update-goldens) the rendered frame becomes the
# reference (a test that compares with another test's reference refused to run above).
if(update)
  get_filename_component(golden_dir ${GOLDEN} DIRECTORY)
  file(MAKE_DIRECTORY ${golden_dir})
  file(COPY_FILE ${actual} ${GOLDEN})
  message(STATUS "wrote ${GOLDEN}")
  return()
endif()
if(NOT EXISTS ${GOLDEN})
  message(FATAL_ERROR "no golden image ${GOLDEN}: render it with scripts/update-goldens ${STAGE_NAME}")
endif()
execute_process(COMMAND ${COMPARE} ${actual} ${GOLDEN} --name ${NAME} --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${STAGE_NAME} ${SCENE} differs from ${GOLDEN}")
endif()
