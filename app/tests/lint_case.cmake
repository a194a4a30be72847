# One case of `dqskin lint` on the command line (app/tests/lint.cmake), at test time: lints FILE with --json
# and checks the exit status and the check ids found; with FIX, writes the fixed copy, checks that the
# fixed file's report (the second file of the JSON) no longer has the check when FIXABLE, and its exit
# status; with VALIDATE, runs the Khronos glTF-Validator on the fixed file (0 errors), or says that it was
# skipped and why when Node.js or the validator is missing.
#
#   cmake -DDQSKIN=dqskin -DFILE=in.gltf -DEXPECTED=status "-DCHECKS=id;id" (or id,id) [-DWORK=folder -DFIX=ON
#         -DFIXABLE=ON|OFF -DFIXED_EXPECTED=status [-DVALIDATE=ON -DNODE=node -DVALIDATOR=dir -DSCRIPT=validate_gltf.mjs]]
#         -P lint_case.cmake
cmake_minimum_required(VERSION 3.25)

# The check ids of file `index` of a lint JSON report, as a ;-list.
function(checks_of json index out)
  set(ids "")
  string(JSON n ERROR_VARIABLE none LENGTH "${json}" files ${index} findings)
  if(n GREATER 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE ${last})
      string(JSON id GET "${json}" files ${index} findings ${i} check)
      list(APPEND ids ${id})
    endforeach()
  endif()
  set(${out} "${ids}" PARENT_SCOPE)
endfunction()

string(REPLACE "," ";" CHECKS "${CHECKS}")  # ids may also come comma-separated (no escaping through add_test)
execute_process(COMMAND "${DQSKIN}" lint --json "${FILE}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                ERROR_VARIABLE err TIMEOUT 120)
if(NOT status STREQUAL "${EXPECTED}")
  message(FATAL_ERROR "dqskin lint ${FILE}: exit status ${status}, expected ${EXPECTED}\n${out}${err}")
endif()
checks_of("${out}" 0 found)
if(NOT found STREQUAL "${CHECKS}")
  message(FATAL_ERROR "dqskin lint ${FILE}: found '${found}', expected '${CHECKS}'\n${out}")
endif()
if(NOT FIX)
  return()
endif()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(fixed "${WORK}/fixed.glb")
execute_process(COMMAND "${DQSKIN}" lint --json --fix "${FILE}" -o "${fixed}" RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT status STREQUAL "${FIXED_EXPECTED}")
  message(FATAL_ERROR "dqskin lint --fix ${FILE}: exit status ${status}, expected ${FIXED_EXPECTED}\n${out}${err}")
endif()
if(NOT EXISTS "${fixed}")
  message(FATAL_ERROR "dqskin lint --fix ${FILE}: ${fixed} was not written")
endif()
checks_of("${out}" 1 after)
foreach(check IN LISTS CHECKS)
  list(FIND after ${check} at)
  if(FIXABLE AND at GREATER -1)
    message(FATAL_ERROR "dqskin lint --fix ${FILE}: ${check} is still there\n${out}")
  elseif(NOT FIXABLE AND at EQUAL -1)
    message(FATAL_ERROR "dqskin lint --fix ${FILE}: ${check} cannot be fixed, but is gone\n${out}")
  endif()
endforeach()

if(VALIDATE)
  if(NOT NODE OR NOT EXISTS "${VALIDATOR}/package.json")
    message("lint: validation skipped: Node.js or the gltf-validator (scripts/install/node_tools.sh) is missing")
    return()
  endif()
  execute_process(COMMAND "${NODE}" "${SCRIPT}" --validator "${VALIDATOR}" "${fixed}" RESULT_VARIABLE status
                  OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "the glTF-Validator finds errors in the fixed ${FILE}:\n${out}${err}")
  endif()
endif()
