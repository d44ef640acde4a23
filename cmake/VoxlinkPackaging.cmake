# SPDX-License-Identifier: BSD-3-Clause
# What `cmake --install` puts where, besides the targets' own install rules (bin/voxlink,
# lib/voxlink/libvoxlink_*.so, the Python module), and the Debian package `cpack -G DEB` makes.
install(FILES ${PROJECT_SOURCE_DIR}/python/paraview/voxlink_reader.py
        DESTINATION share/voxlink/paraview)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/voxlink)

set(CPACK_PACKAGE_NAME voxlink)
set(CPACK_PACKAGE_VENDOR "VoxLink")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Sparse volumes: convert CT and Kriging volumes to VoxLink files, report, validate, render")
set(CPACK_PACKAGE_CONTACT "VoxLink developers")
# The plugin loader and the module look in the prefix the build was configured for, so the
# package installs there too (configure with -DCMAKE_INSTALL_PREFIX=/usr for a .deb).
set(CPACK_PACKAGING_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# dpkg-shlibdeps turns every linked library of the CLI, the plugins and the module into a
# dependency on its Debian package.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# libepoxy opens libEGL/libGL at run time, so shlibdeps cannot see them; Mesa's EGL and drivers
# render headless without a GPU (llvmpipe).
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libgl1")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
if(VOXLINK_BUILD_PYTHON)
  # The module is built for this python3 and hands NumPy arrays; it does not link libpython.
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR})"
         ", python3 (<< ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}.99), python3-numpy")
endif()
include(CPack)
