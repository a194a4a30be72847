# dqskin_outcome_case(TEST EXPECTED WORKING_DIRECTORY dir LABEL label CTEST_TIMEOUT s ARGS ...
#                     [STDOUT regex] [STDERR regex] [ONE_LINE] [FOLDER dir [UNCHANGED]] [PREPARE args]
#                     [ALTER file] [PRESENT paths] [ABSENT paths] [TIMEOUT s] [MEMORY_LIMIT_MB n] [MAX_RSS_MB n])
# One CTest test TEST: `dqskin ARGS` run in WORKING_DIRECTORY through expect_outcome.cmake, which documents
# the checks. MEMORY_LIMIT_MB caps the address space with prlimit (in sanitizer builds ASan's largest
# allocation instead); MAX_RSS_MB is passed in Release builds only (ASan's shadow memory is resident too).
# Shared by the hardening catalogue (hardening.cmake) and the newer commands' (command_limits.cmake).
find_package(Python3 COMPONENTS Interpreter REQUIRED)
find_program(DQSKIN_PRLIMIT prlimit)
mark_as_advanced(DQSKIN_PRLIMIT)

function(dqskin_outcome_case test expected)
  cmake_parse_arguments(T "ONE_LINE;UNCHANGED"
    "WORKING_DIRECTORY;LABEL;CTEST_TIMEOUT;STDOUT;STDERR;FOLDER;ALTER;TIMEOUT;MEMORY_LIMIT_MB;MAX_RSS_MB"
    "ARGS;PREPARE;PRESENT;ABSENT" ${ARGN})
  string(REPLACE ";" "\\;" args "${T_ARGS}")
  set(options -DCOMMAND=$<TARGET_FILE:dqskin_cli> "-DARGS=${args}" -DEXPECTED=${expected}
      -DWORKING_DIRECTORY=${T_WORKING_DIRECTORY})
  foreach(stream STDOUT STDERR)
    if(DEFINED T_${stream})
      list(APPEND options "-D${stream}_REGEX=${T_${stream}}")
    endif()
  endforeach()
  foreach(flag ONE_LINE UNCHANGED)
    if(T_${flag})
      list(APPEND options -D${flag}=ON)
    endif()
  endforeach()
  foreach(value FOLDER ALTER TIMEOUT MEMORY_LIMIT_MB)
    if(DEFINED T_${value})
      list(APPEND options "-D${value}=${T_${value}}")
    endif()
  endforeach()
  if(DEFINED T_MEMORY_LIMIT_MB AND DQSKIN_PRLIMIT AND NOT DQSKIN_SANITIZE)
    list(APPEND options -DPRLIMIT=${DQSKIN_PRLIMIT})
  endif()
  if(DEFINED T_MAX_RSS_MB AND NOT DQSKIN_SANITIZE)
    list(APPEND options -DMAX_RSS_MB=${T_MAX_RSS_MB} -DPYTHON=${Python3_EXECUTABLE})
  endif()
  foreach(list PREPARE PRESENT ABSENT)
    if(DEFINED T_${list})
      string(REPLACE ";" "\\;" value "${T_${list}}")
      list(APPEND options "-D${list}=${value}")
    endif()
  endforeach()
  add_test(NAME ${test} COMMAND ${CMAKE_COMMAND} ${options} -P ${PROJECT_SOURCE_DIR}/app/tests/expect_outcome.cmake)
  set_tests_properties(${test} PROPERTIES TIMEOUT ${T_CTEST_TIMEOUT} LABELS ${T_LABEL}
    ENVIRONMENT "${bake_test_environment}")
endfunction()
