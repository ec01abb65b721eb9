# Helpers for the tests that run one of scripts/ under cmake -P (lesson.cmake, check_exact.cmake).
#   run_script(<rc> <stdout> <stderr> command args...)   runs it, capturing its exit status and both streams.
#   expect_refusal(<name> command args...)               it must refuse: exit 2, nothing on stdout and one line
#                                                        "<name>: error: ..." on stderr (the project's bad-input rule).
function(run_script rc_var out_var err_var)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${rc_var} "${rc}" PARENT_SCOPE)
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${err_var} "${err}" PARENT_SCOPE)
endfunction()

function(expect_refusal name)
  run_script(rc out err ${ARGN})
  string(STRIP "${err}" err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^${name}: error: " OR err MATCHES "\n" OR NOT out STREQUAL "")
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "${command}: expected exit 2 and one '${name}: error:' line on stderr, got ${rc}:\n"
                        "${err}${out}")
  endif()
endfunction()
