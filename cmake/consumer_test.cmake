# The install.consumer test (cmake -P): installs the build tree into a scratch prefix, builds
# cmake/consumer against it with find_package(dqskin), runs the installed CLI and the consumer on a
# shared model. Defined in the top-level CMakeLists.txt, which passes:
#   BUILD_DIR CONFIG PREFIX WORK_DIR SOURCE_DIR GENERATOR MAKE_PROGRAM CXX_COMPILER CXX_FLAGS
#   EXE_LINKER_FLAGS VERSION MODEL
# Without the shared model it does everything else, then prints a line that CTest reports as skipped.

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${PREFIX}" "${WORK_DIR}")

run("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --config "${CONFIG}" --prefix "${PREFIX}")

# Only the API is installed: the headers of load, asset, deform, bake, render, diff, lint, report, verify and
# what they need, not the library's own plumbing (hashing, byte sizes, the output journal, the job loop).
foreach(header load asset deformer bake render image_diff geometry_diff lint report verify)
  if(NOT EXISTS "${PREFIX}/include/dqskin/${header}.hpp")
    message(FATAL_ERROR "the public header dqskin/${header}.hpp was not installed")
  endif()
endforeach()
foreach(header sha256 byte_size output_journal stderr_lock job_run job_plan mesh_output glb_output)
  if(EXISTS "${PREFIX}/include/dqskin/${header}.hpp")
    message(FATAL_ERROR "the internal header dqskin/${header}.hpp was installed")
  endif()
endforeach()

# The consumer sees only the installed tree: same generator, compiler and flags (the sanitizer build
# needs -fsanitize at link time), no user package registry.
run("configuring the consumer" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/cmake/consumer" -B "${WORK_DIR}"
    -G "${GENERATOR}" "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
    "-DCMAKE_BUILD_TYPE=${CONFIG}" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}"
    "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS "${WORK_DIR}/CMakeCache.txt" found REGEX "^dqskin_DIR:")
string(REGEX REPLACE "^[^=]*=" "" found "${found}")
file(REAL_PATH "${found}" found)
file(REAL_PATH "${PREFIX}" real_prefix)
string(FIND "${found}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "find_package(dqskin) used ${found}, not the package installed in ${PREFIX}")
endif()
run("building the consumer" "${CMAKE_COMMAND}" --build "${WORK_DIR}" --config "${CONFIG}")

run("installed dqskin --version" "${PREFIX}/bin/dqskin" --version)
if(NOT out STREQUAL "dqskin ${VERSION}\n")
  message(FATAL_ERROR "installed dqskin --version printed '${out}', expected 'dqskin ${VERSION}'")
endif()

# The image module (libdqskin_image.so.*, opened at run time beside libdqskin) is installed and found: the
# installed CLI bakes the built-in rig into a vertex-animation texture (EXR through OpenImageIO) and checks
# it by reading it back.
run("installed dqskin bake --format vat" "${PREFIX}/bin/dqskin" bake -o "${WORK_DIR}/vat" --format vat -q)
file(GLOB_RECURSE textures "${WORK_DIR}/vat/*.exr")
if(NOT textures)
  message(FATAL_ERROR "the installed dqskin wrote no EXR texture into ${WORK_DIR}/vat")
endif()

if(NOT EXISTS "${MODEL}")
  message("install.consumer: SKIPPED running the consumer: shared test model ${MODEL} is absent")
  return()
endif()
file(GLOB_RECURSE consumer LIST_DIRECTORIES false "${WORK_DIR}/dqskin_consumer")  # any generator's layout
list(GET consumer 0 consumer)
run("dqskin_consumer ${MODEL}" "${consumer}" "${MODEL}")
message("${out}")
# CesiumMan: one 19-joint skin, one clip, 3273 vertices (shared/testdata/README.md); 22 nodes in its JSON.
set(expected "^dqskin ${VERSION}: skins 1 nodes 22 clips 1 vertices 3273\nrest vertex 0: -?[0-9]+\\.[0-9]+ -?[0-9]+\\.[0-9]+ -?[0-9]+\\.[0-9]+\n$")
if(NOT out MATCHES "${expected}")
  message(FATAL_ERROR "dqskin_consumer printed an unexpected summary (expected ${expected})")
endif()
