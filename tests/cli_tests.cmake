# Command-line tests every stage gets: bad input fails cleanly, the stats JSON holds every shared key, and
# --effects auto simulates only what a scene calls for.
function(rt_add_cli_tests stage)
  set(out ${CMAKE_BINARY_DIR}/test-output/cli/${stage})
  set(exe $<TARGET_FILE:${stage}>)
  set(script ${CMAKE_CURRENT_SOURCE_DIR}/run_cli_case.cmake)
  # Each case: name|argument|argument|... (the --out file must not be created). @DIR@ is the case's own folder: the
  # cases check that no temporary is left behind, so they must not share a folder with tests that write outputs
  # (under ctest -j, another test's temporary in a shared folder failed them now and then).
  set(cases
      "width_zero|--width|0|--out|@DIR@/width_zero.png"
      "height_absurd|--height|99999999|--out|@DIR@/height_absurd.png"
      "missing_file|--scene|@DIR@/does_not_exist.gltf|--out|@DIR@/missing_file.png"
      "malformed_gltf|--scene|@DIR@/malformed.gltf|--out|@DIR@/malformed_gltf.png"
      "unknown_builtin|--scene|builtin:nosuchscene|--out|@DIR@/unknown_builtin.png"
      "unknown_option|--no-such-option|--out|@DIR@/unknown_option.png"
      "bad_effect|--effects|shadows,glitter|--out|@DIR@/bad_effect.png"
      "bad_effect_cutout|--effects|cutout|--out|@DIR@/bad_effect_cutout.png"
      "bad_image_type|--out|@DIR@/bad_image_type.bmp"
      "out_folder_missing|--out|@DIR@/no/such/folder/x.png"
      "camera_out_of_range|--camera|7|--out|@DIR@/camera_out_of_range.png"
      "pixel_outside_the_image|--width|16|--height|12|--pixel|16,0|--out|@DIR@/pixel_outside_the_image.png"
      "pixel_not_two_numbers|--pixel|3|--out|@DIR@/pixel_not_two_numbers.png"
      "pixel_with_paths_beyond_31_bits|--pixel|0,0|--max-depth|31|--out|@DIR@/pixel_with_paths_beyond_31_bits.png")
  if(stage MATCHES "^0[45]_")
    # 04 and 05 cannot count tests per pixel with cut-outs (16 storage blocks): refused before rendering.
    list(APPEND cases "heatmap_cutouts|--scene|builtin:cutouts|--width|16|--height|12|--heatmap|@DIR@/h.png|--out|@DIR@/heatmap_cutouts.png"
                      "pixel_cutouts|--scene|builtin:cutouts|--width|16|--height|12|--pixel|8,6|--out|@DIR@/pixel_cutouts.png")
  endif()
  foreach(case IN LISTS cases)
    # Arguments travel to the script "|"-separated (a ";" would split the test command).
    string(FIND "${case}" "|" bar)
    string(SUBSTRING "${case}" 0 ${bar} name)
    math(EXPR bar "${bar} + 1")
    string(SUBSTRING "${case}" ${bar} -1 args)
    string(REPLACE "@DIR@" "${out}/bad_input_${name}" args "${args}")
    add_test(NAME cli.${stage}.bad_input_${name}
             COMMAND ${CMAKE_COMMAND} -DMODE=bad_input -DEXE=${exe} -DOUT_DIR=${out}/bad_input_${name} "-DARGS=${args}"
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
  add_test(NAME cli.${stage}.export_surface_effects_renders_like_builtin
           COMMAND ${CMAKE_COMMAND} -DMODE=export_surface -DEXE=${exe} -DOUT_DIR=${out}/export_surface
                   -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
  set_tests_properties(cli.${stage}.export_surface_effects_renders_like_builtin PROPERTIES LABELS "cli;cli-${stage}")
  add_test(NAME cli.${stage}.frames_write_numbered_images
           COMMAND ${CMAKE_COMMAND} -DMODE=frames -DEXE=${exe} -DOUT_DIR=${out} -P ${script})
  # Hostile input, by class. Each case: class.name|regex its one-line error must match|argument|...;
  # @DIR@ is the case's own folder of fixtures (file, link.png -> target.png, loop_a <-> loop_b, fifo.png, folder.png,
  # read_only.png, and, when named, scene.gltf with its hard link hard_link.json, or textured.gltf with its own
  # buffer.bin and texture.png), @LONG@ a 300-byte name. The case must exit 2 with that one line and leave the folder exactly as it was (run_cli_case.cmake, MODE refused).
  set(refused
      "non_finite_option.fps_nan|--fps: nan is not a finite number|--fps|nan|--out|@DIR@/x.png"
      "non_finite_option.cutoff_nan|--cutoff: nan is not a finite number|--cutoff|nan|--out|@DIR@/x.png"
      "non_finite_option.epsilon_inf|--epsilon: inf is not a finite number|--epsilon|inf|--out|@DIR@/x.png"
      "non_finite_option.fps_overflow|--fps: 1e999 is not a finite number|--fps|1e999|--out|@DIR@/x.png"
      "non_finite_option.exposure_nan|--exposure: nan is not a finite number|--exposure|nan|--out|@DIR@/x.png"
      "readable_range.exposure_too_bright|--exposure: 21 is out of range: must be at least -20 and at most 20|--exposure|21|--out|@DIR@/x.png"
      "readable_range.exposure_word|--exposure: 'bright' is neither a number nor auto|--exposure|bright|--out|@DIR@/x.png"
      "readable_range.epsilon_negative|--epsilon: -1 is out of range: must be above 0 and at most 1000000|--epsilon|-1|--out|@DIR@/x.png"
      "readable_range.camera_negative|--camera: -1 is out of range: must be at least 0 and at most 2147483647|--camera|-1|--out|@DIR@/x.png"
      "count_limit.frames|--frames: 100000 is out of range: must be at least 1 and at most 10000|--frames|100000|--out|@DIR@/x.png"
      "count_limit.spp|--spp: 5000 is out of range: must be at least 1 and at most 4096|--spp|5000|--out|@DIR@/x.png"
      "count_limit.samples_per_frame|--spp 4096 at 16384x4096 is 274877906944 samples a frame: at most 4294967296|--width|16384|--height|4096|--spp|4096|--out|@DIR@/x.png"
      "output_clobbers_input.stats_is_scene|--stats .*scene.gltf: is the scene's input file|--scene|@DIR@/scene.gltf|--stats|@DIR@/scene.gltf|--out|@DIR@/x.png"
      "output_clobbers_input.export_is_scene|--export .*scene.gltf: is the scene's input file|--scene|@DIR@/scene.gltf|--export|@DIR@/../output_clobbers_input.export_is_scene/scene.gltf"
      "output_clobbers_input.hard_link|--stats .*hard_link.json: is the scene's input file|--scene|@DIR@/scene.gltf|--stats|@DIR@/hard_link.json|--out|@DIR@/x.png"
      "output_clobbers_input.out_is_texture|--out .*texture.png: is the scene's input file|--scene|@DIR@/textured.gltf|--out|@DIR@/texture.png"
      "output_clobbers_input.stats_is_buffer|--stats .*buffer.bin: is the scene's input file|--scene|@DIR@/textured.gltf|--stats|@DIR@/buffer.bin|--out|@DIR@/x.png"
      "output_clobbers_output.out_is_stats|--out .*x.png: is the same file as --stats|--out|@DIR@/x.png|--stats|@DIR@/./x.png"
      "output_clobbers_output.frame_is_stats|--out .*x_0001.png: is the same file as --stats|--scene|builtin:dynamic|--frames|3|--out|@DIR@/x.png|--stats|@DIR@/x_0001.png"
      "unsafe_output_target.symlink|--out .*link.png: is a symbolic link|--out|@DIR@/link.png|--stats|@DIR@/x.json"
      "unsafe_output_target.fifo|--stats .*fifo.png: is not a regular file|--stats|@DIR@/fifo.png|--out|@DIR@/x.png"
      "unsafe_output_target.folder|--out .*folder.png: is a folder|--out|@DIR@/folder.png"
      "unsafe_output_target.read_only|--out .*read_only.png: is read-only|--out|@DIR@/read_only.png|--stats|@DIR@/x.json"
      "bad_path.out_under_regular_file|--out .*file/x.png: .*file is not a folder|--out|@DIR@/file/x.png|--stats|@DIR@/x.json"
      "bad_path.out_name_too_long|--out .*nnnn.png: File name too long|--out|@DIR@/@LONG@.png|--stats|@DIR@/x.json"
      "bad_path.out_in_symlink_loop|--out .*loop_a/x.png: folder .*loop_a: Too many levels of symbolic links|--out|@DIR@/loop_a/x.png"
      "bad_path.scene_symlink_loop|cannot read scene .*loop_a: Too many levels of symbolic links|--scene|@DIR@/loop_a|--out|@DIR@/x.png"
      "bad_path.scene_name_too_long|cannot read scene .*nnnn.gltf: File name too long|--scene|@DIR@/@LONG@.gltf|--out|@DIR@/x.png"
      "bad_path.scene_under_regular_file|cannot read scene .*file/x.gltf: Not a directory|--scene|@DIR@/file/x.gltf|--out|@DIR@/x.png"
      "bad_path.scene_is_fifo|scene .*fifo.png is not a regular file|--scene|@DIR@/fifo.png|--out|@DIR@/x.png"
      # What rays leaving the scene see (docs/shading.md, "The environment"); sky.hdr is a copy of tests/data's map.
      "environment.background_syntax|--background: '1,2' is not R,G,B|--background|1,2|--out|@DIR@/x.png"
      "environment.background_word|--background: '1,x,0' is not R,G,B: 'x' is not a number|--background|1,x,0|--out|@DIR@/x.png"
      "environment.background_nan|--background: '0,nan,0': nan is not a finite number|--background|0,nan,0|--out|@DIR@/x.png"
      "environment.background_negative|--background: '0,-1,0': -1 is out of range|--background|0,-1,0|--out|@DIR@/x.png"
      "environment.background_huge|--background: '1e21,0,0': 1e21 is out of range|--background|1e21,0,0|--out|@DIR@/x.png"
      "environment.intensity_nan|--environment-intensity: nan is not a finite number|--environment|@DIR@/sky.hdr|--environment-intensity|nan|--out|@DIR@/x.png"
      "environment.intensity_negative|--environment-intensity: -1 is out of range|--environment|@DIR@/sky.hdr|--environment-intensity|-1|--out|@DIR@/x.png"
      "environment.intensity_huge|--environment-intensity: 1e30 is out of range|--environment|@DIR@/sky.hdr|--environment-intensity|1e30|--out|@DIR@/x.png"
      "environment.intensity_times_texel_too_bright|environment .*sky.hdr: texel .* above 1e20|--environment|@DIR@/sky.hdr|--environment-intensity|1e20|--out|@DIR@/x.png"
      "environment.rotation_inf|--environment-rotation: inf is not a finite number|--environment|@DIR@/sky.hdr|--environment-rotation|inf|--out|@DIR@/x.png"
      "environment.rotation_without_map|--environment-rotation requires --environment|--environment-rotation|30|--out|@DIR@/x.png"
      "environment.missing_file|environment .*no_such_sky.hdr: file not found|--environment|@DIR@/no_such_sky.hdr|--out|@DIR@/x.png"
      "environment.wrong_extension|environment .*target.png: not a .hdr or .exr file|--environment|@DIR@/target.png|--out|@DIR@/x.png"
      "environment.not_an_image|environment .*broken.hdr: not a readable image|--environment|@DIR@/broken.hdr|--out|@DIR@/x.png"
      "output_clobbers_input.out_is_environment|--out .*sky.hdr: is the scene's input file|--environment|@DIR@/sky.hdr|--out|@DIR@/sky.hdr")
  # GPU stages: an image whose per-pixel sums do not fit one storage block (forced small with $RT_MAX_SSBO_BYTES; a
  # 16384-wide image on llvmpipe's 128 MiB does the same) is bad input, and so is a malformed limit.
  if(stage IN_LIST RT_GPU_STAGES)
    list(APPEND refused
         "storage_limit.image_too_large|a 1024x8 image needs 294912 bytes .*storage block limit of 65536 bytes|--width|1024|--height|8|--out|@DIR@/x.png"
         "storage_limit.bad_env|RT_MAX_SSBO_BYTES: expected a positive number of bytes|--out|@DIR@/x.png")
  endif()
  foreach(case IN LISTS refused)
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 name)
    list(GET parts 1 expect)
    list(SUBLIST parts 2 -1 args)
    string(REPLACE ";" "|" args "${args}")
    add_test(NAME cli.${stage}.${name}
             COMMAND ${CMAKE_COMMAND} -DMODE=refused -DEXE=${exe} -DOUT_DIR=${out} "-DARGS=${args}"
                     "-DEXPECT=${expect}" -DNAME=${name} -P ${script})
    set_tests_properties(cli.${stage}.${name} PROPERTIES LABELS "cli;cli-${stage}")
  endforeach()
  if(stage IN_LIST RT_GPU_STAGES)
    set_tests_properties(cli.${stage}.storage_limit.image_too_large PROPERTIES ENVIRONMENT RT_MAX_SSBO_BYTES=65536)
    set_tests_properties(cli.${stage}.storage_limit.bad_env PROPERTIES ENVIRONMENT RT_MAX_SSBO_BYTES=64k)
  endif()
  foreach(mode closed_stdout concurrent_export interrupted static_frames help_lists_builtins unsupported_extensions
               pixel_ray_tree)
    add_test(NAME cli.${stage}.${mode}
             COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DEXE=${exe} -DOUT_DIR=${out} -P ${script})
    set_tests_properties(cli.${stage}.${mode} PROPERTIES LABELS "cli;cli-${stage}")
  endforeach()
  add_test(NAME cli.${stage}.defaults_for_gltf
           COMMAND ${CMAKE_COMMAND} -DMODE=defaults_for_gltf -DEXE=${exe} -DOUT_DIR=${out}
                   -DDATA=${PROJECT_SOURCE_DIR}/tests/data -P ${script})
  set_tests_properties(cli.${stage}.defaults_for_gltf PROPERTIES LABELS "cli;cli-${stage}")
  # The environment costs nothing unused, and a map adds no ray (run_environment_case.cmake).
  add_test(NAME cli.${stage}.environment_costs_nothing_unused
           COMMAND ${CMAKE_COMMAND} -DEXE=${exe} -DOUT_DIR=${out}/environment_costs -DCOMPARE=$<TARGET_FILE:image_compare>
                   -DSKY=${PROJECT_SOURCE_DIR}/tests/data/sky_64x32.hdr
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/run_environment_case.cmake)
  set_tests_properties(cli.${stage}.environment_costs_nothing_unused PROPERTIES LABELS "cli;cli-${stage}")
  add_test(NAME cli.${stage}.extreme_values_stay_finite
           COMMAND ${CMAKE_COMMAND} -DMODE=extreme_values_stay_finite -DEXE=${exe} -DOUT_DIR=${out}
                   -DCOMPARE=$<TARGET_FILE:image_compare> -P ${script})
  set_tests_properties(cli.${stage}.extreme_values_stay_finite PROPERTIES LABELS "cli;cli-${stage}")
  set_tests_properties(cli.${stage}.stats_has_every_key cli.${stage}.diffuse_scene_spends_nothing_on_unused_effects
                       cli.${stage}.export_gltf_renders_like_builtin cli.${stage}.frames_write_numbered_images
                       PROPERTIES LABELS "cli;cli-${stage}")
endfunction()

foreach(stage IN LISTS RT_STAGES)   # tests/stages.txt
  rt_add_cli_tests(${stage})
endforeach()
