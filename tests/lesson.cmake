# lesson.<stage> and lesson.bad_stage: scripts/lesson (what a stage adds to the one it builds on) works on every stage
# and refuses a bad stage name with one line and exit 2. Included from tests/CMakeLists.txt it adds the tests; run
# with cmake -P (as the tests do) it runs one case: LESSON the script, STAGE the stage or BAD the bad name.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  foreach(stage IN LISTS RT_STAGES)   # tests/stages.txt
    add_test(NAME lesson.${stage}
             COMMAND ${CMAKE_COMMAND} -DLESSON=${PROJECT_SOURCE_DIR}/scripts/lesson -DSTAGE=${stage}
                     -P ${CMAKE_CURRENT_LIST_FILE})
    set_tests_properties(lesson.${stage} PROPERTIES LABELS "cli;lesson")
  endforeach()
  add_test(NAME lesson.bad_stage
           COMMAND ${CMAKE_COMMAND} -DLESSON=${PROJECT_SOURCE_DIR}/scripts/lesson -DBAD=06_no_such_stage
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(lesson.bad_stage PROPERTIES LABELS "cli;lesson")
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/script_case.cmake)   # run_script, expect_refusal

if(DEFINED BAD)
  foreach(args "${BAD}" "${BAD};--diff" "01_naive;--no-such-option")
    expect_refusal(lesson ${LESSON} ${args})
  endforeach()
  return()
endif()

run_script(rc out err ${LESSON} ${STAGE})
if(NOT rc EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "scripts/lesson ${STAGE} exited ${rc}: ${err}")
endif()
# It names the stage it builds on (or common/), and lists the stage's own files with their line counts.
if(NOT out MATCHES "^${STAGE} (builds on|replaces)" OR NOT out MATCHES "\n  ${STAGE}/main.cpp +source +[0-9]+ lines\n")
  message(FATAL_ERROR "scripts/lesson ${STAGE}: expected what it builds on and ${STAGE}/main.cpp's lines, got:\n${out}")
endif()
run_script(rc out err ${LESSON} ${STAGE} --diff)
if(NOT rc EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "scripts/lesson ${STAGE} --diff exited ${rc}: ${err}")
endif()
# A diff of the stage's main.cpp against its base's, or (01, which builds on common/ only) the line saying why none.
if(STAGE STREQUAL "01_naive")
  set(expect "^01_naive builds on common/ only: there is no earlier stage to diff against")
else()
  set(expect "\n\\+\\+\\+ ${STAGE}/main.cpp\n")
endif()
if(NOT out MATCHES "${expect}")
  message(FATAL_ERROR "scripts/lesson ${STAGE} --diff: expected a diff of ${STAGE}/main.cpp, got:\n${out}")
endif()
