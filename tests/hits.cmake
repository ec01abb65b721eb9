# Exact cross-stage checks (tests/hit_compare.h; README, "Exact hit checks"): one test per GPU stage of
# tests/stages.txt and scene of tests/golden/scenes.txt, hits.<stage>.<scene>, labelled "hits" and "hits-<stage>".
# The stage's frame and hits are those golden.<stage>.<scene> rendered (160x120, --dump-hits; a CTest fixture, so the
# scene is rendered once for both); the reference renders it the same way, once per build (its render is kept), and
# compare_hits matches the dumps ray by ray.
#   02_raster_hybrid against 01_naive (brute force on the CPU), two checks:
#   - its tracing: every ray 02 traced, traced again by 01's brute force from the same origin and direction
#     (retrace_hits) must hit the same triangle (shadow rays: the same answer), the hit points within 64 ulps of their
#     coordinates (hit_compare.h, point_ulps; measured: 0 on llvmpipe, at most 16 on an NVIDIA H200). 02 rasterizes
#     its primary rays, so up to 0.5% of them may hit another triangle (the bound visibility_test measures; since 02
#     re-tests the 3x3 neighbourhood: at most 0.08%, tests/README.md). Every driver.
#   - its rays: 02's render and 01's, path by path. Every ray outside the trees of differing primaries must exist in
#     both and hit the same triangle, its origin, direction and t within 64 ulps (float on both sides, but the GPU's
#     arithmetic is not the CPU's: no shared rounding). Asserted on llvmpipe, whose division and square roots round
#     like the CPU's; elsewhere printed only: GLSL allows 2.5 ulps for a division, and the differences grow along a
#     path (an NVIDIA H200: thousands of ulps on 12 of 14 scenes; docs/gpu-nvidia.md).
#   every later GPU stage against 02: the same rays, the same hits, bit for bit (0 ulps), hence the same counts of
#     every kind, and the same image at threshold 0 (the shading code and its arithmetic are shared). Every driver.
add_executable(compare_hits compare_hits.cpp hit_compare.cpp)
set_target_properties(compare_hits PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
target_link_libraries(compare_hits PRIVATE rt_app CLI11::CLI11)
# retrace_hits: a dump's rays traced again by 01's brute force, from the same origins and directions.
if(TARGET stage01_naive)
  add_executable(retrace_hits retrace_hits.cpp)
  set_target_properties(retrace_hits PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_link_libraries(retrace_hits PRIVATE stage01_naive CLI11::CLI11)
  # The tool itself: 01's own rays traced again are 01's own hits, bit for bit; bad input is refused.
  find_program(RT_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)   # Debian's, with scripts/setup's modules
  if(RT_PYTHON3)
    add_test(NAME hits.retrace_hits_checks
             COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/check_retrace_hits.py --build-dir ${CMAKE_BINARY_DIR})
    set_tests_properties(hits.retrace_hits_checks PROPERTIES LABELS "hits;hits-02_raster_hybrid")
  endif()
endif()

function(rt_add_hits_tests stage)
  if(stage STREQUAL "02_raster_hybrid")
    set(reference 01_naive)
    set(bounds --primary-fraction 0.005 --ray-ulps 64 --t-ulps 64)
    set(retrace_bounds --primary-fraction 0.005 --ray-ulps 0 --point-ulps 64)
  elseif(TARGET 02_raster_hybrid)
    set(reference 02_raster_hybrid)
    set(bounds --ray-ulps 0 --t-ulps 0)
    set(retrace_bounds "")
  else()
    message(STATUS "no hits tests for ${stage}: they compare with 02_raster_hybrid, which is not built")
    return()
  endif()
  string(REPLACE ";" "|" bounds "${bounds}")
  string(REPLACE ";" "|" retrace_bounds "${retrace_bounds}")
  set(retrace "")
  if(retrace_bounds)
    set(retrace -DRETRACE_EXE=$<TARGET_FILE:retrace_hits> "-DRETRACE_BOUNDS=${retrace_bounds}")
  endif()
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
                     -DSCENE=${scene} -DNAME=${name} -DWIDTH=${RT_GOLDEN_WIDTH} -DHEIGHT=${RT_GOLDEN_HEIGHT}
                     "-DARGS=${args}" "-DBOUNDS=${bounds}" ${retrace}
                     -DSAME_IMAGE=$<NOT:$<STREQUAL:${reference},01_naive>>
                     -DCOMPARE_HITS=$<TARGET_FILE:compare_hits> -DCOMPARE=$<TARGET_FILE:image_compare>
                     -DOUT_DIR=${CMAKE_BINARY_DIR}/test-output/hits/${stage}
                     -DRENDERED_IN=${CMAKE_BINARY_DIR}/test-output/golden/${stage}
                     -DREFERENCE_CACHE=${CMAKE_BINARY_DIR}/test-output/hits/reference-cache
                     "-DREFERENCE_SHADERS=${shader_folders}"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/run_hits_case.cmake)
    # compare_hits never passes an empty dump: a stage that does not record its hits fails here.
    # The stage's frame is golden.<stage>.<name>'s (it records its hits): CTest runs that first, and when it fails
    # this test is not run and counts as failed.
    set_tests_properties(hits.${stage}.${name} PROPERTIES LABELS "hits;hits-${stage}"
                         FIXTURES_REQUIRED frame.${stage}.${name})
  endforeach()
endfunction()

foreach(stage IN LISTS RT_GPU_STAGES)
  rt_add_hits_tests(${stage})
endforeach()
