# check_exact.*: scripts/check-exact, the cross-stage check of hits.cmake on any scene and option setting (run on
# ../shared/scenes for docs/exact_scenes.md; the tests use a built-in scene, as no test may need ../shared).
#   check_exact.cornell_every_variant  every GPU stage after 02 with each of its variants (VARIANTS in the script) on
#                                      builtin:cornell, 2 frames: every run exact, exit 0.
#   check_exact.finds_a_difference     a run whose rays are not 02's (--offset epsilon moves every secondary origin)
#                                      and one that spawns fewer (--max-depth 1): both reported DIFFERS, exit 1; a
#                                      run the stage refuses (--width 0): FAILED.
#   check_exact.bad_arguments          no such scene, no such stage: one line, exit 2.
# Included from tests/CMakeLists.txt it adds the tests; run with cmake -P it runs one CASE.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  list(LENGTH RT_GPU_STAGES gpu_stages)
  if(RT_PYTHON3 AND gpu_stages GREATER 1)
    list(JOIN RT_GPU_STAGES "|" stages)
    foreach(case cornell_every_variant finds_a_difference bad_arguments)
      add_test(NAME check_exact.${case}
               COMMAND ${CMAKE_COMMAND} -DSCRIPT=${PROJECT_SOURCE_DIR}/scripts/check-exact
                       -DBUILD=${CMAKE_BINARY_DIR} -DWORK=${CMAKE_BINARY_DIR}/test-output/check_exact/${case}
                       "-DSTAGES=${stages}" -DCASE=${case} -P ${CMAKE_CURRENT_LIST_FILE})
      set_tests_properties(check_exact.${case} PROPERTIES LABELS "hits;scripts" TIMEOUT 600)
    endforeach()
  endif()
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/script_case.cmake)   # run_script, expect_refusal
set(check_exact ${SCRIPT} --build-dir ${BUILD} --width 16 --height 12)

file(REMOVE_RECURSE ${WORK})
if(CASE STREQUAL "cornell_every_variant")
  run_script(rc out err ${check_exact} --scenes builtin:cornell --frames 2 --work ${WORK}
             --md ${WORK}/table.md)
  string(REPLACE "|" ";" stages "${STAGES}")
  list(POP_FRONT stages reference)
  foreach(stage IN LISTS stages)   # every stage after the reference ran, its defaults among its runs
    if(NOT out MATCHES "cornell ${stage} \\(defaults\\): exact \\(against ${reference}")
      message(FATAL_ERROR "scripts/check-exact on builtin:cornell: no exact run of ${stage}'s defaults:\n${out}${err}")
    endif()
  endforeach()
  if(NOT rc EQUAL 0 OR out MATCHES ": (DIFFERS|FAILED|skipped)" OR NOT out MATCHES ", 0 differed or failed, 0 skipped"
     OR NOT EXISTS ${WORK}/table.md)
    message(FATAL_ERROR "scripts/check-exact on builtin:cornell: exit ${rc} (want 0, no run differing, failed or "
                        "skipped, and table.md):\n${out}${err}")
  endif()
elseif(CASE STREQUAL "finds_a_difference")   # on the last GPU stage (05 in the course) and the second (03)
  string(REPLACE "|" ";" stages "${STAGES}")
  list(GET stages 1 second)
  list(GET stages -1 last)
  run_script(rc out err ${check_exact} --scenes builtin:cornell --frames 1 --work ${WORK} --only-variants
              "--variant=${last}:--offset epsilon --epsilon 0.01" "--variant=${second}:--max-depth 1"
              "--variant=${last}:--width 0")
  if(NOT rc EQUAL 1 OR NOT out MATCHES "${last} --offset epsilon --epsilon 0.01: DIFFERS \\(frame 0: hits"
     OR NOT out MATCHES "${second} --max-depth 1: DIFFERS" OR NOT out MATCHES "${last} --width 0: FAILED"
     OR NOT out MATCHES "0 runs exact, 3 differed or failed")
    message(FATAL_ERROR "scripts/check-exact let a wrong run pass (exit ${rc}, want 1):\n${out}${err}")
  endif()
elseif(CASE STREQUAL "bad_arguments")
  foreach(args "--scenes;${WORK}/no_such.gltf" "--variant=06_no_such_stage:--x" "--scenes;${WORK}/no_folder/")
    expect_refusal(check-exact ${check_exact} ${args})
  endforeach()
else()
  message(FATAL_ERROR "check_exact.cmake: no case ${CASE}")
endif()
