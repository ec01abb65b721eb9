# Golden-image tests: one CTest test per (stage, scene), named golden.<stage>.<scene>, labelled "golden" and
# "golden-<stage>". A stage's images are compared with tests/golden/<stage>/<scene>.png; see tests/image_compare.cpp
# for the tolerance and the README for why it is what it is.
add_executable(image_compare image_compare.cpp)
set_target_properties(image_compare PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
target_include_directories(image_compare PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(image_compare PRIVATE OpenImageIO::OpenImageIO CLI11::CLI11 glm::glm)

# The size every golden frame is rendered at (the references in tests/golden are this size), which hits.* compares
# too (tests/hits.cmake: the golden test's frame and hits, and its reference renders of the same size).
set(RT_GOLDEN_WIDTH 160)
set(RT_GOLDEN_HEIGHT 120)

# tests/golden/scenes.txt: "<name> <scene> [arguments...]"; with --frames N the last frame is the one compared.
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/golden/scenes.txt golden_lines REGEX "^[^#]")
set(RT_GOLDEN_CASES "")
foreach(line IN LISTS golden_lines)
  string(STRIP "${line}" line)
  string(REPLACE "@SOURCE_DIR@" "${PROJECT_SOURCE_DIR}" line "${line}")   # files of the source tree (tests/data)
  string(REGEX REPLACE "[ \t]+" "|" line "${line}")   # name|scene|arg|arg...
  list(APPEND RT_GOLDEN_CASES "${line}")
endforeach()

# rt_add_golden_test(STAGE <target> NAME <scene name> SCENE <spec> [REFERENCE_STAGE <stage>]
#                    [REFERENCE_NAME <name>] [PREFIX golden] [ARGS ...])
# REFERENCE_STAGE/REFERENCE_NAME compare with another golden (cross-stage agreement, far against whitted). Only a
# golden.* test writes its reference in update mode (RT_UPDATE_GOLDENS=1); the others refuse to run then.
# REUSE_GOLDEN_FRAME: render nothing, compare the frame golden.<stage>.<name> rendered with the same command (a CTest
# fixture: CTest runs golden.* first, and when it fails this test is not run and counts as failed).
function(rt_add_golden_test)
  cmake_parse_arguments(G "REUSE_GOLDEN_FRAME" "STAGE;NAME;SCENE;REFERENCE_STAGE;REFERENCE_NAME;PREFIX" "ARGS;LABELS"
                        ${ARGN})
  if(NOT G_REFERENCE_STAGE)
    set(G_REFERENCE_STAGE ${G_STAGE})
  endif()
  if(NOT G_REFERENCE_NAME)
    set(G_REFERENCE_NAME ${G_NAME})
  endif()
  if(NOT G_PREFIX)
    set(G_PREFIX golden)
  endif()
  set(own_reference 0)
  if(G_PREFIX STREQUAL "golden" AND G_REFERENCE_STAGE STREQUAL G_STAGE AND G_REFERENCE_NAME STREQUAL G_NAME)
    set(own_reference 1)
  endif()
  string(REPLACE ";" "|" args "${G_ARGS}")   # "|"-separated: a ";" would split the test command
  set(dump_hits 0)   # the GPU stages' golden frames also record their hits, for hits.<stage>.<name>
  if(own_reference AND G_STAGE IN_LIST RT_GPU_STAGES)
    set(dump_hits 1)
  endif()
  set(rendered_in "")
  if(G_REUSE_GOLDEN_FRAME)
    set(rendered_in ${CMAKE_BINARY_DIR}/test-output/golden/${G_STAGE})
  endif()
  add_test(NAME ${G_PREFIX}.${G_STAGE}.${G_NAME}
           COMMAND ${CMAKE_COMMAND} -DSTAGE=$<TARGET_FILE:${G_STAGE}> -DSTAGE_NAME=${G_STAGE} -DSCENE=${G_SCENE}
                   -DNAME=${G_NAME} -DWIDTH=${RT_GOLDEN_WIDTH} -DHEIGHT=${RT_GOLDEN_HEIGHT}
                   -DGOLDEN=${PROJECT_SOURCE_DIR}/tests/golden/${G_REFERENCE_STAGE}/${G_REFERENCE_NAME}.png
                   -DOWN_REFERENCE=${own_reference}
                   -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/${G_PREFIX}/${G_STAGE} -DCOMPARE=$<TARGET_FILE:image_compare>
                   "-DARGS=${args}" -DRENDERED_IN=${rendered_in} -DDUMP_HITS=${dump_hits}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/run_golden.cmake)
  set_tests_properties(${G_PREFIX}.${G_STAGE}.${G_NAME} PROPERTIES LABELS "${G_PREFIX};${G_PREFIX}-${G_STAGE};${G_LABELS}")
  if(own_reference)
    set_tests_properties(${G_PREFIX}.${G_STAGE}.${G_NAME} PROPERTIES FIXTURES_SETUP frame.${G_STAGE}.${G_NAME})
  elseif(G_REUSE_GOLDEN_FRAME)
    set_tests_properties(${G_PREFIX}.${G_STAGE}.${G_NAME} PROPERTIES FIXTURES_REQUIRED frame.${G_STAGE}.${G_NAME})
  endif()
endfunction()

# One test per line of tests/golden/scenes.txt, all with the same PREFIX/REFERENCE_STAGE (extra arguments).
function(rt_add_golden_tests stage)
  foreach(entry IN LISTS RT_GOLDEN_CASES)
    string(REPLACE "|" ";" fields "${entry}")
    list(POP_FRONT fields name scene)
    rt_add_golden_test(STAGE ${stage} NAME ${name} SCENE ${scene} ARGS ${fields} ${ARGN})
  endforeach()
endfunction()

# builtin:far is builtin:whitted moved by 1e4 with its camera: it must still look like whitted (robust offsets).
function(rt_add_far_test stage)
  rt_add_golden_test(STAGE ${stage} NAME far SCENE builtin:far REFERENCE_STAGE 01_naive REFERENCE_NAME whitted
                     PREFIX far_like_whitted)
endfunction()

foreach(stage IN LISTS RT_STAGES)
  rt_add_golden_tests(${stage})
  rt_add_far_test(${stage})
  if(NOT stage STREQUAL "01_naive")
    # Cross-stage agreement: every later stage's images match 01's references within the same tolerance (the
    # frame golden.* rendered: the same command gives the same frame).
    rt_add_golden_tests(${stage} REFERENCE_STAGE 01_naive PREFIX agree REUSE_GOLDEN_FRAME)
  endif()
endforeach()
