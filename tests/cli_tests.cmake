# Command-line tests every stage gets: bad input fails cleanly, the stats JSON holds every shared key, and
# --effects auto simulates only what a scene calls for.
function(rt_add_cli_tests stage)
  set(out ${CMAKE_BINARY_DIR}/test-output/cli/${stage})
  set(exe $<TARGET_FILE:${stage}>)
  set(script ${CMAKE_CURRENT_SOURCE_DIR}/run_cli_case.cmake)
  # Each case: name|argument|argument|... (the --out file must not be created)
  set(cases
      "width_zero|--width|0|--out|${out}/width_zero.png"
      "height_absurd|--height|99999999|--out|${out}/height_absurd.png"
      "missing_file|--scene|${out}/does_not_exist.gltf|--out|${out}/missing_file.png"
      "malformed_gltf|--scene|${out}/malformed.gltf|--out|${out}/malformed_gltf.png"
      "unknown_builtin|--scene|builtin:nosuchscene|--out|${out}/unknown_builtin.png"
      "unknown_option|--no-such-option|--out|${out}/unknown_option.png"
      "bad_effect|--effects|shadows,glitter|--out|${out}/bad_effect.png"
      "bad_image_type|--out|${out}/bad_image_type.bmp"
      "out_folder_missing|--out|${out}/no/such/folder/x.png"
      "camera_out_of_range|--camera|7|--out|${out}/camera_out_of_range.png")
  foreach(case IN LISTS cases)
    # Arguments travel to the script "|"-separated (a ";" would split the test command).
    string(FIND "${case}" "|" bar)
    string(SUBSTRING "${case}" 0 ${bar} name)
    math(EXPR bar "${bar} + 1")
    string(SUBSTRING "${case}" ${bar} -1 args)
    add_test(NAME cli.${stage}.bad_input_${name}
             COMMAND ${CMAKE_COMMAND} -DMODE=bad_input -DEXE=${exe} -DOUT_DIR=${out} "-DARGS=${args}"
                     -DNAME=${name} -P ${script})
    set_tests_properties(cli.${stage}.bad_input_${name} PROPERTIES LABELS "cli;cli-${stage}")
  endforeach()
  add_test(NAME cli.${stage}.stats_has_every_key
           COMMAND ${CMAKE_COMMAND} -DMODE=stats_keys -DEXE=${exe} -DOUT_DIR=${out} -DSTAGE_NAME=${stage} -P ${script})
  add_test(NAME cli.${stage}.diffuse_scene_spends_nothing_on_unused_effects
           COMMAND ${CMAKE_COMMAND} -DMODE=effects_auto -DEXE=${exe} -DOUT_DIR=${out}
                   -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
  add_test(NAME cli.${stage}.export_gltf_renders_like_builtin
           COMMAND ${CMAKE_COMMAND} -DMODE=export -DEXE=${exe} -DOUT_DIR=${out}
                   -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
  add_test(NAME cli.${stage}.frames_write_numbered_images
           COMMAND ${CMAKE_COMMAND} -DMODE=frames -DEXE=${exe} -DOUT_DIR=${out} -P ${script})
  set_tests_properties(cli.${stage}.stats_has_every_key cli.${stage}.diffuse_scene_spends_nothing_on_unused_effects
                       cli.${stage}.export_gltf_renders_like_builtin cli.${stage}.frames_write_numbered_images
                       PROPERTIES LABELS "cli;cli-${stage}")
endfunction()

foreach(stage IN LISTS RT_STAGES)   # tests/stages.txt
  rt_add_cli_tests(${stage})
endforeach()
