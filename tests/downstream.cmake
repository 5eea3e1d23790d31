# Installs the build into a fresh prefix, then configures, builds and runs
# tests/downstream against that prefix, found once with find_package, once
# with pkg-config, and once with pkg-config --static linking the archives.
# The build tree's own paths are nowhere in the downstream configuration:
# only the prefix is.
#   cmake -DBUILD=<softrast build dir> -DSRC=<tests/downstream> -DWORK=<scratch dir>
#         [-DFLAGS=<compile and link flags>] -P downstream.cmake
cmake_minimum_required(VERSION 3.20)
foreach(var BUILD SRC WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "downstream.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})

foreach(how cmake pkg-config pkg-config-static)
  set(bin ${WORK}/build-${how})
  # pkg-config searches the prefix first; CMake searches only the prefix.
  set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig:${prefix}/lib64/pkgconfig:${prefix}/share/pkgconfig")
  run(${CMAKE_COMMAND} -S ${SRC} -B ${bin} -DSR_FIND=${how}
      -DCMAKE_PREFIX_PATH=${prefix} "-DCMAKE_C_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}" -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  run(${CMAKE_COMMAND} --build ${bin})
  run(${bin}/downstream ${WORK}/${how}.png)
endforeach()
