# exercise.each_stage_builds_and_fails_its_grading (tests/exercise.cmake):
#   cmake -DROOT=<project> -DOUT_DIR=<dir> -DSTAGES="01_naive|..." -DIMAGE_NEUTRAL="05_ray_sorting" -P run_exercise_case.cmake
# For each stage in turn: scripts/exercise writes the student copy of that stage (only its blocks stubbed), the
# copy's stage builds (the stubs compile), and scripts/grade, run in the copy, fails that stage on golden images.
# Then the solution is put back and every stage passes its grading (images; the copy builds no unit tests).
# One working copy and build folder serve every stage: each stage's copy is synced into it file by file (only the
# files that differ are written), so a stage costs an incremental build, not a whole one.
cmake_policy(SET CMP0057 NEW)   # if(... IN_LIST ...) in script mode
string(REPLACE "|" ";" STAGES "${STAGES}")
string(REPLACE "|" ";" IMAGE_NEUTRAL "${IMAGE_NEUTRAL}")
set(copy ${OUT_DIR}/student)
set(fresh ${OUT_DIR}/fresh)
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)

foreach(stage IN LISTS STAGES)
  file(REMOVE_RECURSE ${fresh})
  execute_process(COMMAND ${ROOT}/scripts/exercise ${stage} ${fresh} OUTPUT_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "scripts/exercise ${stage} failed (exit ${rc})")
  endif()
  if(NOT EXISTS ${copy})
    file(RENAME ${fresh} ${copy})
    execute_process(COMMAND ${CMAKE_COMMAND} -S ${copy} -B ${copy}/build -DCMAKE_BUILD_TYPE=Release
                    OUTPUT_QUIET RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "the student copy does not configure (exit ${rc})")
    endif()
  else()
    file(GLOB_RECURSE files RELATIVE ${fresh} ${fresh}/*)
    foreach(f IN LISTS files)
      execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${fresh}/${f} ${copy}/${f})
    endforeach()
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${copy}/build -j ${cores} --target ${stage} image_compare
                  OUTPUT_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the student copy of ${stage} does not build (exit ${rc}): a stub must compile")
  endif()
  set(report ${OUT_DIR}/report-${stage})
  if(stage IN_LIST IMAGE_NEUTRAL)
    execute_process(COMMAND ${copy}/scripts/grade ${stage} --no-build --no-heatmap --build-dir ${copy}/build
                            --no-hard-cases --out ${report} OUTPUT_QUIET RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${stage} changes only the cost, yet its stubs changed its images (grade exited ${rc})")
    endif()
    message(STATUS "${stage}: its stubs build and keep the images (its unit tests grade its exercises)")
    continue()
  endif()
  execute_process(COMMAND ${copy}/scripts/grade ${stage} --no-build --no-heatmap --build-dir ${copy}/build
                          --no-hard-cases --out ${report} OUTPUT_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "scripts/grade on the student copy of ${stage} exited ${rc}, not 1 (a failed grading)")
  endif()
  file(READ ${report}/report.json json)
  string(JSON scenes LENGTH "${json}" stages ${stage} scenes)
  math(EXPR last "${scenes} - 1")
  set(failed "")
  foreach(i RANGE ${last})
    string(JSON passed GET "${json}" stages ${stage} scenes ${i} passed)
    string(JSON name GET "${json}" stages ${stage} scenes ${i} name)
    if(NOT passed)
      list(APPEND failed ${name})
    endif()
  endforeach()
  if(NOT failed)
    message(FATAL_ERROR "${stage}: every golden image passed with the stage's exercises stubbed out")
  endif()
  message(STATUS "${stage}: with its exercises stubbed, the golden images ${failed} fail, as they should")
endforeach()

# The solution back in place (the project's own files over the copy's): every stage passes.
file(GLOB_RECURSE files RELATIVE ${fresh} ${fresh}/*)
foreach(f IN LISTS files)
  execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${ROOT}/${f} ${copy}/${f})
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${copy}/build -j ${cores} --target ${STAGES} image_compare
                OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the copy with the solution put back does not build (exit ${rc})")
endif()
execute_process(COMMAND ${copy}/scripts/grade ${STAGES} --no-build --no-heatmap --no-hard-cases
                        --build-dir ${copy}/build --out ${OUT_DIR}/report-solution OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "with the solution put back, scripts/grade exited ${rc}, not 0 (see ${OUT_DIR}/report-solution)")
endif()
message(STATUS "with the solution put back, every stage passes its grading")

# The reports load in a real browser with every image (Debian's chromium, installed by scripts/setup): a failing
# stage's and the passing one.
find_program(chromium chromium)
if(chromium)
  list(GET STAGES 0 first)
  foreach(report report-${first} report-solution)
    execute_process(COMMAND ${copy}/scripts/grade --check-report ${OUT_DIR}/${report} RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${OUT_DIR}/${report}/index.html does not load with every image in chromium")
    endif()
  endforeach()
else()
  message(FATAL_ERROR "chromium not found: run scripts/setup (it installs chromium for this test)")
endif()
