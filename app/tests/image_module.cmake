# The image module (lib/base/image_module.hpp): libdqskin_image.so is opened only when an image is read or
# written, and an installation without it fails that command in one line.
#
#   cli.image_module_missing   libdqskin.so copied alone into a folder that LD_LIBRARY_PATH puts first (it
#                              wins over the program's run path): a VAT bake exits 2 with one line naming
#                              the module and writes nothing; a glb bake, which reads and writes no image,
#                              still works.
#   cli.no_image_library_mapped  `dqskin --version`, `info` and `lint` on a bundled rig run with the dynamic
#                              loader's list of what it maps: neither libOpenImageIO nor libOSMesa is there,
#                              and the VAT bake does map OpenImageIO (so the check can fail).
add_test(NAME cli.image_module_missing COMMAND ${CMAKE_COMMAND} -DCASE=missing -DCOMMAND=$<TARGET_FILE:dqskin_cli>
  -DLIBRARY=$<TARGET_FILE:dqskin> -DSONAME=$<TARGET_SONAME_FILE_NAME:dqskin>
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/image_module_missing -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/image_module_case.cmake)
add_test(NAME cli.no_image_library_mapped COMMAND ${CMAKE_COMMAND} -DCASE=mapped -DCOMMAND=$<TARGET_FILE:dqskin_cli>
  -DRIG=${PROJECT_SOURCE_DIR}/testdata/twisted_cylinder.gltf
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/image_module_mapped -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/image_module_case.cmake)
