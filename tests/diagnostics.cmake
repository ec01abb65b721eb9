# The diagnostics every stage writes (--dump-hits, --heatmap), run as scripts (tests/run_diagnostics_case.cmake),
# labelled "diagnostics" and "diagnostics-<stage>":
#   diag.<stage>.dump_hits_and_heatmap_per_frame  with --frames 2, one hit file and one heatmap per frame; each hit
#                                                 file holds exactly the frame's traced rays (its stats' ray counts);
#                                                 the heatmap's per-pixel tests sum to the frame's
#                                                 intersection_tests, and with traced primaries none is 0
#   diag.<stage>.dump_hits_refuses_max_depth_31   path numbers have 31 bits: exit 2 with one line, no file written
#   diag.<stage>.still_scene_uploaded_once        GPU stages: --frames 3 of a still scene upload it with frame 0 only
#                                                 (stats frame_stats upload_bytes.scene), of an animated one each frame
function(rt_add_diagnostics_tests stage)
  set(out ${CMAKE_BINARY_DIR}/test-output/diagnostics/${stage})
  set(modes dump_hits_and_heatmap_per_frame dump_hits_refuses_max_depth_31)
  if(stage IN_LIST RT_GPU_STAGES)
    list(APPEND modes still_scene_uploaded_once)
  endif()
  foreach(mode IN LISTS modes)
    add_test(NAME diag.${stage}.${mode}
             COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DEXE=$<TARGET_FILE:${stage}> -DOUT_DIR=${out}
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/run_diagnostics_case.cmake)
    set_tests_properties(diag.${stage}.${mode} PROPERTIES LABELS "diagnostics;diagnostics-${stage}")
  endforeach()
endfunction()

foreach(stage IN LISTS RT_STAGES)
  rt_add_diagnostics_tests(${stage})
endforeach()
