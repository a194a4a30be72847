# The player's crossfade (blend=, docs/DESIGN.md §3.10) in headless Chromium, on the twisted cylinder, whose
# reference is a frame of its own clip: the child turns about its own axis at constant speed, so the
# reference crossfade of frames 1 and 3 of `twist` at 4 fps (45° and 135°) by w = 0.5 is frame 2 (90°).
#   1. bakes the clip (--combine-clips: the player finds it through the input's clip table) as an OpenVAT
#      and a dq bone texture, and renders its frames with `dqskin render --shade normals --size 256x256`;
#   2. draws, through each path, frame 1 crossfaded with frame 3 at w = 0, 0.5 and 1;
#   3. compares each shot with dqskin's render of the frame it should be, with player_test.cmake's
#      thresholds: w = 0 must match frame 1 and w = 1 frame 3 on both paths; at w = 0.5 the bone texture's
#      per-joint DQ blend must match frame 2, and the VAT's vertex lerp, which cuts the twisted half's
#      circles along their chords, must not.
# And two clips of one texture: testdata/walk_run_legs.gltf baked with --combine-clips (run's rows after
# walk's), walk's frame 4 crossfaded with run's frame 5 must show walk's frame at w = 0 and run's at w = 1
# on both paths, so the second clip's frame is found through the clip table.
# Prints "player: SKIPPED: <why>" when something it needs is missing.
#
#   cmake -DDQSKIN=dqskin -DNODE=node -DCHROMIUM=chromium -DSOURCE_DIR=repo -DTHREE_DIR=node_modules/three
#         -DWORK=dir -P player_blend_test.cmake
cmake_minimum_required(VERSION 3.25)

include("${CMAKE_CURRENT_LIST_DIR}/shot_comparison.cmake")  # pixel, percent, run()

macro(skip why)
  message("player: SKIPPED: ${why}")
  return()
endmacro()
foreach(need NODE CHROMIUM)
  if("${${need}}" STREQUAL "" OR "${${need}}" MATCHES "NOTFOUND$" OR NOT EXISTS "${${need}}")
    skip("${need} '${${need}}' is missing (Chromium and Node.js: scripts/install/deps.sh)")
  endif()
endforeach()
if(NOT EXISTS "${THREE_DIR}/build/three.module.js")
  skip("three.js is missing at ${THREE_DIR}; run scripts/install/node_tools.sh on the build folder's tools/")
endif()


set(model "${SOURCE_DIR}/testdata/twisted_cylinder.gltf")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
run("${DQSKIN}" bake "${model}" -o "${WORK}/bake" --anim all --combine-clips --fps 4 --format vat,bones
    --vat-profile openvat -q)
run("${DQSKIN}" render "${model}" -o "${WORK}/render" --anim twist --fps 4 --shade normals --size 256x256 -q)
set(legs "${SOURCE_DIR}/testdata/walk_run_legs.gltf")
run("${DQSKIN}" bake "${legs}" -o "${WORK}/legs" --anim all --combine-clips --fps 16 --format vat,bones
    --vat-profile openvat -q)
run("${DQSKIN}" render "${legs}" -o "${WORK}/render" --anim all --fps 16 --shade normals --size 256x256 -q)
run(env "THREE_DIR=${THREE_DIR}" bash "${SOURCE_DIR}/scripts/install/player.sh" "${WORK}")

# The box dqskin render frames run's frames on: run's bounds in the clip table (the player frames walk's).
file(READ "${WORK}/legs/walk_run_legs/vat.json" side)
set(run_box "")
foreach(i 0 1)
  string(JSON name GET "${side}" clips ${i} name)
  if(name STREQUAL "run")
    foreach(end min max)
      foreach(axis 0 1 2)
        string(JSON value GET "${side}" clips ${i} bounds ${end} ${axis})
        list(APPEND run_box ${value})
      endforeach()
    endforeach()
  endif()
endforeach()
string(REPLACE ";" "," run_box "${run_box}")

# name:path:weight:the render's frame it must show:pass|fail
set(twist twisted_cylinder/twist/frame_000)
set(cases vat_w0:vat:0:${twist}1:pass bones_w0:bones:0:${twist}1:pass
          vat_w1:vat:1:${twist}3:pass bones_w1:bones:1:${twist}3:pass
          bones_w50:bones:0.5:${twist}2:pass vat_w50:vat:0.5:${twist}2:fail
          legs_vat_w0:vat:0:walk_run_legs/walk/frame_0004:pass legs_bones_w0:bones:0:walk_run_legs/walk/frame_0004:pass
          legs_vat_w1:vat:1:walk_run_legs/run/frame_0005:pass legs_bones_w1:bones:1:walk_run_legs/run/frame_0005:pass)
set(captures "")
foreach(case IN LISTS cases)
  string(REPLACE ":" ";" parts "${case}")
  list(GET parts 0 name)
  list(GET parts 1 path)
  list(GET parts 2 weight)
  if(name MATCHES "^legs_")
    set(box "")
    if(weight STREQUAL "1")
      set(box "&box=${run_box}")
    endif()
    list(APPEND captures "${name}=bake=../legs&clip=walk&path=${path}&frame=4&blend=run:5,${weight}${box}")
  else()
    list(APPEND captures "${name}=bake=../bake&clip=twist&path=${path}&frame=1&blend=twist:3,${weight}")
  endif()
endforeach()
run("${NODE}" "${SOURCE_DIR}/web/capture.mjs" --root "${WORK}" --out "${WORK}/shots" --chromium "${CHROMIUM}"
    --size 256x256 ${captures})

set(report "")
set(problems "")
foreach(case IN LISTS cases)
  string(REPLACE ":" ";" parts "${case}")
  list(GET parts 0 name)
  list(GET parts 3 frame)
  list(GET parts 4 expect)
  execute_process(COMMAND "${DQSKIN}" diff "${WORK}/render/${frame}.png"
                          "${WORK}/shots/${name}.png" --fail ${pixel} --failpercent ${percent}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  string(REGEX REPLACE "\n.*" "" line "${out}")
  string(REGEX REPLACE "^([A-Z]+) +[^ ]+ +" "\\1 " line "${line}")
  string(APPEND report "${name} (against ${frame}, must ${expect}): ${line}\n")
  if(expect STREQUAL "fail" AND NOT status EQUAL 2)
    string(APPEND problems "${name}: the VAT lerp matched the blended pose (exit ${status}); the test shows nothing\n")
  elseif(expect STREQUAL "pass" AND NOT (status EQUAL 0 OR status EQUAL 1))
    string(APPEND problems
           "${name}: the player's crossfade differs from dqskin render's ${frame} (exit ${status}) ${err}\n")
  endif()
endforeach()
file(WRITE "${WORK}/figures.txt" "${report}")
message("${report}")
if(problems)
  message(FATAL_ERROR "${problems}")
endif()
