# One case of app/tests/image_module.cmake (CASE: missing or mapped).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

if(CASE STREQUAL "missing")
  file(COPY_FILE "${LIBRARY}" "${WORK}/${SONAME}")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${WORK} ${COMMAND} bake -o ${WORK}/vat --format vat -q
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 2)
    message(FATAL_ERROR "VAT bake without the image module: exit status ${status}, expected 2\n${err}")
  endif()
  if(NOT err MATCHES "^dqskin: [^\n]*cannot load dqskin's image module [^\n]*libdqskin_image\\.so[^\n]*: cannot open shared object file[^\n]*\n$")
    message(FATAL_ERROR "VAT bake without the image module: expected one line naming the module, got:\n${err}")
  endif()
  if(EXISTS "${WORK}/vat")
    message(FATAL_ERROR "VAT bake without the image module wrote ${WORK}/vat")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${WORK} ${COMMAND} bake -o ${WORK}/glb --format glb -q
    RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "glb bake without the image module: exit status ${status}, expected 0\n${err}")
  endif()
  return()
endif()

# LD_DEBUG=files: the dynamic loader prints every object it maps ("file=libX.so.N [0];  needed by …" or
# "… dynamically loaded by …") on stderr.
function(mapped out_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_DEBUG=files ${COMMAND} ${ARGN}
    RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "dqskin ${ARGN}: exit status ${status}\n${err}")
  endif()
  set(${out_var} "${err}" PARENT_SCOPE)
endfunction()

foreach(args "--version" "info;${RIG}" "lint;${RIG}")
  mapped(log ${args})
  foreach(library libOpenImageIO libOSMesa)
    if(log MATCHES "file=${library}")
      string(REPLACE ";" " " shown "${args}")
      message(FATAL_ERROR "dqskin ${shown} mapped ${library}; it reads and writes no image")
    endif()
  endforeach()
endforeach()
mapped(log bake ${RIG} -o ${WORK}/vat --format vat -q)
if(NOT log MATCHES "file=libOpenImageIO")
  message(FATAL_ERROR "a VAT bake did not map libOpenImageIO: this test cannot see the library it looks for")
endif()
