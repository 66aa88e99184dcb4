# Writes OUTPUT, a C++ header holding viewer.js and viewer.css as raw string literals, so that the
# installed xshade writes self-contained report pages without finding its source files.
#   cmake -DSCRIPT=viewer.js -DSTYLE=viewer.css -DOUTPUT=viewer_assets.h -P embed_viewer.cmake
set(delimiter "xshade_viewer")
file(READ "${SCRIPT}" script)
file(READ "${STYLE}" style)
foreach(text IN ITEMS script style)
  string(FIND "${${text}}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "embed_viewer.cmake: the ${text} holds the raw string's end, )${delimiter}\"")
  endif()
endforeach()
file(WRITE "${OUTPUT}.tmp"
  "// Made by harness/report/viewer/embed_viewer.cmake from viewer.js and viewer.css: do not edit.\n"
  "#pragma once\n#include <string_view>\nnamespace xshade::harness {\n"
  "inline constexpr std::string_view kViewerScript = R\"${delimiter}(${script})${delimiter}\";\n"
  "inline constexpr std::string_view kViewerStyle = R\"${delimiter}(${style})${delimiter}\";\n"
  "}  // namespace xshade::harness\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
