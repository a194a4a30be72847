# One case of the geometric diff (app/tests/geometry_diff.cmake), at test time: makes B from SOURCE (with
# scripts/testdata/make_diff_cases.py or an npm optimizer), runs `dqskin diff A B ARGS` through expect_outcome.cmake
# and checks the report.
#
#   cmake -DDQSKIN=dqskin -DPYTHON=python3 -DSCRIPT=scripts/testdata/make_diff_cases.py -DWORK=folder
#         -DA=a.glb [-DSOURCE=file B is made from, default A] [-DB_NAME=b.glb]
#         [-DMAKE=make_diff_cases.py command and its options | -DTOOL=gltfpack|gltf-transform -DTOOLS=node_modules/.bin
#          "-DTOOL_ARGS=arguments, with <A> and <B> for the files"]
#         "-DARGS=diff options" -DEXPECTED=status [-DSTDOUT_REGEX=...] [-DSTDERR_REGEX=...] [-DONE_LINE=ON]
#         [-DFAIL_LINE=ON] [-DEXACT_JSON=ON] [-DCONTROL=ON] [-DMAX_NORMAL_DEGREES=d] [-DFACE_NORMALS=ON]
#         [-DTIMEOUT=s] -P geometry_diff_case.cmake
#
# FAIL_LINE: one line of stdout holds "clip <name>", "t = <seconds> s" and "at <joint>"; after `MAKE
# rotate-key` they must be the clip, joint and key time (within 1e-3 s) that the script printed.
# EXACT_JSON: stdout is one JSON document with status PASS and clips whose max_error is exactly 0.
# MAX_NORMAL_DEGREES: stdout is the JSON report and every clip's max_normal_degrees is at most d.
# FACE_NORMALS: stdout is the JSON report and correspondence.normals counts faces compared on both sides.
# Prints "geometry_diff: SKIPPED: <why>" (CTest's SKIP_REGULAR_EXPRESSION) when SOURCE or the tool is missing.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED TIMEOUT)
  set(TIMEOUT 300)
endif()

# Leaves the script without failing (a macro: its return() ends the file); CTest sees the line.
macro(skip why)
  message("geometry_diff: SKIPPED: ${why}")
  return()
endmacro()
include(${CMAKE_CURRENT_LIST_DIR}/npm_tool.cmake)

if(NOT DEFINED SOURCE)
  set(SOURCE "${A}")
endif()
foreach(f "${A}" "${SOURCE}")
  if(NOT EXISTS "${f}")
    skip("${f} is missing (the shared models are in ../shared/testdata beside the repository)")
  endif()
endforeach()
if(NOT DEFINED B_NAME)
  set(B_NAME b.glb)
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(B "${WORK}/${B_NAME}")

