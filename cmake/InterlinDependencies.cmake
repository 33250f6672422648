# Debian packages only (tools/debian-packages.txt). Usage verified in shared/BUILD-NOTES.md.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)          # Eigen3::Eigen
find_package(OpenMesh REQUIRED)                      # OpenMeshCore, OpenMeshTools (OPENMESH_LIBRARIES is empty)
# PCL (point-cloud filters, normals, binary PCD/PLY decoding; reconstruction/clouds only). Its
# config loads VTK, whose MPI target needs the C language (enabled in the top CMakeLists).
find_package(PCL 1.13 REQUIRED COMPONENTS common io filters features kdtree search)
find_package(flann REQUIRED CONFIG)                  # flann::flann_cpp (the C++ headers also need lz4)
find_package(PNG REQUIRED)                           # PNG::PNG, for the shaded preview
find_package(nlohmann_json 3 REQUIRED)               # nlohmann_json::nlohmann_json, surface JSON
find_package(tomlplusplus 3 REQUIRED CONFIG)         # tomlplusplus::tomlplusplus (shared lib), profile TOML
find_package(Threads REQUIRED)
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
