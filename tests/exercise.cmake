# The course's grading (scripts/exercise, scripts/grade, scripts/mutants; the table tests/exercises.txt):
#  - grading.exercise_table_matches_tests: every pattern of the table matches a test of this build, every marked
#    exercise has a line, every line a marked exercise (a renamed test cannot drop out of grading);
#  - grading.unit_tests_batched_like_ctest: scripts/grade runs GoogleTest cases one process per binary; every case
#    gets the verdict CTest gives it, a failure its assertion's text, and a crash or a missing report no pass
#    (tests/check_grade_batches.py);
#  - exercise.each_stage_builds_and_fails_its_grading: each stage's student copy holds no answer, builds, and is
#    graded "not attempted"; a wrong answer fails with its assertion's text and the report loads in a browser;
#  - mutants.every_wrong_answer_fails (only with -DRT_MUTANTS=ON, label "mutants"; 88 min on 2 cores from scratch): every
#    plausible wrong answer of tests/mutants fails scripts/grade, and the solution passes.
find_program(RT_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT RT_PYTHON3)
  message(STATUS "no /usr/bin/python3: no grading tests")
  return()
endif()
add_test(NAME grading.exercise_table_matches_tests
         COMMAND ${PROJECT_SOURCE_DIR}/scripts/grade --check-table --build-dir ${CMAKE_BINARY_DIR})
set_tests_properties(grading.exercise_table_matches_tests PROPERTIES LABELS "exercise")
add_test(NAME grading.unit_tests_batched_like_ctest
         COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/check_grade_batches.py --build-dir ${CMAKE_BINARY_DIR})
set_tests_properties(grading.unit_tests_batched_like_ctest PROPERTIES LABELS "exercise" TIMEOUT 600)

string(REPLACE ";" "|" stages "${RT_STAGES}")
add_test(NAME exercise.each_stage_builds_and_fails_its_grading
         COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/exercise
                 "-DSTAGES=${stages}" -P ${CMAKE_CURRENT_SOURCE_DIR}/run_exercise_case.cmake)
# COST: scheduled first on a fresh build (it takes minutes: one build of the copy), so the other tests run beside it.
set_tests_properties(exercise.each_stage_builds_and_fails_its_grading PROPERTIES LABELS "exercise" TIMEOUT 2400 COST 10000)

option(RT_MUTANTS "register mutants.every_wrong_answer_fails (about 90 minutes on 2 cores)" OFF)
if(RT_MUTANTS)
  add_test(NAME mutants.every_wrong_answer_fails
           COMMAND ${PROJECT_SOURCE_DIR}/scripts/mutants --work ${CMAKE_BINARY_DIR}/test-output/mutants)
  set_tests_properties(mutants.every_wrong_answer_fails PROPERTIES LABELS "mutants" TIMEOUT 7200)
endif()
