# default_light.<stage>.<scene>: a glTF interior with no light of its own, lit by the default headlight, gives a
# readable image at the default options (under 5% of pixels clipped, the median away from both ends:
# tests/check_default_light.py): tests/data's closed room and a 65,000-triangle hall written by
# tests/data/make_interior_scene.py. The rule lives in the shared driver (docs/shading.md, "Defaults"): one CPU and
# one GPU stage check it (02's brute force is too slow for the hall on llvmpipe).
if(RT_PYTHON3)
  foreach(stage 01_naive 03_uniform_grid)
    if(NOT TARGET ${stage})
      continue()
    endif()
    set(size --width 160 --height 120)
    if(stage STREQUAL "01_naive")
      set(size --width 64 --height 48)   # the hall by brute force: 2 rays a pixel against 65,000 triangles
    endif()
    foreach(scene closed_room hall)
      set(spec hall)
      if(scene STREQUAL "closed_room")
        set(spec ${PROJECT_SOURCE_DIR}/tests/data/closed_room.gltf)
      endif()
      add_test(NAME default_light.${stage}.${scene}
               COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/check_default_light.py --stage $<TARGET_FILE:${stage}>
                       --scene ${spec} --work ${CMAKE_BINARY_DIR}/test-output/default_light/${stage}/${scene} ${size})
      set_tests_properties(default_light.${stage}.${scene} PROPERTIES LABELS "cli;cli-${stage}")
    endforeach()
  endforeach()
endif()
