# Configures, builds and runs the outside project (consumer/) for one package test:
#   cmake -DSOURCE=<consumer> -DBINARY=<dir> -DGENERATOR=<generator> -DRUN=<program>
#         [-DTARGET=<target>] [-DOPTIONS=<-Da=b|-Dc=d|...>] -P build_consumer.cmake
# OPTIONS are cache options separated by '|' (a ';' would split the test's command line). The
# build uses two jobs, like every build on the project's two-core machines.
string(REPLACE "|" ";" options "${OPTIONS}")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${BINARY}" -G "${GENERATOR}" ${options}
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "configuring ${SOURCE} failed (${result})")
endif()
set(target_args "")
if(TARGET)
  set(target_args --target "${TARGET}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BINARY}" --parallel 2 ${target_args} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "building ${SOURCE} failed (${result})")
endif()
execute_process(COMMAND "${BINARY}/${RUN}" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${RUN} failed (${result})")
endif()
