# One hits.<stage>.<scene> test (tests/hits.cmake): the stage's frame and hit dump are the ones golden.<stage>.<scene>
# rendered (RENDERED_IN, a CTest fixture: 160x120, --dump-hits); its reference renders the scene the same way (kept
# in REFERENCE_CACHE), and compare_hits compares the dumps with BOUNDS; with SAME_IMAGE=1 the images must also be
# equal (threshold 0). With RETRACE_EXE, the stage's rays are also traced again by it (retrace_hits) and compared
# with RETRACE_BOUNDS on every driver, while the comparison with the reference's own render is asserted on llvmpipe
# only (hits.cmake says why). With "--frames N" in ARGS the last frame is compared.
string(REPLACE "|" ";" ARGS "${ARGS}")
string(REPLACE "|" ";" BOUNDS "${BOUNDS}")
file(MAKE_DIRECTORY ${OUT_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/last_frame.cmake)
last_frame_suffix("${ARGS}" suffix)   # with --frames N, the last frame's files are compared

# The reference's render is kept (REFERENCE_CACHE) under a key of everything it is made from: the reference
# executable, the shaders it may read (REFERENCE_SHADERS: the shader folders of common/ and of the stages up to it),
# the scene, the arguments, the files they name, and the environment variables that change a render. Stages 03-05
# then compare with one 02 render per scene, and a re-grade after editing a later stage does not render 02 again;
# any change to what 02 is built or shaded from makes a new key.
function(reference_key out)
  file(SHA256 ${REFERENCE_EXE} key)
  string(REPLACE "|" ";" folders "${REFERENCE_SHADERS}")
  foreach(folder IN LISTS folders)
    file(GLOB_RECURSE shaders LIST_DIRECTORIES false ${folder}/*)
    list(SORT shaders)
    foreach(shader IN LISTS shaders)
      file(SHA256 ${shader} h)
      string(APPEND key ";${shader}=${h}")
    endforeach()
  endforeach()
  string(APPEND key ";${SCENE};${size};${ARGS};exr")
  foreach(arg IN LISTS ARGS)
    if(EXISTS "${arg}" AND NOT IS_DIRECTORY "${arg}")
      file(SHA256 ${arg} h)
      string(APPEND key ";${arg}=${h}")
    endif()
  endforeach()
  foreach(variable RT_SHADER_DIR GALLIUM_DRIVER LIBGL_ALWAYS_SOFTWARE LP_NUM_THREADS MESA_LOADER_DRIVER_OVERRIDE)
    string(APPEND key ";${variable}=$ENV{${variable}}")
  endforeach()
  string(SHA256 key "${key}")
  set(${out} ${key} PARENT_SCOPE)
endfunction()

set(size --width ${WIDTH} --height ${HEIGHT})   # the golden frame's (tests/golden.cmake: RT_GOLDEN_WIDTH/HEIGHT)
set(stage_hits ${RENDERED_IN}/${NAME}${suffix}.hits)
set(stage_image ${RENDERED_IN}/${NAME}${suffix}.exr)
set(stage_stats ${RENDERED_IN}/${NAME}.json)
foreach(f IN ITEMS ${stage_hits} ${stage_image} ${stage_stats})
  if(NOT EXISTS ${f})
    message(FATAL_ERROR "no ${f}: golden.<stage>.${NAME} renders it (it did not, or failed)")
  endif()
endforeach()

get_filename_component(reference_name ${REFERENCE_EXE} NAME)
set(base ${OUT_DIR}/${NAME}.reference)
set(reference_hits ${base}${suffix}.hits)
set(reference_image ${base}${suffix}.exr)
file(REMOVE ${reference_hits} ${reference_image})
reference_key(key)
set(cached ${REFERENCE_CACHE}/${reference_name}.${NAME}.${key})
if(EXISTS ${cached}.hits AND EXISTS ${cached}.exr)
  file(COPY_FILE ${cached}.hits ${reference_hits})
  file(COPY_FILE ${cached}.exr ${reference_image})
  message(STATUS "${reference_name} on ${SCENE}: its render of an earlier run (the same binary, shaders, scene)")
else()
  execute_process(COMMAND ${REFERENCE_EXE} --scene ${SCENE} ${size} --quiet --dump-hits ${base}.hits
                          --out ${base}.exr ${ARGS}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${REFERENCE_EXE} failed on ${SCENE} (exit ${rc}):\n${out}\n${err}")
  endif()
  # Into the cache under names of this process, then renamed (atomic: tests running beside this one may read it);
  # the renders of earlier keys for this scene go.
  file(GLOB stale ${REFERENCE_CACHE}/${reference_name}.${NAME}.*)
  file(MAKE_DIRECTORY ${REFERENCE_CACHE})
  string(RANDOM LENGTH 12 tag)
  file(COPY_FILE ${reference_hits} ${cached}.hits.${tag}.tmp)
  file(COPY_FILE ${reference_image} ${cached}.exr.${tag}.tmp)
  list(FILTER stale EXCLUDE REGEX "\\.${key}\\.")
  if(stale)
    file(REMOVE ${stale})
  endif()
  file(RENAME ${cached}.hits.${tag}.tmp ${cached}.hits)
  file(RENAME ${cached}.exr.${tag}.tmp ${cached}.exr)
endif()

set(asserted TRUE)
if(RETRACE_EXE)
  string(REPLACE "|" ";" RETRACE_BOUNDS "${RETRACE_BOUNDS}")
  set(base ${OUT_DIR}/${NAME}.retraced)
  file(REMOVE ${base}${suffix}.hits)
  execute_process(COMMAND ${RETRACE_EXE} --rays ${stage_hits} --scene ${SCENE} ${size} --quiet
                          --dump-hits ${base}.hits ${ARGS}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${RETRACE_EXE} failed on ${SCENE} (exit ${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "its tracing: each of its rays traced again by 01's brute force")
  execute_process(COMMAND ${COMPARE_HITS} ${stage_hits} ${base}${suffix}.hits ${RETRACE_BOUNDS} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${EXE} traced its rays to other hits than brute force does on ${SCENE} "
                        "(compare_hits exit ${rc})")
  endif()
  # The renderer, from the stage's stats: the path-by-path comparison holds where the GPU rounds like the CPU.
  file(READ ${stage_stats} stats_json)
  string(JSON renderer ERROR_VARIABLE json_error GET "${stats_json}" renderer)
  if(json_error OR NOT renderer MATCHES "llvmpipe")
    set(asserted FALSE)
  endif()
  message(STATUS "its rays, path by path against ${REFERENCE_EXE}'s render (on ${renderer})")
endif()
execute_process(COMMAND ${COMPARE_HITS} ${stage_hits} ${reference_hits} ${BOUNDS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 AND asserted)
  message(FATAL_ERROR "the hits of ${EXE} differ from ${REFERENCE_EXE}'s on ${SCENE} (compare_hits exit ${rc})")
elseif(NOT rc EQUAL 0)
  message(STATUS "not asserted on ${renderer}: its division and square roots are not the CPU's, and the rays of a "
                 "path drift apart (tests/hits.cmake); its tracing passed above")
endif()
if(SAME_IMAGE)
  execute_process(COMMAND ${COMPARE} ${stage_image} ${reference_image} --threshold 0 --fail-fraction 0 --name ${NAME}
                          --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the image of ${EXE} differs from ${REFERENCE_EXE}'s on ${SCENE} (threshold 0)")
  endif()
endif()
