# `--max-influences N` deforms as if the file held only each vertex's N largest influences: a bake of
# FILE with `--max-influences KEEP` writes the same frame_NNNN.ply bytes as a bake of CUT (the same rig
# with the KEEP largest kept, from the generator) and as a bake of `lint --fix --max-influences KEEP FILE`;
# a bake of FILE without the flag differs (the dropped weights matter); the manifest records the flag.
#
#   cmake -DDQSKIN=dqskin -DFILE=in.gltf -DCUT=cut.gltf -DKEEP=4 -DBACKEND=cpu -DWORK=folder
#         -P influence_cut.cmake
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

function(run)
  execute_process(COMMAND "${DQSKIN}" ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status STREQUAL "0")
    string(REPLACE ";" " " line "${ARGN}")
    message(FATAL_ERROR "dqskin ${line}: exit status ${status}\n${out}${err}")
  endif()
endfunction()

# The frame_NNNN.ply files of the one animation baked from INPUT into OUT, in frame order.
function(bake input out result)
  run(bake "${input}" -o "${out}" --format ply --mode lbs --backend ${BACKEND} --fps 8 ${ARGN} -q)
  file(GLOB_RECURSE frames "${out}/*/frame_*.ply")
  list(SORT frames)
  list(LENGTH frames count)
  if(count EQUAL 0)
    message(FATAL_ERROR "bake of ${input} wrote no frame_NNNN.ply into ${out}")
  endif()
  set(${result} "${frames}" PARENT_SCOPE)
endfunction()

function(expect_same_frames what a b)
  list(LENGTH a count_a)
  list(LENGTH b count_b)
  if(NOT count_a EQUAL count_b)
    message(FATAL_ERROR "${what}: ${count_a} frames against ${count_b}")
  endif()
  math(EXPR last "${count_a} - 1")
  foreach(i RANGE ${last})
    list(GET a ${i} fa)
    list(GET b ${i} fb)
    file(SHA256 "${fa}" ha)
    file(SHA256 "${fb}" hb)
    if(NOT ha STREQUAL hb)
      message(FATAL_ERROR "${what}: ${fa} and ${fb} differ")
    endif()
  endforeach()
endfunction()

bake("${FILE}" "${WORK}/flag" flag --max-influences ${KEEP})
bake("${CUT}" "${WORK}/cut" cut)
expect_same_frames("bake --max-influences ${KEEP} against the cut file" "${flag}" "${cut}")

# Its exit status is the fixed file's lint verdict, not whether the fix was written.
execute_process(COMMAND "${DQSKIN}" lint --fix --max-influences ${KEEP} "${FILE}" -o "${WORK}/fixed.glb"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
if(NOT status MATCHES "^[012]$" OR NOT EXISTS "${WORK}/fixed.glb")
  message(FATAL_ERROR "dqskin lint --fix --max-influences ${KEEP}: exit status ${status}, no fixed file\n${out}${err}")
endif()
bake("${WORK}/fixed.glb" "${WORK}/fixed" fixed)
expect_same_frames("bake --max-influences ${KEEP} against lint --fix --max-influences ${KEEP}" "${flag}" "${fixed}")

bake("${FILE}" "${WORK}/all" all)
list(GET flag -1 last_flag)
list(GET all -1 last_all)
file(SHA256 "${last_flag}" ha)
file(SHA256 "${last_all}" hb)
if(ha STREQUAL hb)
  message(FATAL_ERROR "bake --max-influences ${KEEP} wrote what a bake of every influence writes: the flag did nothing")
endif()

file(READ "${WORK}/flag/manifest.json" manifest)
string(JSON recorded ERROR_VARIABLE missing GET "${manifest}" max_influences)
if(missing OR NOT recorded STREQUAL "${KEEP}")
  message(FATAL_ERROR "manifest.json does not record max_influences ${KEEP}: ${missing}\n${manifest}")
endif()
file(READ "${WORK}/all/manifest.json" manifest)
string(JSON recorded ERROR_VARIABLE missing GET "${manifest}" max_influences)
if(NOT missing)
  message(FATAL_ERROR "manifest.json of a bake without --max-influences records max_influences ${recorded}")
endif()
message("influence_cut: the frames of bake --max-influences ${KEEP}, of the cut file and of lint --fix agree byte for byte")
