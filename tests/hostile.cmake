# Hostile conditions every stage gets:
#   writes.<stage>.full_disk       every output kind and format, written where the disk cannot take it (a 512-byte
#                                  file-size limit for any user; a full tmpfs as root), exits 1 with one line naming
#                                  the file and the cause, leaves the previous file untouched and no temporary behind
#                                  (tests/write_failures.py).
#   options.<stage>.hostile_values every option in the stage's --help fed "", " ", "nan", "1e400", "-0", "0x10", "4.0",
#                                  " 4" and its bounds: runs or is refused in one line naming the option, never a
#                                  crash (tests/hostile_options.py). The options 01_naive has are parsed by shared
#                                  code and tested there once; the GPU stages test their own.
#   gpu.<stage>.broken_driver      GALLIUM_DRIVER=bogus on every backend, a missing libOSMesa, a missing libEGL and
#                                  both: one error line, exit 1, nothing changed or left behind; no libEGL or libOSMesa
#                                  among the libraries loaded at start (tests/broken_driver.py).
if(RT_PYTHON3)
  foreach(stage IN LISTS RT_STAGES)
    add_test(NAME writes.${stage}.full_disk
             COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/write_failures.py --bin-dir ${CMAKE_BINARY_DIR}/bin
                     --stage ${stage} --work ${CMAKE_BINARY_DIR}/test-output/writes/${stage})
    set_tests_properties(writes.${stage}.full_disk PROPERTIES LABELS "writes;hostile" TIMEOUT 600)
    set(own "")
    if(NOT stage STREQUAL "01_naive")
      set(own --own-only)
    endif()
    add_test(NAME options.${stage}.hostile_values
             COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/hostile_options.py --bin-dir ${CMAKE_BINARY_DIR}/bin
                     --stage ${stage} --work ${CMAKE_BINARY_DIR}/test-output/options/${stage} ${own})
    set_tests_properties(options.${stage}.hostile_values PROPERTIES LABELS "options;hostile" TIMEOUT 900)
    if(stage IN_LIST RT_GPU_STAGES)
      add_test(NAME gpu.${stage}.broken_driver
               COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/broken_driver.py --bin-dir ${CMAKE_BINARY_DIR}/bin
                       --stage ${stage} --work ${CMAKE_BINARY_DIR}/test-output/broken_driver/${stage})
      set_tests_properties(gpu.${stage}.broken_driver PROPERTIES LABELS "gpu;hostile" TIMEOUT 600)
    endif()
  endforeach()
endif()
