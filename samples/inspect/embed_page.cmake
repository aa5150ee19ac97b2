# Writes OUT, a C++ file holding the inspector page's HTML, CSS, inflater and script (HTML, CSS,
# INFLATE, JS) as raw string literals (loom::inspect::assets in inspect_page.cpp). Run at build time by
# samples/inspect/CMakeLists.txt whenever one of the files changes.
set(delimiter "loom_page")
set(text "// Generated from samples/inspect/page/ by embed_page.cmake; do not edit.\nnamespace loom::inspect::assets {\n")
foreach(part HTML CSS INFLATE JS)
  file(READ "${${part}}" content)
  # A raw string ends at )delimiter" : a file containing it would end the literal early.
  string(FIND "${content}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${${part}} contains )${delimiter}\" and cannot be embedded as a raw string")
  endif()
  string(APPEND text "extern const char* const k${part};\nconst char* const k${part} = R\"${delimiter}(${content})${delimiter}\";\n")
endforeach()
string(APPEND text "}  // namespace loom::inspect::assets\n")
# Rewritten only when it changes, so that an unchanged page recompiles nothing.
file(WRITE "${OUT}.new" "${text}")
file(COPY_FILE "${OUT}.new" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.new")
