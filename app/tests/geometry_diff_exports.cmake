# `dqskin diff` on the shapes real exports have (scripts/testdata/make_diff_models.py writes the characters into the
# build tree at configure time): the diff must pass a file that deforms the same and say how it compared.
#   crumpled  a character whose nodes alone crumple the mesh (its pose is only in the clip): against its
#             `gltfpack -noq` output and against itself in another vertex order, exit 0 at --relative
#             --fail 1e-3, the report naming the clip pose the correspondence was made at; one key turned 5°
#             still fails and is named.
#   unused    vertices that no triangle uses, against the same character without them (what gltfpack makes
#             of it, and gltfpack's own output): exit 0, and the note counts them.
#   flat      flat shading, with split normals or without NORMAL, against its gltfpack output: a normal
#             figure under 1°, faces compared (the JSON's correspondence.normals).
# The shared driver is geometry_diff.cmake's geometry_diff_test (geometry_diff_case.cmake).
set(_models ${CMAKE_CURRENT_BINARY_DIR}/geometry_diff_models)
set(_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_diff_models.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${_generator} all ${_models}
                RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_diff_models.py failed (${_status}):\n${_output}")
endif()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_generator} ${PROJECT_SOURCE_DIR}/scripts/testdata/make_rigs.py
                                                               ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py)

# Within 1 mm on a character 4.6 m across: --fail and --warn 1e-3 of the diagonal (gltfpack's 30 Hz
# resampling of the clip moves the surface by up to 410 um).
set(_strict ARGS --relative --fail 1e-3 --warn 1e-3)
set(_pack TOOL gltfpack TOOL_ARGS -i <A> -o <B> -noq)

# -- crumpled rest pose -------------------------------------------------------------------------------------
geometry_diff_test(crumpled_gltfpack 0 A ${_models}/crumpled.glb ${_pack} ${_strict}
  STDOUT "correspondence: closest surface points at clip wave, t = 0 s")
geometry_diff_test(crumpled_reorder 0 A ${_models}/crumpled.glb MAKE permute --seed 3 ${_strict}
  STDOUT "correspondence: closest surface points at clip wave, t = 0 s")
# joint3 is the leaf that carries the tube's top: the worst vertex is its own.
geometry_diff_test(crumpled_defect 2 A ${_models}/crumpled.glb MAKE rotate-key --joint joint3
  ARGS --relative --fail 1e-4 FAIL_LINE)

# -- vertices on no triangle ----------------------------------------------------------------------------------
geometry_diff_test(unused_vertices 0 A ${_models}/unused.glb SOURCE ${_models}/unused_without.glb MAKE copy
  ${_strict} STDOUT "528 of A's 1056 vertices and 0 of B's 528 are on no triangle")
geometry_diff_test(unused_vertices_gltfpack 0 A ${_models}/unused.glb ${_pack} ${_strict}
  STDOUT "528 of A's 1056 vertices and 0 of B's 528 are on no triangle")

# -- flat shading -------------------------------------------------------------------------------------------
foreach(_model flat flat_no_normals)
  geometry_diff_test(${_model}_gltfpack 0 A ${_models}/${_model}.glb ${_pack} ${_strict} --json
    MAX_NORMAL_DEGREES 1 FACE_NORMALS)
endforeach()
