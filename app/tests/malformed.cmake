# The catalogue of malformed inputs (scripts/testdata/make_malformed.py): one CTest test per broken file, each
# checking that `dqskin info FILE` exits with status 2 and prints exactly one line,
# "dqskin: FILE: MESSAGE", whose MESSAGE names the problem (the regex of cases.txt). The valid base files
# must load. Every test has a timeout, so an input that makes the loader hang fails instead of stalling.
# The files are generated at configure time into the build tree; nothing binary is committed.
find_package(Python3 COMPONENTS Interpreter REQUIRED)

set(DQSKIN_MALFORMED_DIR ${CMAKE_CURRENT_BINARY_DIR}/malformed)
set(_generator ${PROJECT_SOURCE_DIR}/scripts/testdata/make_malformed.py)
execute_process(
  COMMAND ${Python3_EXECUTABLE} ${_generator} ${DQSKIN_MALFORMED_DIR}
  RESULT_VARIABLE _status OUTPUT_VARIABLE _output ERROR_VARIABLE _output)
if(NOT _status STREQUAL "0")
  message(FATAL_ERROR "scripts/testdata/make_malformed.py failed (${_status}):\n${_output}")
endif()
# Re-run configure (and so the generator) when the generator changes.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_generator} ${PROJECT_SOURCE_DIR}/scripts/testdata/gltf_builder.py)

set(_checker ${CMAKE_CURRENT_LIST_DIR}/expect_error.cmake)
# Every case runs in malformed/cwd (one case checks that a buffer there is not found) under a 4 GiB
# memory cap (one case makes the loader try to allocate 12 GiB).
set(_options -DWORKING_DIRECTORY=${DQSKIN_MALFORMED_DIR}/cwd -DMEMORY_LIMIT_MB=4096)
find_program(DQSKIN_PRLIMIT prlimit)
mark_as_advanced(DQSKIN_PRLIMIT)
if(DQSKIN_PRLIMIT AND NOT DQSKIN_SANITIZE)
  list(APPEND _options -DPRLIMIT=${DQSKIN_PRLIMIT})
endif()

# Timeouts: 20 s for one `info` (a quadratic pass over valid_deep_hierarchy.gltf took 45 s in a Release
# build), 60 s for the three commands of an undeformable case; DQSKIN_TIMEOUT_SCALE times that in the
# sanitizer build (CMakeLists.txt).
math(EXPR _info_timeout "20 * ${DQSKIN_TIMEOUT_SCALE}")
math(EXPR _undeformable_timeout "60 * ${DQSKIN_TIMEOUT_SCALE}")

file(STRINGS ${DQSKIN_MALFORMED_DIR}/valid.txt _valid_files)
foreach(_file IN LISTS _valid_files)
  add_test(NAME malformed.${_file}
    COMMAND ${CMAKE_COMMAND} -DCOMMAND=$<TARGET_FILE:dqskin_cli> -DFILE=${DQSKIN_MALFORMED_DIR}/${_file}
            ${_options} -P ${_checker})
  set_tests_properties(malformed.${_file} PROPERTIES TIMEOUT ${_info_timeout} LABELS malformed)
endforeach()

# cases.txt: "<file name>\t<regex>" per line, files that must fail; warnings.txt the same for files that
# must load with a warning; undeformable.txt for files that parse as glTF but cannot be deformed: info and
# lint describe them, bake refuses them in one line (expect_undeformable.cmake). The regexes contain no ';'
# (make_malformed.py asserts it).
foreach(_list cases warnings undeformable)
  file(STRINGS ${DQSKIN_MALFORMED_DIR}/${_list}.txt _cases)
  foreach(_line IN LISTS _cases)
    string(FIND "${_line}" "\t" _tab)
    if(_tab LESS 1)
      message(FATAL_ERROR "malformed/${_list}.txt: bad line '${_line}'")
    endif()
    string(SUBSTRING "${_line}" 0 ${_tab} _file)
    math(EXPR _start "${_tab} + 1")
    string(SUBSTRING "${_line}" ${_start} -1 _regex)
    string(REGEX REPLACE "\\.(gltf|glb)$" "" _case "${_file}")
    if(_list STREQUAL "undeformable")
      # Three commands, bake among them: more time than one info.
      set(_run "-DREGEX=${_regex}" -DSCRATCH=${DQSKIN_MALFORMED_DIR}/undeformable_out/${_case}
               -DWORKING_DIRECTORY=${DQSKIN_MALFORMED_DIR}/cwd -P ${CMAKE_CURRENT_LIST_DIR}/expect_undeformable.cmake)
      set(_timeout ${_undeformable_timeout})
    else()
      set(_variable REGEX)
      if(_list STREQUAL "warnings")
        set(_variable WARNING)
      endif()
      set(_run "-D${_variable}=${_regex}" ${_options} -P ${_checker})
      set(_timeout ${_info_timeout})
    endif()
    add_test(NAME malformed.${_case}
      COMMAND ${CMAKE_COMMAND} -DCOMMAND=$<TARGET_FILE:dqskin_cli> -DFILE=${DQSKIN_MALFORMED_DIR}/${_file} ${_run})
    set_tests_properties(malformed.${_case} PROPERTIES TIMEOUT ${_timeout} LABELS malformed)
  endforeach()
endforeach()
