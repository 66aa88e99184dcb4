# Writes OUTPUT, a C++ header holding text files as raw string literals, so that an installed
# xshade has its pages' scripts and style without finding its source files.
#   cmake -DOUTPUT=assets.h "-DTEXTS=kViewerScript=viewer.js;kViewerStyle=viewer.css" -P embed_text.cmake
set(delimiter "xshade_text")
set(body "")
set(sources "")
foreach(entry IN LISTS TEXTS)
  string(FIND "${entry}" "=" equals)
  string(SUBSTRING "${entry}" 0 ${equals} name)
  math(EXPR after "${equals} + 1")
  string(SUBSTRING "${entry}" ${after} -1 file)
  file(READ "${file}" text)
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "embed_text.cmake: ${file} holds the raw string's end, )${delimiter}\"")
  endif()
  get_filename_component(base "${file}" NAME)
  list(APPEND sources "${base}")
  string(APPEND body "inline constexpr std::string_view ${name} = R\"${delimiter}(${text})${delimiter}\";\n")
endforeach()
list(JOIN sources ", " sources)
file(WRITE "${OUTPUT}.tmp"
  "// Made by cmake/embed_text.cmake from ${sources}: do not edit.\n"
  "#pragma once\n#include <string_view>\nnamespace xshade::harness {\n${body}}  // namespace xshade::harness\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
