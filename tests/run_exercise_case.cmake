# exercise.each_stage_builds_and_fails_its_grading (tests/exercise.cmake):
#   cmake -DROOT=<project> -DOUT_DIR=<dir> -DSTAGES="01_naive|..." -P run_exercise_case.cmake
# For each stage in turn: scripts/exercise writes the student copy of that stage (its blocks and their twins
# stubbed; the script itself refuses a copy that still holds an answer line), scripts/grade --images-only builds the
# stages in the copy (the stubs must compile) and reports every exercise of the stage "not attempted", exit 1. Then,
# with the solution put back, one plausible wrong answer (a mutant of tests/mutants: 03.dda_cell_end's < for <=) is
# graded on its images, counts and hits with heatmaps: exit 1, that exercise failed with the differing counts or
# pixels, the other one passed or points at it, and the report loads in a real browser with every image.
# (--images-only keeps this test to a build of the stages, without the unit tests; grading with the unit tests is
# scripts/mutants.)
# (Every mutant failing, and the solution passing, is scripts/mutants: mutants.every_wrong_answer_fails.)
# One working copy and build folder serve every stage: each stage's copy is synced into it file by file (only the
# files that differ are written), so a stage costs an incremental build, not a whole one.
string(REPLACE "|" ";" STAGES "${STAGES}")
set(copy ${OUT_DIR}/student)
set(fresh ${OUT_DIR}/fresh)
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

function(sync_into_copy from)
  file(GLOB_RECURSE files RELATIVE ${fresh} ${fresh}/*)
  list(APPEND files .exercises)
  foreach(f IN LISTS files)
    if(EXISTS ${from}/${f})
      execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${from}/${f} ${copy}/${f})
    else()
      file(REMOVE ${copy}/${f})
    endif()
  endforeach()
endfunction()

function(exercise_field json name field out)
  string(JSON value ERROR_VARIABLE err GET "${json}" exercises ${name} ${field})
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

foreach(stage IN LISTS STAGES)
  file(REMOVE_RECURSE ${fresh})
  execute_process(COMMAND ${ROOT}/scripts/exercise ${stage} ${fresh} OUTPUT_QUIET ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "scripts/exercise ${stage} failed (exit ${rc}): ${err}")
  endif()
  if(NOT EXISTS ${copy})
    file(RENAME ${fresh} ${copy})
  else()
    sync_into_copy(${fresh})
  endif()
  set(report ${OUT_DIR}/report-${stage})
  execute_process(COMMAND ${copy}/scripts/grade ${stage} --no-images --images-only --build-dir ${copy}/build --out ${report}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1 OR NOT EXISTS ${report}/report.json)
    message(FATAL_ERROR "scripts/grade on the student copy of ${stage} exited ${rc}, not 1:\n${out}${err}")
  endif()
  file(READ ${report}/report.json json)
  string(JSON count LENGTH "${json}" exercises)
  if(count EQUAL 0)
    message(FATAL_ERROR "${stage}: the report names no exercise")
  endif()
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    string(JSON name MEMBER "${json}" exercises ${i})
    exercise_field("${json}" ${name} verdict verdict)
    exercise_field("${json}" ${name} message message)
    if(NOT verdict STREQUAL "not attempted")
      message(FATAL_ERROR "${stage}: the stub of ${name} is graded '${verdict}', not 'not attempted': ${message}")
    endif()
  endforeach()
  message(STATUS "${stage}: the copy builds with its ${count} exercises stubbed, each graded 'not attempted'")
endforeach()

# The solution back in place (the project's own files over the copy's; no .exercises: nothing is a stub), then a
# wrong answer to 03.dda_cell_end.
sync_into_copy(${ROOT})
set(mutant ${ROOT}/tests/mutants/03.dda_cell_end/01-strict_tie_break.patch)
execute_process(COMMAND patch -p1 --silent -d ${copy} -i ${mutant} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${mutant} does not apply to the solution")
endif()
set(report ${OUT_DIR}/report-wrong-answer)
execute_process(COMMAND ${copy}/scripts/grade 03_uniform_grid --images-only --build-dir ${copy}/build --out ${report}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 1 OR NOT EXISTS ${report}/report.json)
  message(FATAL_ERROR "a wrong answer to 03.dda_cell_end: scripts/grade exited ${rc}, not 1:\n${out}${err}")
endif()
file(READ ${report}/report.json json)
exercise_field("${json}" 03.dda_cell_end verdict verdict)
exercise_field("${json}" 03.dda_cell_end message message)
exercise_field("${json}" 03.grid_cells verdict other)
if(NOT verdict STREQUAL "failed" OR NOT message MATCHES "expected|differ")
  message(FATAL_ERROR "a wrong answer to 03.dda_cell_end is graded '${verdict}' with '${message}'")
endif()
exercise_field("${json}" 03.grid_cells message other_message)
if(NOT other STREQUAL "passed" AND NOT other_message MATCHES "shared with 03.dda_cell_end")
  message(FATAL_ERROR "03.grid_cells, answered, is graded '${other}' beside a wrong 03.dda_cell_end, without "
                      "pointing at it: ${other_message}")
endif()
string(REGEX MATCH "[^\n]*" first "${message}")
message(STATUS "a wrong 03.dda_cell_end fails its grading (${first}); 03.grid_cells: ${other}")
execute_process(COMMAND patch -R -p1 --silent -d ${copy} -i ${mutant})

# The report loads in a real browser with every image (Debian's chromium, installed by scripts/setup).
find_program(chromium chromium)
if(NOT chromium)
  message(FATAL_ERROR "chromium not found: run scripts/setup (it installs chromium for this test)")
endif()
execute_process(COMMAND ${copy}/scripts/grade --check-report ${report} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${report}/index.html does not load with every image in chromium")
endif()
