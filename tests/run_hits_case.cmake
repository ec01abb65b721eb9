# One hits.<stage>.<scene> test (tests/hits.cmake): render with the stage and its reference with --dump-hits, then
# compare the dumps with compare_hits and BOUNDS; with SAME_IMAGE=1 the images must also be equal (threshold 0).
# With "--frames N" in ARGS the last frame is compared.
string(REPLACE "|" ";" ARGS "${ARGS}")
string(REPLACE "|" ";" BOUNDS "${BOUNDS}")
file(MAKE_DIRECTORY ${OUT_DIR})
set(suffix "")
list(FIND ARGS --frames frames_at)
if(frames_at GREATER_EQUAL 0)
  math(EXPR frames_at "${frames_at} + 1")
  list(GET ARGS ${frames_at} frames)
  math(EXPR last "${frames} - 1")
  string(LENGTH "${last}" digits)
  while(digits LESS 4)   # frame_path's %04d
    string(PREPEND last "0")
    math(EXPR digits "${digits} + 1")
  endwhile()
  set(suffix _${last})
endif()

foreach(side stage reference)
  set(exe ${EXE})
  if(side STREQUAL "reference")
    set(exe ${REFERENCE_EXE})
  endif()
  set(base ${OUT_DIR}/${NAME}.${side})
  file(REMOVE ${base}${suffix}.hits ${base}${suffix}.png)
  execute_process(COMMAND ${exe} --scene ${SCENE} --width 80 --height 60 --quiet --dump-hits ${base}.hits
                          --out ${base}.png ${ARGS}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${exe} failed on ${SCENE} (exit ${rc}):\n${out}\n${err}")
  endif()
  set(${side}_hits ${base}${suffix}.hits)
  set(${side}_png ${base}${suffix}.png)
endforeach()

execute_process(COMMAND ${COMPARE_HITS} ${stage_hits} ${reference_hits} ${BOUNDS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the hits of ${EXE} differ from ${REFERENCE_EXE}'s on ${SCENE} (compare_hits exit ${rc})")
endif()
if(SAME_IMAGE)
  execute_process(COMMAND ${COMPARE} ${stage_png} ${reference_png} --threshold 0 --fail-fraction 0 --name ${NAME}
                          --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the image of ${EXE} differs from ${REFERENCE_EXE}'s on ${SCENE} (threshold 0)")
  endif()
endif()
