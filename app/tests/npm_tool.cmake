# Included by the test drivers that run an npm optimizer (geometry_diff_case.cmake, optimized_input_case.cmake):
# npm_tool_or_skip(TOOL) sets `program` to TOOLS/TOOL, or calls the includer's skip(why) (a macro, so that
# its return() ends the script) when the tool is missing or cannot start. gltf-transform 4 needs Node.js 20;
# both print their version and exit 0 (gltfpack: -v alone).
macro(npm_tool_or_skip tool)
  set(program "${TOOLS}/${tool}")
  if(NOT EXISTS "${program}")
    skip("${program} is missing; run scripts/install/node_tools.sh on the build folder's tools/")
  endif()
  set(_version_flag --version)
  if("${tool}" STREQUAL "gltfpack")
    set(_version_flag -v)
  endif()
  execute_process(COMMAND "${program}" ${_version_flag} RESULT_VARIABLE _status OUTPUT_QUIET ERROR_VARIABLE _err
                  TIMEOUT 60)
  if(NOT _status STREQUAL "0")
    string(REGEX REPLACE "\n.*" "" _err "${_err}")
    skip("${tool} does not run here (exit status ${_status}: ${_err})")
  endif()
endmacro()
