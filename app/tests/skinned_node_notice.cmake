# The notice that a skinned mesh node's transform is ignored (glTF 2.0 §3.7.3.1): one line per file, not one
# per node, from info; from bake only with --verbose. The file: three skinned mesh nodes under a moved node
# (scripts/testdata/make_lint_cases.py three_skinned_nodes, generated at configure time into the build tree).
# DQSKIN_LINT_CASES_DIR: written by lint_cases.cmake, included before this file.
set(notice_scratch ${CMAKE_CURRENT_BINARY_DIR}/skinned_node_notice)

# Lines that mention the transform: the notice ("have a transform") or the warning it was ("has a transform").
set(_notice "have a transform|has a transform")
set(_three ${DQSKIN_LINT_CASES_DIR}/three_skinned_nodes.gltf)
function(dqskin_notice_test name count)
  string(REPLACE ";" "\\;" args "${ARGN}")
  set(script_args "-DARGS=${args}")  # expanded unquoted below: one argument holding the ;-list
  add_test(NAME cli.skinned_node_notice_${name} COMMAND ${CMAKE_COMMAND} -DCOMMAND=$<TARGET_FILE:dqskin_cli>
    ${script_args} -DEXPECTED=0 "-DREGEX=${_notice}" -DCOUNT=${count}
    -P ${CMAKE_CURRENT_LIST_DIR}/count_lines.cmake)
  set_tests_properties(cli.skinned_node_notice_${name} PROPERTIES LABELS notice)
endfunction()
dqskin_notice_test(info_once 1 info ${_three})
dqskin_notice_test(bake_silent 0 bake ${_three} -o ${notice_scratch}/silent --format ply --backend cpu
  --frames 0:0 -f)
dqskin_notice_test(bake_verbose_once 1 bake ${_three} -o ${notice_scratch}/verbose --format ply --backend cpu
  --frames 0:0 -f -v)
