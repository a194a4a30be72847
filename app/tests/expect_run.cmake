# Runs COMMAND with ARGS (a ;-list) and checks its exit status (EXPECTED) and, when given, that stdout
# matches STDOUT_REGEX and stderr matches STDERR_REGEX (CMake regex syntax). CTest alone cannot check a
# status and an output together.
#   cmake -DCOMMAND=dqskin "-DARGS=bake;x.gltf" -DEXPECTED=2 [-DSTDERR_REGEX=...] [-DSTDOUT_REGEX=...]
#         -P expect_run.cmake
execute_process(COMMAND ${COMMAND} ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
set(problems "")
if(NOT status STREQUAL EXPECTED)
  string(APPEND problems "exit status ${status}, expected ${EXPECTED}\n")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  string(APPEND problems "stdout does not match ${STDOUT_REGEX}\n")
endif()
if(DEFINED STDERR_REGEX AND NOT err MATCHES "${STDERR_REGEX}")
  string(APPEND problems "stderr does not match ${STDERR_REGEX}\n")
endif()
if(problems)
  message(FATAL_ERROR "${COMMAND} ${ARGS}:\n${problems}stdout:\n${out}\nstderr:\n${err}")
endif()
