# `dqskin lint --junit` over the whole bad-skin catalogue: the report is written, is well-formed XML (checked
# with Python's XML parser where python3 is found, else by its envelope), and has one testcase per file and
# check and a failure per file with an error.
#
#   cmake -DDQSKIN=dqskin -DDIR=testdata/bad_skins -DOUT=junit.xml -P lint_junit.cmake
cmake_minimum_required(VERSION 3.25)
file(GLOB files "${DIR}/*.gltf")
list(SORT files)
file(REMOVE "${OUT}")
execute_process(COMMAND "${DQSKIN}" lint ${files} --junit "${OUT}" RESULT_VARIABLE status OUTPUT_QUIET
                ERROR_VARIABLE err TIMEOUT 120)
if(NOT status STREQUAL "2" OR NOT EXISTS "${OUT}")
  message(FATAL_ERROR "dqskin lint --junit: exit status ${status} (expected 2), ${OUT} written: ${err}")
endif()
file(READ "${OUT}" xml)
if(NOT xml MATCHES "^<\\?xml version=\"1.0\" encoding=\"UTF-8\"\\?>\n<testsuites name=\"dqskin lint\" tests=\"([0-9]+)\" failures=\"([0-9]+)\"")
  message(FATAL_ERROR "not a JUnit report:\n${xml}")
endif()
set(tests ${CMAKE_MATCH_1})
set(failures ${CMAKE_MATCH_2})
string(REGEX MATCHALL "<testcase " cases "${xml}")
list(LENGTH cases n)
list(LENGTH files f)
# The checks as `lint --help` lists them ("  ID  SEVERITY ..." under "Checks"), so that a new check needs no
# edit here.
execute_process(COMMAND "${DQSKIN}" lint --help OUTPUT_VARIABLE help TIMEOUT 60)
string(REGEX MATCHALL "\n  [a-z][a-z0-9-]* *(info|warning|error) " check_lines "${help}")
list(LENGTH check_lines checks)
math(EXPR expected "${f} * ${checks}")
if(checks LESS 17 OR NOT n EQUAL tests OR NOT n EQUAL expected)
  message(FATAL_ERROR "${n} testcases for ${f} files (expected ${f} × ${checks} checks, tests=\"${tests}\")")
endif()
string(REGEX MATCHALL "<failure " failed "${xml}")
list(LENGTH failed nf)
# The files whose problem is an error (app/tests/lint.cmake: exit status 2).
if(NOT nf EQUAL failures OR NOT nf EQUAL 10)
  message(FATAL_ERROR "${nf} failures, failures=\"${failures}\", expected 10")
endif()
find_program(PYTHON python3)
if(PYTHON)
  execute_process(COMMAND "${PYTHON}" -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" "${OUT}"
                  RESULT_VARIABLE parsed ERROR_VARIABLE why)
  if(NOT parsed STREQUAL "0")
    message(FATAL_ERROR "${OUT} is not well-formed XML: ${why}")
  endif()
endif()
