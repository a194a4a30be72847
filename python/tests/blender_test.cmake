# The module inside Blender (CTest python.blender): runs test_in_blender.py with Blender's own Python and
# expects its OK. Prints "blender_test: SKIPPED: <why>" (CTest's SKIP_REGULAR_EXPRESSION) without Blender.
#
#   cmake -DBLENDER=blender -DMODULE_DIR=build/release/python -DSOURCE=. -P blender_test.cmake
cmake_minimum_required(VERSION 3.25)

if("${BLENDER}" STREQUAL "" OR "${BLENDER}" MATCHES "NOTFOUND$" OR NOT EXISTS "${BLENDER}")
  message("blender_test: SKIPPED: Blender is missing (Debian's blender: scripts/install/deps.sh)")
  return()
endif()
execute_process(COMMAND "${BLENDER}" -b --factory-startup --python-exit-code 1
                        --python "${SOURCE}/python/tests/test_in_blender.py" -- "${MODULE_DIR}" "${SOURCE}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
string(REPLACE ";" "," out "${out}")  # not a CMake list separator
string(REGEX MATCHALL "test_in_blender: [^\n]*" lines "${out}")
list(JOIN lines "\n" lines)
message("${lines}")
if(NOT status EQUAL 0 OR NOT out MATCHES "test_in_blender: OK")
  message(FATAL_ERROR "Blender ran test_in_blender.py with exit status ${status}:\n${out}\n${err}")
endif()
