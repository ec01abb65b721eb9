# See tests/portable.cmake. Runs the portable 01_naive that portable.binaries_need_only_small_libraries built.
# The portable build reads Radiance .hdr environments through stb_image. It must give the same texels as
# OpenImageIO's: the portable 01_naive renders stage 01's environment golden. It must refuse a truncated file, flat
# or run-length encoded, with exit 2: stb reads zeros past the end, and a zero run length would loop forever (the
# 60 s limit catches a hang).
set(out ${BUILD}/environment-check)
file(REMOVE_RECURSE ${out})
file(MAKE_DIRECTORY ${out})
execute_process(COMMAND ${BUILD}/bin/01_naive --scene builtin:whitted --width 160 --height 120 --quiet
                        --environment ${SOURCE}/tests/data/sky_64x32.hdr --environment-rotation 30
                        --environment-intensity 0.8 --out ${out}/environment.png RESULT_VARIABLE rc TIMEOUT 600)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the portable 01_naive failed to render the environment scene (exit ${rc})")
endif()
execute_process(COMMAND ${COMPARE} ${out}/environment.png ${SOURCE}/tests/golden/01_naive/environment.png
                        --name portable_environment --diff-dir ${out} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the portable build's environment image differs from tests/golden/01_naive/environment.png")
endif()
# rle.hdr: 64x4, each scanline's four channels one run each (stb's and Radiance's new RLE scanlines).
execute_process(COMMAND python3 -c "
import sys
out = bytearray(b'#?RADIANCE\\nFORMAT=32-bit_rle_rgbe\\n\\n-Y 4 +X 64\\n')
for y in range(4):
    out += bytes([2, 2, 0, 64])
    for value in (100 + y, 50, 25, 129):
        out += bytes([128 + 64, value])
open(sys.argv[1], 'wb').write(out)
flat = open(sys.argv[2], 'rb').read()
open(sys.argv[3], 'wb').write(out[:-7])
open(sys.argv[4], 'wb').write(flat[:-1])
" ${out}/rle.hdr ${SOURCE}/tests/data/sky_64x32.hdr ${out}/rle_truncated.hdr ${out}/flat_truncated.hdr
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not write the .hdr test files")
endif()
foreach(case rle:0 rle_truncated:2 flat_truncated:2)
  string(REPLACE ":" ";" case ${case})
  list(GET case 0 name)
  list(GET case 1 want)
  execute_process(COMMAND ${BUILD}/bin/01_naive --scene builtin:whitted --width 8 --height 6 --quiet
                          --environment ${out}/${name}.hdr --out ${out}/${name}.png
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
  if(NOT "${rc}" STREQUAL "${want}")
    message(FATAL_ERROR "the portable 01_naive on ${name}.hdr: exit ${rc} (expected ${want}): ${err}")
  endif()
  if(want EQUAL 2 AND EXISTS ${out}/${name}.png)
    message(FATAL_ERROR "the portable 01_naive wrote ${out}/${name}.png from a refused ${name}.hdr")
  endif()
  message(STATUS "${name}.hdr: exit ${rc} ${err}")
endforeach()
