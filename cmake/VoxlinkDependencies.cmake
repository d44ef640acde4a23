# SPDX-License-Identifier: BSD-3-Clause
# Every dependency comes from Debian 12 packages (scripts/install-deps.sh installs them).
find_package(Threads REQUIRED)
find_package(ZLIB REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)

# OpenVDB: Debian ships only a Find module.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)
# FindOpenVDB sets BUILD_SHARED_LIBS ON in our scope, which made every later add_library without
# a type (voxlink_geostat) a shared library that `cmake --install` did not install: our
# libraries are static, linked into the executable, the module and the plugins.
set(BUILD_SHARED_LIBS OFF)

# OpenImageIO's config lists /usr/include/opencv4 as an include directory although OpenCV is
# not a dependency of ours; drop directories that do not exist so configuring does not fail.
find_package(OpenImageIO CONFIG REQUIRED)
foreach(oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${oiio_target})
    get_target_property(oiio_dirs ${oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(oiio_dirs)
      set(kept_dirs "")
      foreach(dir IN LISTS oiio_dirs)
        if(EXISTS "${dir}" OR dir MATCHES "\\$<")
          list(APPEND kept_dirs "${dir}")
        endif()
      endforeach()
      set_target_properties(${oiio_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${kept_dirs}")
    endif()
  endif()
endforeach()

find_package(GDCM REQUIRED CONFIG PATHS /usr/lib/x86_64-linux-gnu/gdcm-3.0)

# NIfTI-1/2 C library (libnifti2-dev): no CMake config, plain library + headers.
find_path(NIFTI_INCLUDE_DIR nifti2_io.h PATH_SUFFIXES nifti REQUIRED)
find_library(NIFTI2_LIBRARY nifti2 REQUIRED)
find_library(ZNZ_LIBRARY znz)
add_library(voxlink_nifti INTERFACE)
target_include_directories(voxlink_nifti SYSTEM INTERFACE ${NIFTI_INCLUDE_DIR})
target_link_libraries(voxlink_nifti INTERFACE ${NIFTI2_LIBRARY} ZLIB::ZLIB)
if(ZNZ_LIBRARY)
  target_link_libraries(voxlink_nifti INTERFACE ${ZNZ_LIBRARY})
endif()

# Dense linear algebra for global kriging: OpenBLAS (BLAS + LAPACK with run-time CPU dispatch,
# libopenblas-dev) through LAPACKE (liblapacke-dev). OpenBLAS is linked directly so its LAPACK,
# not the reference one, serves LAPACKE whatever the system's alternatives say.
find_path(OPENBLAS_INCLUDE_DIR cblas.h PATH_SUFFIXES openblas-pthread openblas REQUIRED)
find_library(OPENBLAS_LIBRARY openblas REQUIRED)
find_path(LAPACKE_INCLUDE_DIR lapacke.h REQUIRED)
find_library(LAPACKE_LIBRARY lapacke REQUIRED)
add_library(voxlink_blas INTERFACE)
target_include_directories(voxlink_blas SYSTEM INTERFACE ${OPENBLAS_INCLUDE_DIR}
                                                          ${LAPACKE_INCLUDE_DIR})
target_link_libraries(voxlink_blas INTERFACE ${OPENBLAS_LIBRARY} ${LAPACKE_LIBRARY})

if(VOXLINK_BUILD_VIEWER)
  find_package(glfw3 3.3 REQUIRED)
  find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
  find_package(glm REQUIRED)
endif()

if(VOXLINK_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
