# One model through another runtime's own bone-texture reader (web/CMakeLists.txt), at test time:
#   1. bakes MODEL's clip CLIP (with COMBINED, every clip into one texture: --combine-clips) at FPS with
#      --mode lbs (these runtimes blend linearly) into WORK/bake:
#      --format bones in RUNTIME's profile (babylon: mat4, playcanvas: mat3x4), and a VAT only for its
#      vat.json, whose clip bounds both renderers frame;
#   2. renders the same frames with `dqskin render --mode lbs --shade normals --size 256x256` into WORK/render;
#   3. draws each of FRAMES with the runtime's page (web/runtimes/RUNTIME.html: Babylon.js's baked vertex
#      animation, or PlayCanvas's skinning chunk fed one row of the texture a frame) in headless Chromium
#      (web/runtimes/capture.mjs), into WORK/shots;
#   4. compares every shot with dqskin's render of that frame as the three.js player's test does
#      (shot_comparison.cmake's thresholds): `dqskin diff` must pass (or warn) with --fail ${pixel}
#      --failpercent ${percent}; and each of FAULTS (frame:fault, a deliberately wrong read of the texture:
#      row-order, transpose, joint-order,
#      texel-offset, clip-offset: web/runtimes/page.js) must fail it.
# Prints "runtimes: SKIPPED: <why>" (CTest's SKIP_REGULAR_EXPRESSION) when something it needs is missing.
#
#   cmake -DDQSKIN=dqskin -DNODE=node -DCHROMIUM=chromium -DSOURCE_DIR=repo -DMODULES=tools/node_modules
#         -DRUNTIME=babylon|playcanvas -DMODEL=m.glb -DCLIP=name -DFPS=30 -DFRAMES=4,15
#         -DFAULTS=4:transpose,15:row-order [-DCOMBINED=1] -DWORK=dir -P runtimes_test.cmake
cmake_minimum_required(VERSION 3.25)

# The three.js player's thresholds, run() and compare_shots().
include("${CMAKE_CURRENT_LIST_DIR}/shot_comparison.cmake")

macro(skip why)
  message("runtimes: SKIPPED: ${why}")
  return()
endmacro()
foreach(need MODEL NODE CHROMIUM)
  if("${${need}}" STREQUAL "" OR "${${need}}" MATCHES "NOTFOUND$" OR NOT EXISTS "${${need}}")
    skip("${need} '${${need}}' is missing (Chromium and Node.js: scripts/install/deps.sh; the shared models: ../shared/testdata)")
  endif()
endforeach()
if(RUNTIME STREQUAL "babylon")
  set(profile mat4)
  set(package "@babylonjs/core/package.json")
elseif(RUNTIME STREQUAL "playcanvas")
  set(profile mat3x4)
  set(package "playcanvas/build/playcanvas.mjs")
else()
  message(FATAL_ERROR "RUNTIME '${RUNTIME}': babylon or playcanvas")
endif()
# The pages read EXR with three.js's EXRLoader (web/exr_texture.js) and frame with web/camera.js.
foreach(file "${package}" three/build/three.module.js)
  if(NOT EXISTS "${MODULES}/${file}")
    skip("${MODULES}/${file} is missing; run scripts/install/node_tools.sh on the build folder's tools/")
  endif()
endforeach()


file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
# COMBINED: every clip in one texture (--combine-clips); the page finds CLIP through the clip table.
if(COMBINED)
  set(clips --anim all --combine-clips)
else()
  set(clips --anim "${CLIP}")
endif()
run("${DQSKIN}" bake "${MODEL}" -o "${WORK}/bake" ${clips} --fps ${FPS} --format bones,vat
    --bones-profile ${profile} --mode lbs -q)
run("${DQSKIN}" render "${MODEL}" -o "${WORK}/render" --anim "${CLIP}" --fps ${FPS} --mode lbs --shade normals
    --size 256x256 -q)

get_filename_component(stem "${MODEL}" NAME_WE)
string(REPLACE "," ";" frames "${FRAMES}")
string(REPLACE "," ";" faults "${FAULTS}")
set(captures "")
set(expect_pass "")
foreach(frame IN LISTS frames)
  set(name ${RUNTIME}_${frame})
  list(APPEND captures "${name}=${RUNTIME}.html?bake=/bake/bake&clip=${CLIP}&frame=${frame}")
  list(APPEND expect_pass "${name}:${frame}")
endforeach()
set(expect_fail "")
foreach(fault IN LISTS faults)
  if(NOT fault MATCHES "^([0-9]+):(row-order|transpose|joint-order|texel-offset|clip-offset)$")
    message(FATAL_ERROR "FAULTS: '${fault}' is not frame:row-order|transpose|joint-order|texel-offset|clip-offset")
  endif()
  set(name fault_${CMAKE_MATCH_2}_${CMAKE_MATCH_1})
  list(APPEND captures "${name}=${RUNTIME}.html?bake=/bake/bake&clip=${CLIP}&frame=${CMAKE_MATCH_1}&fault=${CMAKE_MATCH_2}")
  list(APPEND expect_fail "${name}:${CMAKE_MATCH_1}")
endforeach()
run("${NODE}" "${SOURCE_DIR}/web/runtimes/capture.mjs" --modules "${MODULES}" --bakes "${WORK}" --out "${WORK}/shots"
    --chromium "${CHROMIUM}" --size 256x256 ${captures})

compare_shots("${RUNTIME}")
