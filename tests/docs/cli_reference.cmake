# docs/cli.md is what `xshade --help` and `xshade VERB --help` print, verb by verb, so that the
# reference cannot drift from the binary.
#
#   cmake -DXSHADE=path/to/xshade -DREFERENCE=docs/cli.md -DMODE=check|write -P cli_reference.cmake
#
# check fails, naming the first verb that differs, when the file is not what the binary prints;
# write rewrites it (`cmake --build build --target cli_reference`).
foreach(variable XSHADE REFERENCE MODE)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "cli_reference.cmake needs -D${variable}=...")
  endif()
endforeach()

function(help_of out)
  execute_process(COMMAND ${XSHADE} ${ARGN} --help RESULT_VARIABLE code OUTPUT_VARIABLE text ERROR_VARIABLE errors)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "xshade ${ARGN} --help failed (${code}): ${errors}")
  endif()
  string(STRIP "${text}" text)
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

help_of(main_help)
# The verbs, from the main help's list (two spaces, the name, spaces, its description).
string(REGEX MATCH "Subcommands:\n.*" verb_lines "${main_help}")
string(REGEX MATCHALL "\n  [a-z]+ " verb_matches "${verb_lines}")
if(NOT verb_matches)
  message(FATAL_ERROR "xshade --help lists no subcommands")
endif()

set(markdown "# xshade command line\n\n")
string(APPEND markdown
  "<!-- Generated from xshade's own --help by tests/docs/cli_reference.cmake: edit the help texts in\n"
  "the verb's file (cli/VERB_command.cpp; shared options in cli/command_options.cpp), then\n"
  "`cmake --build build --target cli_reference`. The test\n"
  "docs.cli_reference_is_current fails when this file differs from what the binary prints. -->\n\n"
  "Every verb as `xshade VERB --help` prints it. Folders: [getting_started.md](getting_started.md);\n"
  "scene files: [scenes.md](scenes.md); the language: [hlsl_like.md](hlsl_like.md).\n\n"
  "## xshade\n\n```text\n${main_help}\n```\n")
foreach(match IN LISTS verb_matches)
  string(STRIP "${match}" verb)
  help_of(verb_help ${verb})
  string(APPEND markdown "\n## xshade ${verb}\n\n```text\n${verb_help}\n```\n")
  # A verb with verbs of its own (xshade report merge): each of those too.
  string(REGEX MATCH "Subcommands:\n.*" inner_lines "${verb_help}")
  string(REGEX MATCHALL "\n  [a-z]+ " inner_matches "${inner_lines}")
  foreach(inner_match IN LISTS inner_matches)
    string(STRIP "${inner_match}" inner)
    help_of(inner_help ${verb} ${inner})
    string(APPEND markdown "\n## xshade ${verb} ${inner}\n\n```text\n${inner_help}\n```\n")
  endforeach()
endforeach()

if(MODE STREQUAL "write")
  file(WRITE ${REFERENCE} "${markdown}")
  message(STATUS "wrote ${REFERENCE}")
  return()
endif()
if(NOT EXISTS ${REFERENCE})
  message(FATAL_ERROR "${REFERENCE} is missing; write it with `cmake --build build --target cli_reference`")
endif()
file(READ ${REFERENCE} current)
if(NOT current STREQUAL markdown)
  # Name the first section that differs, so the message says where to look.
  string(REGEX MATCHALL "\n## [^\n]+" headings "${markdown}")
  set(where "the introduction")
  foreach(heading IN LISTS headings)
    string(FIND "${markdown}" "${heading}" generated_at)
    string(SUBSTRING "${markdown}" 0 ${generated_at} generated_head)
    string(LENGTH "${generated_head}" head_length)
    string(SUBSTRING "${current}" 0 ${head_length} current_head)
    if(NOT current_head STREQUAL generated_head)
      break()
    endif()
    string(STRIP "${heading}" where)
  endforeach()
  message(FATAL_ERROR "${REFERENCE} is not what xshade --help prints (first difference in or after '${where}'); "
                      "rewrite it with `cmake --build build --target cli_reference` and review the change")
endif()
