# xshade_add_scene_tests: a project's scenes as CTest tests, one per scene and lane, plus one per
# scene that holds its lanes against each other.
#
#   xshade_add_scene_tests(SCENES dir GOLDEN dir
#                          [SHADERS dir...]        # searched before xshade's shader library
#                          [LANES gl vk vk-hlsl]   # default: all three
#                          [PREFIX xshade]         # tests are PREFIX.SCENE.LANE and PREFIX.SCENE.all_lanes
#                          [LABELS label...]       # CTest labels (default: xshade)
#                          [REPORT dir]            # default: ${CMAKE_CURRENT_BINARY_DIR}/xshade-report
#                          [CACHE dir]             # compiled shaders; default: ${CMAKE_BINARY_DIR}/xshade-cache
#                          [ENVIRONMENT VAR=value...])  # set for every test (CTest's ENVIRONMENT)
#
# Relative folders are relative to the calling CMakeLists.txt. Each lane's test runs `xshade run
# SCENE --lane LANE` with exactly these folders (no project file is read), writes its own report
# folder (REPORT/tests/TEST), and passes only when xshade does: the scene matches its golden and
# renders finite and deterministic. all_lanes holds what the lane tests rendered against each
# other (xshade report merge --cross-lane), rendering nothing again; CTest runs the lane tests
# first. A lane a scene does not list is
# reported as skipped. After the tests, PREFIX.report merges what this CTest run wrote into one
# report, REPORT/index.html with its junit.xml and results.json (xshade report merge); before
# them, PREFIX.report_start clears the earlier run's folders, so the merge holds this run alone.
# The scene files are found when CMake configures; adding one re-runs the configuration on the
# next build.
function(xshade_add_scene_tests)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "" "SCENES;GOLDEN;PREFIX;REPORT;CACHE" "SHADERS;LANES;LABELS;ENVIRONMENT")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "xshade_add_scene_tests: unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  foreach(required SCENES GOLDEN)
    if(NOT ARG_${required})
      message(FATAL_ERROR "xshade_add_scene_tests: ${required} <dir> is required")
    endif()
  endforeach()
  if(NOT TARGET xshade::xshade)
    message(FATAL_ERROR "xshade_add_scene_tests: no xshade::xshade target; call find_package(xshade) first")
  endif()
  if(NOT ARG_LANES)
    set(ARG_LANES gl vk vk-hlsl)
  endif()
  foreach(lane IN LISTS ARG_LANES)
    if(NOT lane MATCHES "^(gl|vk|vk-hlsl)$")
      message(FATAL_ERROR "xshade_add_scene_tests: unknown lane '${lane}' (lanes: gl, vk, vk-hlsl)")
    endif()
  endforeach()
  if(NOT ARG_PREFIX)
    set(ARG_PREFIX xshade)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS xshade)
  endif()
  if(NOT ARG_REPORT)
    set(ARG_REPORT ${CMAKE_CURRENT_BINARY_DIR}/xshade-report)
  endif()
  if(NOT ARG_CACHE)
    set(ARG_CACHE ${CMAKE_BINARY_DIR}/xshade-cache)
  endif()

  get_filename_component(scenes "${ARG_SCENES}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(golden "${ARG_GOLDEN}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  set(folders --no-project --scenes "${scenes}" --golden "${golden}")
  foreach(shaders IN LISTS ARG_SHADERS)
    get_filename_component(shaders "${shaders}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    if(NOT IS_DIRECTORY "${shaders}")
      message(FATAL_ERROR "xshade_add_scene_tests: SHADERS folder ${shaders} does not exist")
    endif()
    list(APPEND folders --shaders "${shaders}")
  endforeach()

  file(GLOB scene_files CONFIGURE_DEPENDS "${scenes}/*.toml")
  if(NOT scene_files)
    message(FATAL_ERROR "xshade_add_scene_tests: no scenes (*.toml) in ${scenes}")
  endif()
  list(SORT scene_files)
  list(LENGTH ARG_LANES lane_count)
  # Matches xshade's message for a lane the scene does not list (and nothing else it prints).
  set(skipped "skipped: the scene runs on .*, none of the lanes asked for")
  set(fixture ${ARG_PREFIX}_report)
  foreach(scene_file IN LISTS scene_files)
    get_filename_component(scene "${scene_file}" NAME_WE)
    set(lane_reports)
    foreach(lane IN LISTS ARG_LANES)
      add_test(NAME ${ARG_PREFIX}.${scene}.${lane}
               COMMAND xshade::xshade run ${scene} --lane ${lane} ${folders}
                       --report "${ARG_REPORT}/tests/${scene}.${lane}" --cache "${ARG_CACHE}")
      set_tests_properties(${ARG_PREFIX}.${scene}.${lane} PROPERTIES LABELS "${ARG_LABELS}"
                           SKIP_REGULAR_EXPRESSION "${skipped}" FIXTURES_REQUIRED ${fixture}
                           FIXTURES_SETUP ${ARG_PREFIX}_${scene}_lanes ENVIRONMENT "${ARG_ENVIRONMENT}")
      list(APPEND lane_reports "${ARG_REPORT}/tests/${scene}.${lane}")
    endforeach()
    # The lanes against each other from what the lane tests rendered, not rendered again: their
    # reports merged, the lanes compared as one run of all of them would (CTest runs the lane
    # tests first, also under -R).
    if(lane_count GREATER 1)
      add_test(NAME ${ARG_PREFIX}.${scene}.all_lanes
               COMMAND xshade::xshade report merge ${lane_reports} --out "${ARG_REPORT}/tests/${scene}"
                       --cross-lane --exit-code)
      set_tests_properties(${ARG_PREFIX}.${scene}.all_lanes PROPERTIES LABELS "${ARG_LABELS}"
                           FIXTURES_REQUIRED "${fixture};${ARG_PREFIX}_${scene}_lanes"
                           ENVIRONMENT "${ARG_ENVIRONMENT}")
    endif()
  endforeach()
  # One report of the whole CTest run: the per-test folders cleared before, merged after (CTest
  # runs a fixture's cleanup whether its tests passed or not, and with any -R that picks one).
  add_test(NAME ${ARG_PREFIX}.report_start COMMAND ${CMAKE_COMMAND} -E rm -rf "${ARG_REPORT}/tests")
  add_test(NAME ${ARG_PREFIX}.report
           COMMAND xshade::xshade report merge "${ARG_REPORT}/tests" --out "${ARG_REPORT}")
  set_tests_properties(${ARG_PREFIX}.report_start PROPERTIES LABELS "${ARG_LABELS}" FIXTURES_SETUP ${fixture})
  set_tests_properties(${ARG_PREFIX}.report PROPERTIES LABELS "${ARG_LABELS}" FIXTURES_CLEANUP ${fixture}
                       ENVIRONMENT "${ARG_ENVIRONMENT}")
endfunction()
