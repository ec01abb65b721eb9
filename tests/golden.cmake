# Golden-image tests: one CTest test per (stage, scene), named golden.<stage>.<scene>, labelled "golden" and
# "golden-<stage>". A stage's images are compared with tests/golden/<stage>/<scene>.png; see tests/image_compare.cpp
# for the tolerance and the README for why it is what it is.
add_executable(image_compare image_compare.cpp)
set_target_properties(image_compare PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
target_include_directories(image_compare PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(image_compare PRIVATE OpenImageIO::OpenImageIO CLI11::CLI11 glm::glm)

file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/golden/scenes.txt golden_lines REGEX "^[^#]")
set(RT_GOLDEN_SCENES "")
foreach(line IN LISTS golden_lines)
  string(REGEX MATCH "^([^ \t]+)[ \t]+([^ \t]+)" _ "${line}")
  list(APPEND RT_GOLDEN_SCENES "${CMAKE_MATCH_1}=${CMAKE_MATCH_2}")
endforeach()

# rt_add_golden_test(STAGE <target> NAME <scene name> SCENE <spec> [REFERENCE_STAGE <stage>]
#                    [REFERENCE_NAME <name>] [PREFIX golden] [ARGS ...])
# REFERENCE_STAGE/REFERENCE_NAME compare with another golden (cross-stage agreement, far against whitted).
function(rt_add_golden_test)
  cmake_parse_arguments(G "" "STAGE;NAME;SCENE;REFERENCE_STAGE;REFERENCE_NAME;PREFIX" "ARGS;LABELS" ${ARGN})
  if(NOT G_REFERENCE_STAGE)
    set(G_REFERENCE_STAGE ${G_STAGE})
  endif()
  if(NOT G_REFERENCE_NAME)
    set(G_REFERENCE_NAME ${G_NAME})
  endif()
  if(NOT G_PREFIX)
    set(G_PREFIX golden)
  endif()
  string(REPLACE ";" "|" args "${G_ARGS}")   # "|"-separated: a ";" would split the test command
  add_test(NAME ${G_PREFIX}.${G_STAGE}.${G_NAME}
           COMMAND ${CMAKE_COMMAND} -DSTAGE=$<TARGET_FILE:${G_STAGE}> -DSTAGE_NAME=${G_STAGE} -DSCENE=${G_SCENE}
                   -DNAME=${G_NAME} -DGOLDEN=${PROJECT_SOURCE_DIR}/tests/golden/${G_REFERENCE_STAGE}/${G_REFERENCE_NAME}.png
                   -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/${G_PREFIX}/${G_STAGE} -DCOMPARE=$<TARGET_FILE:image_compare>
                   "-DARGS=${args}" -P ${CMAKE_CURRENT_SOURCE_DIR}/run_golden.cmake)
  set_tests_properties(${G_PREFIX}.${G_STAGE}.${G_NAME} PROPERTIES LABELS "${G_PREFIX};${G_PREFIX}-${G_STAGE};${G_LABELS}")
endfunction()

function(rt_add_golden_tests stage)
  foreach(entry IN LISTS RT_GOLDEN_SCENES)
    string(REPLACE "=" ";" pair "${entry}")
    list(GET pair 0 name)
    list(GET pair 1 scene)
    rt_add_golden_test(STAGE ${stage} NAME ${name} SCENE ${scene} ${ARGN})
  endforeach()
endfunction()

# builtin:far is builtin:whitted moved by 1e4 with its camera: it must still look like whitted (robust offsets).
function(rt_add_far_test stage)
  rt_add_golden_test(STAGE ${stage} NAME far SCENE builtin:far REFERENCE_STAGE 01_naive REFERENCE_NAME whitted
                     PREFIX far_like_whitted)
endfunction()

rt_add_golden_tests(01_naive)
rt_add_far_test(01_naive)
if(TARGET 02_raster_hybrid)
  rt_add_golden_tests(02_raster_hybrid)
  rt_add_far_test(02_raster_hybrid)
  # Cross-stage agreement: 02's images match 01's references within the same tolerance.
  foreach(entry IN LISTS RT_GOLDEN_SCENES)
    string(REPLACE "=" ";" pair "${entry}")
    list(GET pair 0 name)
    list(GET pair 1 scene)
    rt_add_golden_test(STAGE 02_raster_hybrid NAME ${name} SCENE ${scene} REFERENCE_STAGE 01_naive PREFIX agree)
  endforeach()
endif()

