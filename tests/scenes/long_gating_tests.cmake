# Read by CTest after gating_tests' discovered tests (tests/scenes/CMakeLists.txt): every fixed
# scene rendered twice (about 25 s) and a bless killed after each of its steps (about 20 s).
foreach(test IN LISTS gating_tests_TESTS)
  if(test MATCHES "^(WorkerCount\\.|BlessCommit\\.AKill)")
    set_tests_properties("${test}" PROPERTIES COST 250)
  endif()
endforeach()
