# Checks that DIR holds exactly the three frames `dqskin render bending_arm.gltf --frames 0:2` writes.
#   cmake -DDIR=out -P render_files.cmake
file(GLOB_RECURSE found RELATIVE ${DIR} ${DIR}/*)
list(SORT found)
set(expected bending_arm/bend/frame_0000.png bending_arm/bend/frame_0001.png bending_arm/bend/frame_0002.png)
if(NOT found STREQUAL expected)
  message(FATAL_ERROR "${DIR} holds '${found}', expected '${expected}'")
endif()
