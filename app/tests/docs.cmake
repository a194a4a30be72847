# The command pages (docs/commands/<command>.md) against the command line: every command has a page and
# every long flag its --help prints is on it (docs_flags.cmake). The second test removes one flag from one
# page in memory and must see the check fail naming it, so that the first cannot pass by checking nothing.
set(docs_flags_args -DDQSKIN=$<TARGET_FILE:dqskin_cli> -DDOCS=${PROJECT_SOURCE_DIR}/docs/commands)
add_test(NAME cli.docs_every_flag_on_its_page COMMAND ${CMAKE_COMMAND} ${docs_flags_args}
  -P ${CMAKE_CURRENT_LIST_DIR}/docs_flags.cmake)
add_test(NAME cli.docs_a_flag_missing_from_its_page_fails COMMAND ${CMAKE_COMMAND} ${docs_flags_args}
  -DDROP=bake:--max-size -P ${CMAKE_CURRENT_LIST_DIR}/docs_flags.cmake)
set_tests_properties(cli.docs_a_flag_missing_from_its_page_fails PROPERTIES
  PASS_REGULAR_EXPRESSION "bake: [^\n]*/docs/commands/bake.md does not mention --max-size\n")
