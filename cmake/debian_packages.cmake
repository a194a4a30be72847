# The Debian packages, made by CPack from the install components (scripts/package/debian.sh):
#   dqskin          the command line, the shared library and its image module, the player (runtime)
#   libdqskin-dev   the public headers, the .so link and the CMake package (dev)
#   python3-dqskin  the Python module and its type stubs (python)
# Dependencies on Debian's libraries come from dpkg-shlibdeps; the others are stated here. Configure with
# -DCMAKE_INSTALL_PREFIX=/usr, so that the files land where Debian's tools look.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME dqskin)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# One synopsis for the three (CPack 3.25 takes it for every component); each extended description says
# what its package holds.
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "glTF skinned animation with dual quaternions, headless")
set(CPACK_PACKAGE_CONTACT "dqskin developers <dqskin@packages.invalid>")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev python)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libdqskin is the project's own: dpkg-shlibdeps finds it in the build tree.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/lib)
set(CPACK_STRIP_FILES ON)
# A shlibs file for the libraries, and ldconfig as Debian runs it now, by a trigger (lintian's
# lacks-ldconfig-trigger; CPack's maintainer scripts still call it too, a warning).
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
file(WRITE ${PROJECT_BINARY_DIR}/debian/triggers "activate-noawait ldconfig\n")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA ${PROJECT_BINARY_DIR}/debian/triggers)
set(_dqskin_exact "${PROJECT_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE}")

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME dqskin)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "dqskin turns the animated skeleton of a glTF 2.0 character into dual
quaternions (Kavan et al.) and deforms its meshes on the GPU (EGL, OSMesa)
or the CPU: per-frame meshes, vertex-animation and bone textures, morph
animations, images, reports, and diffs for continuous integration. This
package holds the command line, its shared library and the static player
page of its bakes.")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME libdqskin-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "dqskin (= ${_dqskin_exact}), libglm-dev")
set(CPACK_DEBIAN_DEV_DESCRIPTION "Development files: the public C++ headers of dqskin's library and its
CMake package. find_package(dqskin) and link dqskin::dqskin to load glTF
files, sample their animations and deform them with dual quaternions.")

if(NOT Python3_VERSION_MINOR)
  find_package(Python3 COMPONENTS Interpreter)
endif()
math(EXPR _dqskin_python_next "${Python3_VERSION_MINOR} + 1")
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-dqskin)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
    "dqskin (= ${_dqskin_exact}), python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), python3 (<< ${Python3_VERSION_MAJOR}.${_dqskin_python_next}), python3-numpy")
set(CPACK_DEBIAN_PYTHON_DESCRIPTION "For Python 3 and Blender: import dqskin to load glTF files, deform
their clips into NumPy arrays, and run dqskin's bake, diff, lint and
report with their options as keyword arguments.")

include(CPack)
