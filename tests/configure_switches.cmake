# Checks what the configure step says of each optional library: one
# switched off with SR_WITH_<LIB>=OFF is said to be switched off, never
# "install ..." (that would send the reader to install what the build was
# told to leave out), and one switched on but not found keeps its
# "install ..." line.  Configures the source twice in WORK: every switch
# off, then every switch on with pkg-config and CMake's find modules
# finding none of the libraries.
#   cmake -DSRC=. -DWORK=dir -DCC=cc -DGENERATOR=... -P configure_switches.cmake
cmake_minimum_required(VERSION 3.20)
foreach(var SRC WORK CC GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "configure_switches.cmake: -D${var}=... is required")
  endif()
endforeach()
set(libs JANSSON JPEG EXPAT MESHOPT DRACO WEBP TEXT FRIBIDI ASSIMP VIEWER)
# Only the configure step runs: the parts that need nothing optional stay
# out to keep it short.
set(common -S ${SRC} -G ${GENERATOR} -DCMAKE_C_COMPILER=${CC} -DSR_BUILD_TESTS=OFF
    -DSR_BUILD_BENCH=OFF -DSR_BUILD_PYTHON=OFF -DSR_BUILD_EXAMPLES=OFF)

function(configure dir out_var)
  file(REMOVE_RECURSE ${WORK}/${dir})
  execute_process(COMMAND ${ARGN} ${common} -B ${WORK}/${dir}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring ${dir} failed:\n${out}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

set(off "")
foreach(lib ${libs})
  list(APPEND off -DSR_WITH_${lib}=OFF)
endforeach()
configure(off out ${CMAKE_COMMAND} ${off})
set(failed "")
foreach(lib ${libs})
  if(NOT out MATCHES "softrast: switched off \\(SR_WITH_${lib}=OFF\\)")
    list(APPEND failed "SR_WITH_${lib}=OFF is not said to be switched off")
  endif()
endforeach()
string(REGEX MATCHALL "softrast: install [^\n]*" installs "${out}")
foreach(line ${installs})
  list(APPEND failed "with every library switched off: '${line}'")
endforeach()

# Every switch on, nothing found: an empty pkg-config search path, and
# CMake's FindJPEG and FindEXPAT disabled.  The libraries whose features
# need another one (meshoptimizer and Draco need jansson, text needs
# expat, FriBidi text) are not asked for when that one is missing.
file(MAKE_DIRECTORY ${WORK}/empty-pkgconfig)
configure(missing out ${CMAKE_COMMAND} -E env PKG_CONFIG_LIBDIR=${WORK}/empty-pkgconfig
  PKG_CONFIG_PATH= ${CMAKE_COMMAND} -DCMAKE_DISABLE_FIND_PACKAGE_JPEG=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_EXPAT=ON)
foreach(pkg libjansson-dev libjpeg-dev libexpat1-dev libwebp-dev libassimp-dev libsdl2-dev)
  if(NOT out MATCHES "softrast: install ${pkg} ")
    list(APPEND failed "with ${pkg} missing: no 'softrast: install ${pkg} ...' line")
  endif()
endforeach()
if(out MATCHES "softrast: switched off")
  list(APPEND failed "with every switch on: a library is said to be switched off")
endif()

if(failed)
  list(JOIN failed "\n  " text)
  message(FATAL_ERROR "configure_switches:\n  ${text}\n--- last configure's output:\n${out}")
endif()
file(REMOVE_RECURSE ${WORK}/off ${WORK}/missing)
message(STATUS "configure_switches: every switch said as it is")
