# Every flag the command line prints is on its command's page, so the pages cannot drift from the code:
# for each command `dqskin --help` lists, DOCS/<command>.md must exist and mention every long flag (--out,
# --max-size) that `dqskin <command> --help` prints, as a whole word (--max does not count for --max-size).
# Fails with one line per command without a page and per flag a page does not mention.
#
#   cmake -DDQSKIN=path/to/dqskin -DDOCS=docs/commands [-DDROP=command:--flag] -P docs_flags.cmake
#
# DROP removes every mention of one flag from one page before the check (the file itself is not touched),
# so that a test can show the check fails when a page loses a flag.

# The commands, from the "Subcommands:" section of the main help (one per line, indented two spaces).
execute_process(COMMAND ${DQSKIN} --help OUTPUT_VARIABLE main_help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${DQSKIN} --help exited ${status}")
endif()
string(REGEX REPLACE "^.*\nSubcommands:\n" "" subcommand_lines "${main_help}")
string(REGEX REPLACE "\n\n.*$" "" subcommand_lines "${subcommand_lines}")
string(REGEX MATCHALL "(^|\n)  [a-z]+ " commands "${subcommand_lines}")
list(TRANSFORM commands STRIP)
# A control: a help text this script cannot parse must fail, not pass with nothing checked.
list(LENGTH commands command_count)
if(command_count LESS 2)
  message(FATAL_ERROR "found ${command_count} commands in `dqskin --help`, expected the Subcommands section:\n${main_help}")
endif()

set(problems "")
set(flags_checked 0)
foreach(command IN LISTS commands)
  set(page ${DOCS}/${command}.md)
  if(NOT EXISTS ${page})
    list(APPEND problems "${command}: no page ${page}")
    continue()
  endif()
  file(READ ${page} text)
  if(DEFINED DROP AND DROP MATCHES "^${command}:(.*)$")
    string(REPLACE "${CMAKE_MATCH_1}" "" text "${text}")
  endif()

  execute_process(COMMAND ${DQSKIN} ${command} --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    list(APPEND problems "${command}: `dqskin ${command} --help` exited ${status}")
    continue()
  endif()
  # Option lines start with two spaces and a dash: "  -o,--out OUTDIR", "  --max-size TEXELS:UINT ...".
  string(REGEX MATCHALL "\n  -[-a-zA-Z0-9,]+" option_names "${help}")
  set(flags "")
  foreach(names IN LISTS option_names)
    string(REGEX MATCHALL "--[a-z0-9][-a-z0-9]*" long_names "${names}")
    list(APPEND flags ${long_names})
  endforeach()
  list(REMOVE_ITEM flags --help)
  list(REMOVE_DUPLICATES flags)
  foreach(flag IN LISTS flags)
    math(EXPR flags_checked "${flags_checked} + 1")
    if(NOT text MATCHES "${flag}([^-a-z0-9]|$)")
      list(APPEND problems "${command}: ${page} does not mention ${flag}")
    endif()
  endforeach()
endforeach()

if(problems)
  list(JOIN problems "\n" problems)
  message(FATAL_ERROR "the command pages have drifted from `dqskin COMMAND --help`:\n${problems}")
endif()
message(STATUS "${command_count} commands, ${flags_checked} flags: every one on its page")
