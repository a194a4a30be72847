# What the browser tests share (player_test.cmake, runtimes_test.cmake, player_blend_test.cmake): the
# thresholds a shot is held to, a step that must succeed, and the comparison of every shot with dqskin's
# render of its frame.

# Thresholds, idiff's: a pixel is over when a channel differs by more than `pixel` (0 to 1), and a shot
# fails when more than `percent` % of its pixels are. The two renderers rasterize the same triangles with
# different multisample patterns and resolve at different points (dqskin resolves linear colour, then
# encodes sRGB; WebGL resolves the encoded values), so silhouette pixels differ by up to the whole
# contrast between model and background; inside the silhouette the colours agree to a few 8-bit steps.
set(pixel 0.05)
set(percent 2)

# Runs a command; any exit but 0 fails the test with the command and what it printed.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 600)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " line "${ARGN}")
    message(FATAL_ERROR "${line}: exit ${status}\n${out}${err}")
  endif()
endfunction()

# Compares each shot WORK/shots/NAME.png of `expect_pass` and `expect_fail` (NAME:FRAME items; fault
# shots are named fault_…) with dqskin's render of FRAME in WORK/render/STEM/<the one clip folder>:
# `dqskin diff` must pass or warn for the others and fail for every fault. Writes WORK/figures.txt, prints
# it, and fails the test naming each shot that broke the rule; `who` names the drawer in that message.
function(compare_shots who)
  # The render's folder for the clip: bake and render name it alike (docs/formats.md, "Bake outputs").
  file(GLOB clip_dirs LIST_DIRECTORIES true "${WORK}/render/${stem}/*")
  list(LENGTH clip_dirs count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "${WORK}/render/${stem}: expected one clip folder, found ${count}")
  endif()
  set(report "")
  set(problems "")
  foreach(item IN LISTS expect_pass expect_fail)
    string(REPLACE ":" ";" parts "${item}")
    list(GET parts 0 name)
    list(GET parts 1 frame)
    # Frame file names have at least four digits.
    set(number "000${frame}")
    string(LENGTH "${number}" length)
    math(EXPR first "${length} - 4")
    string(SUBSTRING "${number}" ${first} 4 number)
    execute_process(COMMAND "${DQSKIN}" diff "${clip_dirs}/frame_${number}.png" "${WORK}/shots/${name}.png"
                            --fail ${pixel} --failpercent ${percent}
                    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
    string(REGEX REPLACE "\n.*" "" line "${out}")
    string(REGEX REPLACE "^([A-Z]+) +[^ ]+ +" "\\1 " line "${line}")
    string(APPEND report "${name} (frame ${frame}): ${line}\n")
    if(name MATCHES "^fault_")
      if(NOT status EQUAL 2)
        string(APPEND problems "${name}: a deliberately wrong decode passed the comparison (exit ${status})\n")
      endif()
    elseif(NOT (status EQUAL 0 OR status EQUAL 1))
      string(APPEND problems "${name}: ${who} differs from dqskin render (exit ${status}) ${err}\n")
    endif()
  endforeach()
  file(WRITE "${WORK}/figures.txt" "${report}")
  message("${report}")
  if(problems)
    message(FATAL_ERROR "${problems}")
  endif()
endfunction()
