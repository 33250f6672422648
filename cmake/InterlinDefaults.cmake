include(GNUInstallDirs)

# Compile settings shared by every interlin target: warnings on, sanitizers on request.
function(interlin_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(INTERLIN_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
    # GCC's manual: sanitizers "tend to increase the rate of false positive warnings, most notably
    # those around -Wmaybe-uninitialized" (here inside libstdc++'s <regex> and OpenMesh's
    # properties); the Release build keeps the warning for our code.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
  if(INTERLIN_FUZZ) # coverage for libFuzzer; the fuzz binaries add -fsanitize=fuzzer at link
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# A library that `cmake --install` installs and interlinConfig.cmake exports as interlin::<name>
# (cmake/InterlinInstall.cmake). Every interlin_module is one; call this for other libraries
# (e.g. an INTERFACE library grouping modules).
function(interlin_export target)
  set_property(GLOBAL APPEND PROPERTY INTERLIN_EXPORTED_TARGETS ${target})
endfunction()

# A module library: sources in <module>/src, public headers in <module>/include (installed under
# include/). Static, position-independent (it also goes into the Python module), C++20 for its
# users, exported as interlin::<name>. PRIVATE_DEPS stay out of users' compile lines; a static
# library still needs them at link time, so their packages must be found with
# interlin_find_dependency (cmake/InterlinDependencies.cmake), which interlinConfig.cmake replays.
function(interlin_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  add_library(interlin::${name} ALIAS ${name})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_features(${name} PUBLIC cxx_std_20)
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  # A header-only private dependency (an INTERFACE library that links nothing) is needed to build
  # the module, never to link it: keep it out of the exported link interface.
  set(private "")
  foreach(dep IN LISTS ARG_PRIVATE_DEPS)
    if(TARGET ${dep})
      get_target_property(type ${dep} TYPE)
      get_target_property(links ${dep} INTERFACE_LINK_LIBRARIES)
      if(type STREQUAL "INTERFACE_LIBRARY" AND NOT links)
        set(dep "$<BUILD_INTERFACE:${dep}>")
      endif()
    endif()
    list(APPEND private "${dep}")
  endforeach()
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${private})
  interlin_defaults(${name})
  interlin_export(${name})
endfunction()
