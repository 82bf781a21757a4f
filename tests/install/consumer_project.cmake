# cmake -DPREFIX -DSOURCE -DBINARY -DGENERATOR [-DRUN_ARGS=a|b] [-DDISABLE=P1|P2]
#       [-DEXPECT_ERROR=regex] [-DLAUNCHER=ccache] -P consumer_project.cmake:
# configures SOURCE (a project outside ffdkit, tests/install/consumers/<component>/) against the
# ffdkit package installed in PREFIX, builds it and runs it with RUN_ARGS. No package of DISABLE
# may be looked for, checked twice: each is made unfindable (CMAKE_DISABLE_FIND_PACKAGE_<name>:
# a REQUIRED lookup of it fails), and CMake's trace of the configure step must hold no
# find_package of it (which also catches a QUIET lookup). With EXPECT_ERROR the configure step
# must fail with output matching it. LAUNCHER (ccache) compiles the project through the compiler
# cache, with BINARY's parent folder as its base folder (paths below it hashed relative to the
# build folder: tests/install/CMakeLists.txt puts BINARY beside PREFIX).
cmake_minimum_required(VERSION 3.25)  # IN_LIST and the other policies of a project
file(REMOVE_RECURSE "${BINARY}")
file(MAKE_DIRECTORY "${BINARY}")
string(REPLACE "|" ";" disable "${DISABLE}")
string(REPLACE "|" ";" run_args "${RUN_ARGS}")
set(options "")
foreach(package IN LISTS disable)
  list(APPEND options "-DCMAKE_DISABLE_FIND_PACKAGE_${package}=ON")
endforeach()
if(LAUNCHER)
  list(APPEND options "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  cmake_path(GET BINARY PARENT_PATH base)
  set(ENV{CCACHE_BASEDIR} "${base}")
endif()
set(trace "${BINARY}/configure-trace.json")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE}" -B "${BINARY}" -G "${GENERATOR}"
                        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${PREFIX}" ${options}
                        --trace-expand --trace-format=json-v1 "--trace-redirect=${trace}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(DEFINED EXPECT_ERROR)
  if(rc EQUAL 0)
    message(FATAL_ERROR "configuring ${SOURCE} succeeded; expected an error matching '${EXPECT_ERROR}':\n${log}")
  elseif(NOT log MATCHES "${EXPECT_ERROR}")
    message(FATAL_ERROR "configuring ${SOURCE} failed, but not with '${EXPECT_ERROR}':\n${log}")
  endif()
  message(STATUS "configuring failed as expected:\n${log}")
  return()
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring ${SOURCE} against ${PREFIX} failed (${rc}) with ${options}:\n${log}")
endif()
file(STRINGS "${trace}" lookups REGEX "\"cmd\":\"find_package\"")
set(looked_for "")
foreach(lookup IN LISTS lookups)
  if(lookup MATCHES "^{\"args\":\\[\"([^\"]+)\"")
    list(APPEND looked_for ${CMAKE_MATCH_1})
  endif()
endforeach()
list(REMOVE_DUPLICATES looked_for)
string(REPLACE ";" ", " looked_for_text "${looked_for}")
message(STATUS "packages looked for: ${looked_for_text}")
foreach(package IN LISTS disable)
  if(package IN_LIST looked_for)
    message(FATAL_ERROR "configuring ${SOURCE} looked for ${package}, which it must not need (trace: ${trace})")
  endif()
endforeach()
if(NOT "ffdkit" IN_LIST looked_for)
  message(FATAL_ERROR "the trace ${trace} shows no find_package(ffdkit): the check above saw nothing")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${BINARY}" RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building ${SOURCE} failed (${rc}):\n${log}")
endif()
execute_process(COMMAND "${BINARY}/consumer" ${run_args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "${BINARY}/consumer ${run_args}:\n${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the consumer failed (${rc})")
endif()