# -- make B ---------------------------------------------------------------------------------------------------
set(made "")
if(DEFINED TOOL)
  npm_tool_or_skip(${TOOL})
  list(TRANSFORM TOOL_ARGS REPLACE "^<A>$" "${SOURCE}")
  list(TRANSFORM TOOL_ARGS REPLACE "^<B>$" "${B}")
  execute_process(COMMAND "${program}" ${TOOL_ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE made ERROR_VARIABLE err
                  TIMEOUT 300)
  if(NOT status STREQUAL "0" OR NOT EXISTS "${B}")
    message(FATAL_ERROR "${TOOL} ${TOOL_ARGS} failed (${status}):\n${made}${err}")
  endif()
else()
  list(POP_FRONT MAKE make_command)
  execute_process(COMMAND "${PYTHON}" "${SCRIPT}" ${make_command} "${SOURCE}" "${B}" ${MAKE}
                  RESULT_VARIABLE status OUTPUT_VARIABLE made ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status STREQUAL "0")
    message(FATAL_ERROR "make_diff_cases.py ${make_command} ${MAKE} failed (${status}):\n${made}${err}")
  endif()
endif()

# -- run the diff ---------------------------------------------------------------------------------------------
# CONTROL: A and B each compare equal to themselves first, so that an expected failure is not a file the
# diff cannot read at all.
if(CONTROL)
  foreach(f "${A}" "${B}")
    execute_process(COMMAND "${DQSKIN}" diff "${f}" "${f}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                    ERROR_VARIABLE err TIMEOUT ${TIMEOUT})
    if(NOT status STREQUAL "0")
      message(FATAL_ERROR "dqskin diff ${f} ${f}: exit status '${status}', expected 0\n${out}${err}")
    endif()
  endforeach()
endif()
set(COMMAND "${DQSKIN}")
set(ARGS diff "${A}" "${B}" ${ARGS})
include(${CMAKE_CURRENT_LIST_DIR}/expect_outcome.cmake)  # fails on a wrong status or stream; sets out, err

function(report problem)
  message(FATAL_ERROR "dqskin ${ARGS}:\n${problem}\n${made}stdout:\n${out}\nstderr:\n${err}")
endfunction()

# "12.5" → 12500000: seconds as integer microseconds (CMake has no floating-point arithmetic). Other
# spellings (an exponent) give "".
function(microseconds text result)
  if(text MATCHES "^([0-9]+)(\\.([0-9]*))?$")
    set(whole ${CMAKE_MATCH_1})
    string(SUBSTRING "${CMAKE_MATCH_3}000000" 0 6 fraction)
    string(REGEX MATCH "^0*([0-9]+)$" fraction "${fraction}")  # without leading zeros, keeping one
    math(EXPR value "${whole} * 1000000 + ${CMAKE_MATCH_1}")
    set(${result} ${value} PARENT_SCOPE)
  else()
    set(${result} "" PARENT_SCOPE)
  endif()
endfunction()

function(regex_escape text result)
  string(REGEX REPLACE "([][.*+?^$()|\\\\])" "\\\\\\1" text "${text}")
  set(${result} "${text}" PARENT_SCOPE)
endfunction()

if(FAIL_LINE)
  set(clip_regex "[^ ]+")
  set(joint_regex "[^ ]+")
  set(expected_time "")
  if(make_command STREQUAL "rotate-key")
    if(NOT made MATCHES "^clip (.+) joint (.+) key [0-9]+ t = ([^ ]+) s\n$")
      message(FATAL_ERROR "make_diff_cases.py rotate-key printed something else:\n${made}")
    endif()
    regex_escape("${CMAKE_MATCH_1}" clip_regex)
    regex_escape("${CMAKE_MATCH_2}" joint_regex)
    microseconds("${CMAKE_MATCH_3}" expected_time)
  endif()
  string(REPLACE ";" "," lines "${out}")  # one list item per line
  string(REPLACE "\n" ";" lines "${lines}")
  set(found OFF)
  foreach(line IN LISTS lines)
    if(line MATCHES "clip ${clip_regex}([^A-Za-z0-9_]|$)" AND line MATCHES "at ${joint_regex}([^A-Za-z0-9_]|$)"
       AND line MATCHES "t = ([0-9.eE+-]+) s")
      if(expected_time STREQUAL "")
        set(found ON)
      else()
        microseconds("${CMAKE_MATCH_1}" time)
        if(NOT time STREQUAL "")
          math(EXPR off "${time} - ${expected_time}")
          if(off GREATER_EQUAL -1000 AND off LESS_EQUAL 1000)
            set(found ON)
          endif()
        endif()
      endif()
    endif()
  endforeach()
  if(NOT found)
    report("no line of stdout holds \"clip ${clip_regex}\", \"at ${joint_regex}\" and \"t = <seconds> s\""
           " (expected time in microseconds: '${expected_time}', within 1000)")
  endif()
endif()

if(EXACT_JSON)
  string(JSON status ERROR_VARIABLE problem GET "${out}" status)
  if(problem)
    report("stdout is not the JSON report: ${problem}")
  endif()
  if(NOT status STREQUAL "PASS")
    report("status is '${status}', not PASS")
  endif()
  string(JSON clips ERROR_VARIABLE problem LENGTH "${out}" clips)
  if(problem OR clips LESS 1)
    report("no clips in the report ${problem}")
  endif()
  math(EXPR last "${clips} - 1")
  foreach(i RANGE ${last})
    string(JSON name ERROR_VARIABLE problem GET "${out}" clips ${i} name)
    foreach(key max_error max_error_relative)
      string(JSON value ERROR_VARIABLE problem GET "${out}" clips ${i} ${key})
      if(problem OR NOT value EQUAL 0)
        report("clip ${i} (${name}): ${key} is '${value}', not exactly 0 ${problem}")
      endif()
    endforeach()
  endforeach()
endif()

# OUT_FILES: the diff ran with --out WORK/out (in ARGS); each listed file is there and is a PNG, and the
# first (a clip's heat map) is HEAT_MAP_SIZE pixels high and wider (its legend's panel).
if(DEFINED OUT_FILES)
  foreach(name IN LISTS OUT_FILES)
    set(file "${WORK}/out/${name}")
    if(NOT EXISTS "${file}")
      report("--out wrote no ${name}")
    endif()
    file(READ "${file}" header LIMIT 24 HEX)
    if(NOT header MATCHES "^89504e470d0a1a0a")
      report("${name} is not a PNG")
    endif()
  endforeach()
  list(GET OUT_FILES 0 first)
  file(READ "${WORK}/out/${first}" header LIMIT 24 HEX)
  string(SUBSTRING "${header}" 32 8 width_hex)
  string(SUBSTRING "${header}" 40 8 height_hex)
  math(EXPR width "0x${width_hex}")
  math(EXPR height "0x${height_hex}")
  if(NOT width GREATER HEAT_MAP_SIZE OR NOT height EQUAL HEAT_MAP_SIZE)
    report("${first} is ${width}x${height}, expected ${HEAT_MAP_SIZE} high and wider")
  endif()
endif()

if(DEFINED MAX_NORMAL_DEGREES)
  string(JSON clips ERROR_VARIABLE problem LENGTH "${out}" clips)
  if(problem OR clips LESS 1)
    report("stdout is not a JSON report with clips ${problem}")
  endif()
  math(EXPR last "${clips} - 1")
  foreach(i RANGE ${last})
    string(JSON degrees ERROR_VARIABLE problem GET "${out}" clips ${i} max_normal_degrees)
    if(problem OR degrees GREATER MAX_NORMAL_DEGREES)  # if() compares numbers as doubles
      report("clip ${i}: max_normal_degrees is '${degrees}', more than ${MAX_NORMAL_DEGREES} ${problem}")
    endif()
  endforeach()
endif()

if(FACE_NORMALS)
  foreach(side a b)
    string(JSON faces ERROR_VARIABLE problem GET "${out}" correspondence normals faces_${side})
    if(problem OR NOT faces GREATER 0)
      report("correspondence.normals.faces_${side} is '${faces}', expected faces compared ${problem}")
    endif()
  endforeach()
endif()
