# Renders the golden set of the synthetic rigs in testdata/ into OUT (removed first), with the flags the
# committed goldens in testdata/golden/ were made with. scripts/testdata/make_goldens.sh runs this same script, so
# the goldens and their test cannot drift apart.
#   cmake -DDQSKIN=path/to/dqskin -DTESTDATA=testdata -DOUT=folder [-DMODE=dqs] [-DBACKEND=auto] [-DONLY=rig]
#         -P golden_render.cmake
# MODE replaces dqs in the lit renders; ONLY renders just the lit frames of one rig (the test renders
# ONLY=twisted_cylinder MODE=lbs to show that a real change fails).
if(NOT DEFINED MODE)
  set(MODE dqs)
endif()
if(NOT DEFINED BACKEND)
  set(BACKEND auto)
endif()
file(REMOVE_RECURSE ${OUT})
# Every clip of every rig lasts 1 s: its start, middle and end.
set(common --times 0,0.5,1 --backend ${BACKEND} --quiet)
file(GLOB rigs ${TESTDATA}/*.gltf)
list(SORT rigs)
if(DEFINED ONLY)
  set(rigs ${TESTDATA}/${ONLY}.gltf)
endif()
function(golden_render)
  execute_process(COMMAND ${DQSKIN} render ${ARGN} ${common} RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "dqskin render ${ARGN} ${common}: exit status ${status}\n${err}")
  endif()
endfunction()
# lit, every rig: OUT/<rig>/<animation>/frame_NNNN.png (automatic camera)
golden_render(${rigs} -o ${OUT} --mode ${MODE} --shade lit --size 256x256)
if(DEFINED ONLY)
  return()
endif()
# the candy wrapper of the twisted cylinder: the lbs-dqs heat map, and lbs normals
golden_render(${TESTDATA}/twisted_cylinder.gltf -o ${OUT}/mode-diff --shade mode-diff --size 256x256)
golden_render(${TESTDATA}/twisted_cylinder.gltf -o ${OUT}/lbs-normals --mode lbs --shade normals --size 256x256)
# dib, deformed by the CPU reference, on the textured cylinder
golden_render(${TESTDATA}/textured_cylinder.gltf -o ${OUT}/dib --mode dib --size 256x256)
# the glTF cameras of camera_dolly: the moving perspective one and the orthographic one, in their aspect
# ratio (3:2), which is also what they give without --size
golden_render(${TESTDATA}/camera_dolly.gltf -o ${OUT}/camera-dolly --camera dolly --size 384x256)
golden_render(${TESTDATA}/camera_dolly.gltf -o ${OUT}/camera-top --camera top --size 384x256)
