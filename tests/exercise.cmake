# The course's grading can fail (scripts/exercise, scripts/grade): the student copy of each stage (its exercises
# stubbed out) builds, and scripts/grade finds some of its golden images wrong. The solution passing is the golden
# tests themselves (golden.<stage>.*). One working copy serves every stage in turn (tests/run_exercise_case.cmake),
# building only the stage and image_compare, so the test costs about one build of the stages.
find_program(RT_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT RT_PYTHON3)
  message(STATUS "no /usr/bin/python3: no exercise test")
  return()
endif()
string(REPLACE ";" "|" stages "${RT_STAGES}")
# Stages whose technique changes only the cost, never the image (05 sorts the rays: --sort off gives the same frame):
# their exercises cannot fail a golden image; scripts/grade fails them on their unit tests (keys and sorted order
# against the CPU reference), which this test does not build. Here they must build and keep their images.
set(image_neutral 05_ray_sorting)
add_test(NAME exercise.each_stage_builds_and_fails_its_grading
         COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/exercise
                 "-DSTAGES=${stages}" "-DIMAGE_NEUTRAL=${image_neutral}" -P ${CMAKE_CURRENT_SOURCE_DIR}/run_exercise_case.cmake)
# COST: scheduled first on a fresh build (it takes minutes), so the other tests run beside it.
set_tests_properties(exercise.each_stage_builds_and_fails_its_grading PROPERTIES LABELS "exercise" TIMEOUT 1800 COST 10000)
