# Checks that DIR holds exactly the three frames `dqskin render bending_arm.gltf --frames 0:2` writes and
# the render's manifest, which lists them with their sizes and SHA-256.
#   cmake -DDIR=out -P render_files.cmake
file(GLOB_RECURSE found RELATIVE ${DIR} ${DIR}/*)
list(SORT found)
set(expected bending_arm/bend/frame_0000.png bending_arm/bend/frame_0001.png bending_arm/bend/frame_0002.png
  render-manifest.json)
if(NOT found STREQUAL expected)
  message(FATAL_ERROR "${DIR} holds '${found}', expected '${expected}'")
endif()
file(READ ${DIR}/render-manifest.json manifest)
foreach(i 0 1 2)
  string(JSON path GET "${manifest}" outputs ${i} path)
  string(JSON sha GET "${manifest}" outputs ${i} sha256)
  file(SHA256 ${DIR}/${path} actual)
  list(GET expected ${i} want)
  if(NOT path STREQUAL want OR NOT sha STREQUAL actual)
    message(FATAL_ERROR "render-manifest.json lists '${path}' with ${sha}; expected ${want} with ${actual}")
  endif()
endforeach()
