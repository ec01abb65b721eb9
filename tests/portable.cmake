# The portable build (RT_PORTABLE=ON) for bare GPU machines: configure and build the stages in
# build/portable, then check with ldd that each binary needs nothing beyond the C/C++ runtime, libEGL and the small
# libraries listed in tests/check_portable.cmake. Slow (a second build), so it has its own label: "portable".
string(REPLACE ";" "|" rt_stage_targets "${RT_STAGES}")
add_test(NAME portable.binaries_need_only_small_libraries
         COMMAND ${CMAKE_COMMAND} -DSOURCE=${PROJECT_SOURCE_DIR} -DBUILD=${CMAKE_BINARY_DIR}/portable
                 "-DTARGETS=${rt_stage_targets}" -P ${CMAKE_CURRENT_SOURCE_DIR}/check_portable.cmake)
set_tests_properties(portable.binaries_need_only_small_libraries PROPERTIES LABELS portable TIMEOUT 1800 RUN_SERIAL TRUE
                     FIXTURES_SETUP portable_build)
# Without OpenImageIO, .hdr environments come through stb_image: the same image, and truncated files refused.
add_test(NAME portable.environment_hdr_reads_as_openimageio_does
         COMMAND ${CMAKE_COMMAND} -DSOURCE=${PROJECT_SOURCE_DIR} -DBUILD=${CMAKE_BINARY_DIR}/portable
                 -DCOMPARE=$<TARGET_FILE:image_compare> -P ${CMAKE_CURRENT_SOURCE_DIR}/check_portable_environment.cmake)
set_tests_properties(portable.environment_hdr_reads_as_openimageio_does PROPERTIES LABELS portable TIMEOUT 900
                     FIXTURES_REQUIRED portable_build)
