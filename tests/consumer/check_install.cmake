# The installed package, used as a tool outside the tree would: install this build into a
# fresh prefix, configure and build tests/consumer against it (find_package), run its C++ and
# C programs and, with pkg-config, the C program compiled from `pkg-config --cflags --libs`.
# Each must print the same tip displacement as REFERENCE (the same main.cpp on the in-tree
# library). With PYTHON (the module was built) the installed Python module, imported from
# PYTHON_DIR under the prefix alone, must load the prefix's librockdd.so and print the same
# from example.py. docs/library.md quotes the consumer's files: they must still be there verbatim.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DREFERENCE=... -DSCENE=...
#         [-DPYTHON=/usr/bin/python3 -DPYTHON_DIR=lib/python3/dist-packages] -P check_install.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR REFERENCE SCENE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_install.cmake needs -D${var}=...")
  endif()
endforeach()

# Runs the command; stops the test with its output when it fails. OUTPUT_VARIABLE: stdout.
function(run_step name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "OUTPUT_VARIABLE" "COMMAND")
  execute_process(COMMAND ${ARG_COMMAND} RESULT_VARIABLE status OUTPUT_VARIABLE out
    ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${name} failed (${status}):\n${out}\n${err}")
  endif()
  if(ARG_OUTPUT_VARIABLE)
    set(${ARG_OUTPUT_VARIABLE} "${out}" PARENT_SCOPE)
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run_step(install COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file include/rockdd/rockdd.hpp include/rockdd/rockdd.h lib/cmake/rockdd/rockddConfig.cmake
    lib/cmake/rockdd/rockddConfigVersion.cmake lib/pkgconfig/rockdd.pc bin/rockdd)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install has no ${file}")
  endif()
endforeach()

run_step(configure COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run_step(build COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build)

run_step(reference COMMAND ${REFERENCE} ${SCENE} OUTPUT_VARIABLE expected)
run_step(tip_cpp COMMAND ${WORK_DIR}/build/tip_cpp ${SCENE} OUTPUT_VARIABLE cpp)
run_step(tip_c COMMAND ${WORK_DIR}/build/tip_c ${SCENE} OUTPUT_VARIABLE c)
message(STATUS "library run: ${expected}C++ consumer: ${cpp}C consumer: ${c}")
if(NOT expected MATCHES "^tip uy = -[0-9]")
  message(FATAL_ERROR "the library run printed '${expected}', expected 'tip uy = -...'")
endif()
if(NOT cpp STREQUAL expected OR NOT c STREQUAL expected)
  message(FATAL_ERROR "the consumers disagree with the library run")
endif()

find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
  set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
  run_step(pkg-config COMMAND ${PKG_CONFIG} --cflags --libs rockdd OUTPUT_VARIABLE flags)
  string(STRIP "${flags}" flags)
  message(STATUS "pkg-config --cflags --libs rockdd: ${flags}")
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run_step(cc COMMAND cc ${SOURCE_DIR}/tests/consumer/main.c ${flags} -Wl,-rpath,${prefix}/lib
    -o ${WORK_DIR}/tip_pkg_config)
  run_step(tip_pkg_config COMMAND ${WORK_DIR}/tip_pkg_config ${SCENE} OUTPUT_VARIABLE pc)
  if(NOT pc STREQUAL expected)
    message(FATAL_ERROR "the pkg-config build printed '${pc}', the library run '${expected}'")
  endif()
else()
  message(STATUS "no pkg-config: its check skipped")
endif()

set(quoted CMakeLists.txt main.cpp main.c)
if(PYTHON)
  set(module_dir ${prefix}/${PYTHON_DIR})
  file(GLOB module ${module_dir}/rockdd*.so)
  if(NOT module)
    message(FATAL_ERROR "the install has no Python module in ${PYTHON_DIR}")
  endif()
  # Only the prefix on the paths: the module must find librockdd.so through its RPATH.
  set(clean_env ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH PYTHONPATH=${module_dir})
  run_step(python_import COMMAND ${clean_env} ${PYTHON} -c
    "import rockdd; print(rockdd.__file__); print([l.split()[-1] for l in open('/proc/self/maps') if 'librockdd.so' in l][0])"
    OUTPUT_VARIABLE loaded)
  message(STATUS "the installed module and library: ${loaded}")
  string(FIND "${loaded}" "${module_dir}/rockdd" at_module)
  string(FIND "${loaded}" "${prefix}/lib/librockdd.so" at_library)
  if(NOT at_module EQUAL 0 OR at_library EQUAL -1)
    message(FATAL_ERROR "python imported '${loaded}', expected the module and library under ${prefix}")
  endif()
  run_step(python_example
    COMMAND ${clean_env} ${PYTHON} ${SOURCE_DIR}/tests/consumer/example.py ${SCENE}
    OUTPUT_VARIABLE py)
  message(STATUS "Python example: ${py}")
  if(NOT py STREQUAL expected)
    message(FATAL_ERROR "the Python example printed '${py}', the library run '${expected}'")
  endif()
  list(APPEND quoted example.py)
else()
  message(STATUS "no Python module built: its check skipped")
endif()

foreach(file ${quoted})
  file(READ ${SOURCE_DIR}/tests/consumer/${file} text)
  file(READ ${SOURCE_DIR}/docs/library.md doc)
  string(STRIP "${text}" text)
  string(FIND "${doc}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "docs/library.md no longer quotes tests/consumer/${file} as it is")
  endif()
endforeach()
