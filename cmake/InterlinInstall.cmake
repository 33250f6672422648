# `cmake --install`: headers, the exported libraries, the CLI and a CMake package, so that another
# project does find_package(interlin REQUIRED) and links interlin::<module>. Included once, at the
# end of the top-level CMakeLists.txt, after every target exists.
include(CMakePackageConfigHelpers)

set(INTERLIN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/interlin)

# Public include directories given as plain source-tree paths (target_include_directories(T
# PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/part/include), as for a module's parts) are valid only in
# the build tree: they become $<BUILD_INTERFACE:...> and are installed under include/.
function(interlin_install_include_dirs target)
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT dirs)
    return()
  endif()
  set(result "")
  foreach(dir IN LISTS dirs)
    if(IS_ABSOLUTE "${dir}" AND (dir MATCHES "^${PROJECT_SOURCE_DIR}/" OR
                                 dir MATCHES "^${PROJECT_BINARY_DIR}/"))
      list(APPEND result "$<BUILD_INTERFACE:${dir}>")
      install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    else()
      list(APPEND result "${dir}")
    endif()
  endforeach()
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${result}")
endfunction()

# Every imported target in an exported library's link interface must come from a package that
# interlinConfig.cmake finds again (interlin_find_dependency), else the installed package would
# name a target its users do not have. Checked here so that the configure step fails, not the
# users' builds.
function(interlin_check_link_interface target exported provided)
  get_target_property(libs ${target} INTERFACE_LINK_LIBRARIES)
  if(NOT libs)
    return()
  endif()
  foreach(lib IN LISTS libs)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
    string(REGEX REPLACE "^interlin::" "" own "${lib}")
    if(lib MATCHES "^\\$<" OR own IN_LIST exported OR NOT TARGET ${lib})
      continue() # generator expressions, our own libraries, plain library names and flags
    endif()
    get_target_property(imported ${lib} IMPORTED)
    if(imported AND NOT lib IN_LIST provided)
      message(FATAL_ERROR
        "interlin::${target} links ${lib}, which no package found with interlin_find_dependency "
        "provides: find its package with interlin_find_dependency in "
        "cmake/InterlinDependencies.cmake so that interlinConfig.cmake finds it for users.")
    endif()
  endforeach()
endfunction()

function(interlin_install_package)
  get_property(exported GLOBAL PROPERTY INTERLIN_EXPORTED_TARGETS)
  get_property(provided GLOBAL PROPERTY INTERLIN_DEPENDENCY_TARGETS)
  get_property(INTERLIN_FIND_DEPENDENCIES GLOBAL PROPERTY INTERLIN_FIND_DEPENDENCIES)
  foreach(target IN LISTS exported)
    interlin_install_include_dirs(${target})
    interlin_check_link_interface(${target} "${exported}" "${provided}")
  endforeach()
  install(TARGETS ${exported} EXPORT interlinTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT interlinTargets NAMESPACE interlin:: DESTINATION ${INTERLIN_CMAKE_DIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/interlinConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/interlinConfig.cmake
                                INSTALL_DESTINATION ${INTERLIN_CMAKE_DIR})
  # 0.x: a minor version may change the API.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/interlinConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/interlinConfig.cmake
                ${PROJECT_BINARY_DIR}/interlinConfigVersion.cmake
          DESTINATION ${INTERLIN_CMAKE_DIR})
endfunction()

interlin_install_package()
