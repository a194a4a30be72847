# Golden images: the synthetic rigs rendered as scripts/testdata/make_goldens.sh rendered testdata/golden/ (both run
# golden_render.cmake), then `dqskin diff` against the committed images.
#
# Thresholds: a pixel fails above 0.02 (5 steps of 255 in a channel) and an image fails when more than
# 0.2 % of its pixels (131 of 256×256) do; any pixel over 0.004 (one step) warns. llvmpipe through EGL and
# through OSMesa (Mesa 22.3.6) give bit-identical images (max 0; cli.golden_osmesa_diff renders the whole
# set through OSMesa and compares it too), so this only leaves room for another Mesa's rasterization and
# MSAA resolve along silhouettes. A real change is far above it: lbs instead of
# dqs fails the twisted cylinder with 8 % of its pixels up to 0.6 off (cli.golden_lbs_fails).
set(golden_out ${CMAKE_CURRENT_BINARY_DIR}/golden)
set(golden_thresholds --fail 0.02 --failpercent 0.2 --warn 0.004)
function(dqskin_golden_render name out)
  add_test(NAME cli.golden_render${name} COMMAND ${CMAKE_COMMAND} -DDQSKIN=$<TARGET_FILE:dqskin_cli>
    -DTESTDATA=${PROJECT_SOURCE_DIR}/testdata -DOUT=${out} ${ARGN} -P ${PROJECT_SOURCE_DIR}/app/tests/golden_render.cmake)
  set_tests_properties(cli.golden_render${name} PROPERTIES ENVIRONMENT "${bake_test_environment}" LABELS gpu
    FIXTURES_SETUP golden${name})
endfunction()

dqskin_golden_render("" ${golden_out})
set(golden_diff_args ${PROJECT_SOURCE_DIR}/testdata/golden ${golden_out} ${golden_thresholds})
string(REPLACE ";" "\\;" golden_diff_args "${golden_diff_args}")  # one -DARGS= argument
set(golden_diff_args -DCOMMAND=$<TARGET_FILE:dqskin_cli> "-DARGS=${golden_diff_args}")
add_test(NAME cli.golden_diff COMMAND ${CMAKE_COMMAND} ${golden_diff_args} -P ${PROJECT_SOURCE_DIR}/app/tests/golden_diff.cmake)
set_tests_properties(cli.golden_diff PROPERTIES FIXTURES_REQUIRED golden LABELS gpu)

# The other backend: the whole set through OSMesa against the same goldens (made through EGL).
get_directory_property(golden_have_osmesa DIRECTORY ${PROJECT_SOURCE_DIR}/lib DEFINITION OSMESA_FOUND)
if(golden_have_osmesa)
  dqskin_golden_render(_osmesa ${golden_out}_osmesa -DBACKEND=osmesa)
  set(osmesa_diff_args ${PROJECT_SOURCE_DIR}/testdata/golden ${golden_out}_osmesa ${golden_thresholds})
  string(REPLACE ";" "\\;" osmesa_diff_args "${osmesa_diff_args}")  # one -DARGS= argument
  set(osmesa_diff_args -DCOMMAND=$<TARGET_FILE:dqskin_cli> "-DARGS=${osmesa_diff_args}")
  add_test(NAME cli.golden_osmesa_diff COMMAND ${CMAKE_COMMAND} ${osmesa_diff_args}
    -P ${PROJECT_SOURCE_DIR}/app/tests/golden_diff.cmake)
  set_tests_properties(cli.golden_osmesa_diff PROPERTIES FIXTURES_REQUIRED golden_osmesa LABELS gpu)
endif()

# The same thresholds catch a real change: the twisted cylinder blended with lbs fails the dqs goldens.
dqskin_golden_render(_lbs ${golden_out}_lbs -DONLY=twisted_cylinder -DMODE=lbs)
include(${CMAKE_CURRENT_LIST_DIR}/cli_test.cmake)
dqskin_cli_test(cli.golden_lbs_fails 2 ARGS diff ${PROJECT_SOURCE_DIR}/testdata/golden/twisted_cylinder
  ${golden_out}_lbs/twisted_cylinder ${golden_thresholds} STDOUT "FAIL  twist/frame_0002.png  .*summary: FAIL")
set_tests_properties(cli.golden_lbs_fails PROPERTIES FIXTURES_REQUIRED golden_lbs)
