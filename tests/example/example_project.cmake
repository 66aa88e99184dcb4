# The example user project (examples/user_project) against the installed xshade, from nothing:
# install this build into a fresh prefix, configure the example in a fresh build folder with only
# that prefix to find xshade by, build it and run its CTest tests. Fails on the first step that
# fails, and when the example's tests are not the installed xshade's or do not all pass.
#
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P example_project.cmake
foreach(variable BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "example_project.cmake needs -D${variable}=...")
  endif()
endforeach()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message("---- ${what}\n${output}")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${what} failed (${code})")
  endif()
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
set(example_build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})

run_step("install xshade into ${prefix}" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The installed binary reads its own shader library: the prelude include exists only there.
file(WRITE ${WORK_DIR}/uses_prelude.hlsl
  "#include \"include/xshade_prelude.hlsl\"\n#pragma fragment frag\nfixed4 frag() : SV_Target { return fixed4(UNITY_PI, 0, 0, 1); }\n")
run_step("the installed xshade compiles against its installed library"
  ${prefix}/bin/xshade compile ${WORK_DIR}/uses_prelude.hlsl --target gl)

run_step("configure the example" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/user_project -B ${example_build} -G Ninja
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
run_step("build the example" ${CMAKE_COMMAND} --build ${example_build})

# Every test runs the installed binary, not this build's.
run_step("list the example's tests" ${CMAKE_CTEST_COMMAND} --test-dir ${example_build} --show-only=json-v1)
string(JSON test_count LENGTH "${step_output}" tests)
if(test_count EQUAL 0)
  message(FATAL_ERROR "the example registered no tests")
endif()
math(EXPR last "${test_count} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${step_output}" tests ${i} name)
  string(JSON program GET "${step_output}" tests ${i} command 0)
  # The one test that runs no xshade: clearing the earlier run's report folders (cmake -E rm).
  if(name MATCHES "\\.report_start$" AND program STREQUAL "${CMAKE_COMMAND}")
    continue()
  endif()
  if(NOT program STREQUAL "${prefix}/bin/xshade")
    message(FATAL_ERROR "test ${name} runs ${program}, not the installed ${prefix}/bin/xshade")
  endif()
endforeach()

run_step("test the example" ${CMAKE_CTEST_COMMAND} --test-dir ${example_build} --output-on-failure)
if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of ${test_count}")
  message(FATAL_ERROR "not every one of the example's ${test_count} tests passed")
endif()
# CTest counts a skipped test among the passed ones; a run that skipped them checked nothing.
if(step_output MATCHES "did not run" OR step_output MATCHES "\\*\\*\\*Skipped")
  message(FATAL_ERROR "some of the example's tests were skipped, so they checked nothing")
endif()
# The CTest run's own report: every test's merged into one (xshade.report).
set(merged ${example_build}/xshade-report/results.json)
if(NOT EXISTS ${merged})
  message(FATAL_ERROR "the example's CTest run left no merged report (${merged})")
endif()
file(READ ${merged} merged_json)
string(JSON merged_scenes GET "${merged_json}" scene_counts total)
string(JSON merged_passed GET "${merged_json}" scene_counts pass)
if(NOT merged_scenes EQUAL 1 OR NOT merged_passed EQUAL 1)
  message(FATAL_ERROR "the merged report holds ${merged_scenes} scenes, ${merged_passed} passed; the example has 1")
endif()
