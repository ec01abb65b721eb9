# Exact cross-stage checks (tests/hit_compare.h; README, "Exact hit checks"): one test per GPU stage of
# tests/stages.txt and scene of tests/golden/scenes.txt, hits.<stage>.<scene>, labelled "hits" and "hits-<stage>".
# Both stages render the scene at 80x60 with --dump-hits; compare_hits matches the dumps ray by ray.
#   02_raster_hybrid against 01_naive (brute force on the CPU): 02 rasterizes its primary rays, so up to 0.5% of
#     them may hit another triangle (the bound visibility_test measures; measured since 02 re-tests the 3x3
#     neighbourhood: at most 0.08%, tests/README.md); the rays of such a pixel's tree are excluded. Every other ray must exist in both and hit the same triangle, its origin, direction and t
#     within 64 ulps (float on both sides, but the GPU's arithmetic is not the CPU's: no shared rounding).
#   every later GPU stage against 02: the same rays, the same hits, bit for bit (0 ulps), hence the same counts of
#     every kind, and the same image at threshold 0 (the shading code and its arithmetic are shared).
add_executable(compare_hits compare_hits.cpp hit_compare.cpp)
set_target_properties(compare_hits PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
target_link_libraries(compare_hits PRIVATE rt_app CLI11::CLI11)

function(rt_add_hits_tests stage)
  if(stage STREQUAL "02_raster_hybrid")
    set(reference 01_naive)
    set(bounds --primary-fraction 0.005 --ray-ulps 64 --t-ulps 64)
  elseif(TARGET 02_raster_hybrid)
    set(reference 02_raster_hybrid)
    set(bounds --ray-ulps 0 --t-ulps 0)
  else()
    message(STATUS "no hits tests for ${stage}: they compare with 02_raster_hybrid, which is not built")
    return()
  endif()
  string(REPLACE ";" "|" bounds "${bounds}")
  # The shader folders the reference may read: common's and those of the stages up to it (run_hits_case.cmake keys
  # its cached render on them).
  set(shader_folders ${CMAKE_BINARY_DIR}/shaders/common)
  foreach(s IN LISTS RT_STAGES)
    list(APPEND shader_folders ${CMAKE_BINARY_DIR}/shaders/${s})
    if(s STREQUAL reference)
      break()
    endif()
  endforeach()
  string(REPLACE ";" "|" shader_folders "${shader_folders}")
  foreach(entry IN LISTS RT_GOLDEN_CASES)
    string(REPLACE "|" ";" fields "${entry}")
    list(POP_FRONT fields name scene)
    string(REPLACE ";" "|" args "${fields}")
    add_test(NAME hits.${stage}.${name}
             COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:${stage}> -DREFERENCE_EXE=$<TARGET_FILE:${reference}>
                     -DSCENE=${scene} -DNAME=${name} "-DARGS=${args}" "-DBOUNDS=${bounds}"
                     -DSAME_IMAGE=$<NOT:$<STREQUAL:${reference},01_naive>>
                     -DCOMPARE_HITS=$<TARGET_FILE:compare_hits> -DCOMPARE=$<TARGET_FILE:image_compare>
                     -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/hits/${stage}
                     -DREFERENCE_CACHE=${CMAKE_BINARY_DIR}/test-output/hits/reference-cache
                     "-DREFERENCE_SHADERS=${shader_folders}"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/run_hits_case.cmake)
    # compare_hits never passes an empty dump: a stage that does not record its hits fails here.
    set_tests_properties(hits.${stage}.${name} PROPERTIES LABELS "hits;hits-${stage}")
  endforeach()
endfunction()

foreach(stage IN LISTS RT_GPU_STAGES)
  rt_add_hits_tests(${stage})
endforeach()
