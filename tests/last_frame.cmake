# last_frame_suffix(<args list> <out var>): what frame_path (common/app) adds to a file name for the last frame a
# run with these arguments writes: with "--frames N" it writes <name>_0000 ... <name>_(N-1) and the tests compare the
# last one ("_0002" for N = 3); one frame, "--frames 1" included, keeps the name as given (""). scripts/golden_cases.py
# (frame_suffixes) has the same rule.
function(last_frame_suffix args out)
  set(suffix "")
  list(FIND args --frames at)
  if(at GREATER_EQUAL 0)
    math(EXPR at "${at} + 1")
    list(GET args ${at} frames)
    if(frames LESS_EQUAL 1)   # frame_path leaves a single frame's name alone
      set(${out} "" PARENT_SCOPE)
      return()
    endif()
    math(EXPR last "${frames} - 1")
    string(LENGTH "${last}" digits)
    while(digits LESS 4)   # frame_path's %04d
      string(PREPEND last "0")
      math(EXPR digits "${digits} + 1")
    endwhile()
    set(suffix _${last})
  endif()
  set(${out} "${suffix}" PARENT_SCOPE)
endfunction()
