# Plans GRAPH with PLAN_TOOL, writes its DOT, and renders it to SVG with Graphviz (DOT):
# fails when either step fails or the SVG does not show the graph's passes.
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${PLAN_TOOL}" "${GRAPH}" --dot "${OUT}/plan.dot"
                RESULT_VARIABLE plan_result OUTPUT_QUIET ERROR_VARIABLE plan_error)
if(NOT plan_result EQUAL 0)
  message(FATAL_ERROR "loom-plan failed (${plan_result}): ${plan_error}")
endif()
execute_process(COMMAND "${DOT}" -Tsvg "${OUT}/plan.dot" -o "${OUT}/plan.svg"
                RESULT_VARIABLE dot_result ERROR_VARIABLE dot_error)
if(NOT dot_result EQUAL 0 OR NOT dot_error STREQUAL "")
  message(FATAL_ERROR "Graphviz rejected ${OUT}/plan.dot (${dot_result}): ${dot_error}")
endif()
# Every pass of the graph file appears as text in the picture.
file(READ "${GRAPH}" graph_json)
string(JSON pass_count LENGTH "${graph_json}" passes)
math(EXPR last "${pass_count} - 1")
file(READ "${OUT}/plan.svg" svg)
foreach(i RANGE ${last})
  string(JSON name GET "${graph_json}" passes ${i} name)
  string(FIND "${svg}" "${name}" found)
  if(found EQUAL -1)
    message(FATAL_ERROR "pass '${name}' is missing from the rendered plan ${OUT}/plan.svg")
  endif()
endforeach()
