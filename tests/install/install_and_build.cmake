# cmake -P script (CTest test "install: find_package(interlin) consumer"): installs the build tree
# into a fresh prefix, configures and builds tests/install/consumer against it with
# find_package(interlin REQUIRED), runs the consumer.
#   -DBUILD_DIR=<interlin build tree> -DWORK_DIR=<scratch> -DSOURCE_DIR=<tests/install/consumer>
#   -DCXX=<compiler>
foreach(var BUILD_DIR WORK_DIR SOURCE_DIR CXX)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_and_build.cmake: -D${var}=... missing")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
  set(output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/run)
set(prefix ${WORK_DIR}/prefix)
run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# Only the installed tree may satisfy find_package: no package registries, no source paths.
run("configure consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
run("build consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2)
run("run consumer" ${WORK_DIR}/build/consumer ${WORK_DIR}/run)
message("${output}")
file(REMOVE_RECURSE ${WORK_DIR})
