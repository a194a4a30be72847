# One case of the animation-channel tests (animation_channels.cmake), at test time. MODE says which:
#   pointer    B = A with every channel rewritten as a KHR_animation_pointer channel (make_animation_cases.py
#              pointer-copy, MESH_WEIGHTS=ON: node weights as the mesh's weights where that is the same);
#              `dqskin diff A B --json` must pass with every clip's max errors exactly 0. A is compared with
#              itself first, so that a failure is not a model diff cannot read. Skipped when A is missing.
#   identical  FILE (ORIGINAL's channel repeated 14 times) loads with one warning naming the count, and bakes
#              to the same bytes as ORIGINAL (every frame file, glb and ply).
#   different  FILE (two channels for one node and path with different keys): `bake` refuses with one line
#              naming both channels; `info` names them too (on stdout as a finding, or as its one error line);
#              `lint` exits 2 with duplicate-channel; `lint --fix` writes a file without it, which bakes to
#              the same bytes as ORIGINAL (the first channel kept) and not as SECOND (the second kept), and
#              which the Khronos glTF-Validator accepts (skipped when it is not installed).
#
#   cmake -DDQSKIN=dqskin -DMODE=pointer -DPYTHON=python3 -DSCRIPT=make_animation_cases.py -DA=in.glb
#         -DWORK=folder [-DMESH_WEIGHTS=ON] -P animation_case.cmake
#   cmake -DDQSKIN=dqskin -DMODE=identical|different -DFILE=case.gltf -DORIGINAL=rig.gltf [-DSECOND=other.gltf
#         -DNODE=node -DVALIDATOR=dir -DVALIDATE_SCRIPT=validate_gltf.mjs] -DWORK=folder -P animation_case.cmake
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND "${DQSKIN}" ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 600)
  set(status "${status}" PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_status command expected)
  if(NOT status STREQUAL "${expected}")
    message(FATAL_ERROR "dqskin ${command}: exit status '${status}', expected ${expected}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
endfunction()

# Bakes `file` as glb and ply frames into WORK/name; sets `frames` to the "relative path;hash" list of every
# frame file (the manifest names the input, so it is left out).
function(bake_frames file name)
  run(bake "${file}" -o "${WORK}/${name}" --format glb,ply --fps 10)
  expect_status("bake ${file}" 0)
  get_filename_component(stem "${file}" NAME_WE)
  file(GLOB_RECURSE files RELATIVE "${WORK}/${name}/${stem}" "${WORK}/${name}/${stem}/*")
  list(SORT files)
  set(result "")
  foreach(f IN LISTS files)
    file(SHA256 "${WORK}/${name}/${stem}/${f}" hash)
    list(APPEND result "${f} ${hash}")
  endforeach()
  list(LENGTH result n)
  if(n LESS 2)
    message(FATAL_ERROR "bake ${file} wrote ${n} frame files")
  endif()
  set(frames "${result}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

if(MODE STREQUAL "pointer")
  if(NOT EXISTS "${A}")
    message("animation: SKIPPED: ${A} is missing (the shared models are in ../shared/testdata beside the repository)")
    return()
  endif()
  get_filename_component(ext "${A}" EXT)
  set(B "${WORK}/pointer${ext}")
  set(flags "")
  if(MESH_WEIGHTS)
    set(flags --mesh-weights)
  endif()
  execute_process(COMMAND "${PYTHON}" "${SCRIPT}" pointer-copy "${A}" "${B}" ${flags} RESULT_VARIABLE status
                  OUTPUT_VARIABLE made ERROR_VARIABLE err)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "make_animation_cases.py pointer-copy ${A} failed (${status}):\n${made}${err}")
  endif()
  message("${made}")
  run(diff "${A}" "${A}")
  expect_status("diff ${A} ${A}" 0)
  run(diff "${A}" "${B}" --json)
  expect_status("diff ${A} ${B}" 0)
  string(JSON clips ERROR_VARIABLE problem LENGTH "${out}" clips)
  if(problem OR clips LESS 1)
    message(FATAL_ERROR "dqskin diff ${A} ${B}: no clips in the report ${problem}\n${out}")
  endif()
  math(EXPR last "${clips} - 1")
  foreach(i RANGE ${last})
    foreach(key max_error max_error_relative)
      string(JSON value GET "${out}" clips ${i} ${key})
      if(NOT value EQUAL 0)
        message(FATAL_ERROR "dqskin diff ${A} ${B}: clip ${i}: ${key} is ${value}, not exactly 0\n${out}")
      endif()
    endforeach()
  endforeach()
  return()
endif()

if(MODE STREQUAL "identical")
  run(info "${FILE}")
  expect_status("info ${FILE}" 0)
  string(REGEX MATCHALL "duplicate channel" mentions "${out}${err}")
  list(LENGTH mentions n)
  if(NOT n EQUAL 1 OR NOT out MATCHES "animation 0 'twist': 14 duplicate channels \\(the same node, path and keys as an earlier channel\\) are ignored")
    message(FATAL_ERROR "dqskin info ${FILE}: expected one warning naming 14 duplicate channels\n${out}${err}")
  endif()
  bake_frames("${FILE}" case)
  set(case_frames "${frames}")
  bake_frames("${ORIGINAL}" original)
  if(NOT case_frames STREQUAL frames)
    message(FATAL_ERROR "${FILE} bakes differently from ${ORIGINAL}:\n${case_frames}\n${frames}")
  endif()
  return()
endif()

if(MODE STREQUAL "different")
  set(both "animation 0 'twist': channels 0 and 1 both animate node 2 'child' rotation with different keys")
  run(bake "${FILE}" -o "${WORK}/refused")
  expect_status("bake ${FILE}" 2)
  if(NOT err MATCHES "^dqskin: [^\n]*: ${both}[^\n]*\n$" OR EXISTS "${WORK}/refused/manifest.json")
    message(FATAL_ERROR "dqskin bake ${FILE}: expected one line naming both channels, and no output\n${err}")
  endif()
  # info reports the file: as a finding once it describes files it cannot deform, else as its one error line.
  run(info "${FILE}")
  if(NOT status MATCHES "^[02]$" OR NOT "${out}${err}" MATCHES "${both}")
    message(FATAL_ERROR "dqskin info ${FILE}: exit status ${status}, and no line naming both channels\n${out}${err}")
  endif()
  run(lint --json "${FILE}")
  expect_status("lint ${FILE}" 2)
  string(JSON check ERROR_VARIABLE problem GET "${out}" files 0 findings 0 check)
  if(NOT check STREQUAL "duplicate-channel")
    message(FATAL_ERROR "dqskin lint ${FILE}: expected the finding duplicate-channel ${problem}\n${out}")
  endif()
  set(fixed "${WORK}/fixed.glb")
  run(lint --json --fix "${FILE}" -o "${fixed}")
  expect_status("lint --fix ${FILE}" 0)
  string(JSON after ERROR_VARIABLE problem LENGTH "${out}" files 1 findings)
  if(NOT after EQUAL 0)
    message(FATAL_ERROR "dqskin lint --fix ${FILE}: the fixed file still has findings\n${out}")
  endif()
  bake_frames("${fixed}" fixed)
  set(fixed_frames "${frames}")
  bake_frames("${ORIGINAL}" original)
  if(NOT fixed_frames STREQUAL frames)
    message(FATAL_ERROR "the fixed ${FILE} bakes differently from ${ORIGINAL} (the first channel):\n${fixed_frames}\n${frames}")
  endif()
  bake_frames("${SECOND}" second)
  if(fixed_frames STREQUAL frames)
    message(FATAL_ERROR "the fixed ${FILE} bakes like ${SECOND} (the second channel): the bakes do not tell them apart")
  endif()
  if(NOT NODE OR NOT EXISTS "${VALIDATOR}/package.json")
    message("animation: validation skipped: Node.js or the gltf-validator (scripts/install/node_tools.sh) is missing")
    return()
  endif()
  execute_process(COMMAND "${NODE}" "${VALIDATE_SCRIPT}" --validator "${VALIDATOR}" "${fixed}" RESULT_VARIABLE status
                  OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "the glTF-Validator finds errors in the fixed ${FILE}:\n${out}${err}")
  endif()
  return()
endif()

message(FATAL_ERROR "animation_case.cmake: unknown MODE '${MODE}'")
