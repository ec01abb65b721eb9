# The environment costs nothing unless asked for (docs/shading.md, "The environment"). Invoked by CTest as:
#   cmake -DEXE=<stage> -DOUT_DIR=<dir> -DCOMPARE=<image_compare> -DSKY=<tests/data/sky_64x32.hdr> -P run_environment_case.cmake
# builtin:whitted at 80x60, three ways:
#   plain                     the stats name no environment; a GPU stage compiles without RT_ENVIRONMENT;
#   --background 0.2,0.3,0.5  whitted's own colour through the option: the same image at threshold 0;
#   --environment SKY         RT_ENVIRONMENT (GPU), the same programs and exactly the same rays of every kind: the
#                             map is looked up where rays leave the scene, it traces nothing.
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

function(render name)
  execute_process(COMMAND ${EXE} --scene builtin:whitted --width 80 --height 60 --quiet --out ${OUT_DIR}/${name}.exr
                          --stats ${OUT_DIR}/${name}.json ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit ${rc}: ${err}")
  endif()
  file(READ ${OUT_DIR}/${name}.json json)
  set(json_${name} "${json}" PARENT_SCOPE)
endfunction()

render(plain)
render(background --background 0.2,0.3,0.5)
render(mapped --environment ${SKY} --environment-rotation 30)

string(JSON plain_environment ERROR_VARIABLE none GET "${json_plain}" environment)
if(NOT none)
  message(FATAL_ERROR "plain: the stats report an environment: ${plain_environment}")
endif()
string(JSON mapped_width GET "${json_mapped}" environment width)
if(NOT mapped_width EQUAL 64)
  message(FATAL_ERROR "mapped: the stats should report the 64-wide map, got ${mapped_width}")
endif()

string(JSON plain_defines ERROR_VARIABLE cpu_stage GET "${json_plain}" shader_defines)
if(NOT cpu_stage)   # a GPU stage
  string(JSON mapped_defines GET "${json_mapped}" shader_defines)
  if(plain_defines MATCHES "RT_ENVIRONMENT" OR NOT mapped_defines MATCHES "\"RT_ENVIRONMENT\"")
    message(FATAL_ERROR "RT_ENVIRONMENT should be defined with a map only: plain ${plain_defines}, mapped ${mapped_defines}")
  endif()
  string(JSON plain_programs GET "${json_plain}" programs)
  string(JSON mapped_programs GET "${json_mapped}" programs)
  if(NOT plain_programs STREQUAL mapped_programs)
    message(FATAL_ERROR "a map changed the programs: ${plain_programs} -> ${mapped_programs}")
  endif()
endif()
foreach(kind primary shadow reflection refraction transparency)
  string(JSON plain_rays GET "${json_plain}" rays ${kind})
  string(JSON mapped_rays GET "${json_mapped}" rays ${kind})
  if(NOT plain_rays EQUAL mapped_rays)
    message(FATAL_ERROR "a map changed the ${kind} rays: ${plain_rays} -> ${mapped_rays}")
  endif()
endforeach()

execute_process(COMMAND ${COMPARE} ${OUT_DIR}/background.exr ${OUT_DIR}/plain.exr --threshold 0 --fail-fraction 0
                        --name background_vs_plain --diff-dir ${OUT_DIR} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "--background with the scene's own colour changed the image")
endif()
execute_process(COMMAND ${COMPARE} ${OUT_DIR}/mapped.exr ${OUT_DIR}/plain.exr --threshold 0.05 --fail-fraction 0.05
                        --name mapped_vs_plain RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "--environment did not change the image")
endif()
