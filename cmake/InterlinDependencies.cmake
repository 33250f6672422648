# Debian packages only (tools/debian-packages.txt). Usage verified in shared/BUILD-NOTES.md.

# find_package(PACKAGE ARGS... REQUIRED) for a package the installed libraries link against
# (public, or private to a static library: users link it too). interlinConfig.cmake replays the
# call as find_dependency(PACKAGE ARGS...); the imported targets it creates are recorded, and
# cmake/InterlinInstall.cmake refuses an exported library that links an imported target from a
# package found otherwise.
macro(interlin_find_dependency package)
  get_property(_interlin_before DIRECTORY PROPERTY IMPORTED_TARGETS)
  find_package(${package} ${ARGN} REQUIRED)
  get_property(_interlin_after DIRECTORY PROPERTY IMPORTED_TARGETS)
  if(_interlin_before)
    list(REMOVE_ITEM _interlin_after ${_interlin_before})
  endif()
  set_property(GLOBAL APPEND PROPERTY INTERLIN_DEPENDENCY_TARGETS ${_interlin_after})
  string(JOIN " " _interlin_args ${package} ${ARGN})
  set_property(GLOBAL APPEND_STRING PROPERTY INTERLIN_FIND_DEPENDENCIES
               "find_dependency(${_interlin_args})\n")
endmacro()

interlin_find_dependency(Eigen3 3.4 NO_MODULE)       # Eigen3::Eigen
interlin_find_dependency(OpenMesh)                   # OpenMeshCore, OpenMeshTools (OPENMESH_LIBRARIES is empty)
# PCL (point-cloud filters, normals, binary PCD/PLY decoding; reconstruction/clouds only). Its
# config loads VTK, whose MPI target needs the C language (enabled in the top CMakeLists, and by
# interlinConfig.cmake for users).
interlin_find_dependency(PCL 1.13 COMPONENTS common io filters features kdtree search)
interlin_find_dependency(flann CONFIG)               # flann::flann_cpp (the C++ headers also need lz4)
interlin_find_dependency(PNG)                        # PNG::PNG, for the shaded preview
find_package(nlohmann_json 3 REQUIRED)               # nlohmann_json::nlohmann_json, surface JSON
find_package(tomlplusplus 3 REQUIRED CONFIG)         # tomlplusplus::tomlplusplus (shared lib), profile TOML
interlin_find_dependency(Threads)
# OpenCASCADE (optional) is a baseline and an independent IGES reader for checks, never a
# dependency of the library.
find_package(OpenCASCADE QUIET)
if(INTERLIN_BUILD_TESTS)
  find_package(Catch2 2 REQUIRED)                    # Catch2::Catch2 (v2, single header)
  include(Catch)
endif()
if(INTERLIN_BUILD_BENCH)
  find_package(benchmark QUIET)
  if(NOT benchmark_FOUND)
    message(STATUS "Google Benchmark not found: bench/ is skipped")
    set(INTERLIN_BUILD_BENCH OFF)
  endif()
endif()
