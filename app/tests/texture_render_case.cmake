# Whether a file draws the colours of another: renders CASE and REFERENCE lit, one frame at TIME (default
# 0.5 s; a file without animations draws its rest pose) at the same size, and passes when `dqskin diff`
# finds the two images equal within the golden thresholds and, when given, `dqskin info CASE` prints a
# warning matching WARNING. A control diff of the reference against UNLIKE (a render that must differ: the
# rig without its texture, or with it) proves that the comparison can fail. Used for the texture
# extensions (scripts/testdata/make_texture_cases.py) and the meshes written beside textures.
#   cmake -DDQSKIN=dqskin -DCASE=a.gltf -DREFERENCE=b.gltf -DUNLIKE=c.gltf -DOUT=dir [-DTIME=s]
#         [-DWARNING=regex] -P texture_render_case.cmake
file(REMOVE_RECURSE ${OUT})
if(NOT DEFINED TIME)
  set(TIME 0.5)
endif()
set(common --times ${TIME} --size 128x128 --shade lit --quiet)
set(thresholds --fail 0.02 --failpercent 0.2)

function(render input folder)
  execute_process(COMMAND ${DQSKIN} render ${input} -o ${OUT}/${folder} ${common}
                  RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "dqskin render ${input}: exit status ${status}\n${err}")
  endif()
endfunction()

# The one image rendered, whatever the input's and the clip's names: OUT/<folder>/<input>/<clip>/*.png.
function(frames folder result)
  file(GLOB_RECURSE images ${OUT}/${folder}/*.png)
  list(LENGTH images n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected one image in ${OUT}/${folder}, found ${n}")
  endif()
  set(${result} ${images} PARENT_SCOPE)
endfunction()

function(diff_status a b result)
  execute_process(COMMAND ${DQSKIN} diff ${a} ${b} ${thresholds} RESULT_VARIABLE status OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 300)
  set(${result} ${status} PARENT_SCOPE)
  set(diff_text "${out}${err}" PARENT_SCOPE)
endfunction()

render(${REFERENCE} reference)
render(${UNLIKE} unlike)
frames(reference reference_frames)
frames(unlike unlike_frames)
diff_status(${reference_frames} ${unlike_frames} control)
if(NOT control EQUAL 2)
  message(FATAL_ERROR "control: the render of ${UNLIKE} should differ from that of ${REFERENCE} (diff exit ${control})\n${diff_text}")
endif()

render(${CASE} case)
frames(case case_frames)
diff_status(${reference_frames} ${case_frames} status)
message("${diff_text}")
if(NOT status EQUAL 0 AND NOT status EQUAL 1)
  message(FATAL_ERROR "the render of ${CASE} does not show the colours of ${REFERENCE} (diff exit ${status})")
endif()
if(DEFINED WARNING)
  execute_process(COMMAND ${DQSKIN} info ${CASE} OUTPUT_VARIABLE info ERROR_VARIABLE info_err TIMEOUT 60)
  if(NOT "${info}${info_err}" MATCHES "${WARNING}")
    message(FATAL_ERROR "no warning matching '${WARNING}' for ${CASE}:\n${info}${info_err}")
  endif()
endif()
