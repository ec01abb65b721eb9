# readme.commands_render: every stage command of the READMEs runs (at 64x48) and writes what it names under out/,
# which git ignores (tests/run_readme_commands.py).
if(RT_PYTHON3)
  add_test(NAME readme.commands_render
           COMMAND ${RT_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/run_readme_commands.py --root ${PROJECT_SOURCE_DIR}
                   --bin-dir ${CMAKE_BINARY_DIR}/bin --work ${CMAKE_BINARY_DIR}/test-output/readme)
  set_tests_properties(readme.commands_render PROPERTIES LABELS "readme")
endif()
