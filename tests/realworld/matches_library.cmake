# A Unity .shader of examples/unity against xshade's own library material of the same formulas:
# SCENE (of SCENES, drawing the .shader) rendered on the gl lane, then `xshade diff` against
# REFERENCE (the library's golden of the same layout and values), held to 1 sRGB step on all
# but BUDGET of the pixels. Fails with the diff's report when they part.
foreach(variable XSHADE SCENES SCENE REFERENCE BUDGET WORK_DIR SHADERS)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "matches_library.cmake needs -D${variable}=...")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/golden")
# SHADERS: the shader folders, separated by '|' (a ';' would not survive add_test).
string(REPLACE "|" ";" shader_folders "${SHADERS}")
set(shader_options)
foreach(folder IN LISTS shader_folders)
  list(APPEND shader_options "--shaders=${folder}")
endforeach()
# The run has no golden of its own to compare (its exit code says so); the images are what counts.
execute_process(COMMAND "${XSHADE}" run --no-project --no-cache --lane gl --scenes "${SCENES}" ${shader_options}
                        --golden "${WORK_DIR}/golden" --report "${WORK_DIR}/report" "${SCENE}"
                OUTPUT_VARIABLE run_output ERROR_VARIABLE run_output)
if(NOT EXISTS "${WORK_DIR}/report/${SCENE}/gl.png")
  message(FATAL_ERROR "${SCENE} rendered no image on gl:\n${run_output}")
endif()
execute_process(COMMAND "${XSHADE}" diff "${WORK_DIR}/report/${SCENE}/gl.png" "${REFERENCE}" --tolerance 1 --budget ${BUDGET}
                RESULT_VARIABLE diff_result OUTPUT_VARIABLE diff_output ERROR_VARIABLE diff_output)
if(NOT diff_result EQUAL 0)
  message(FATAL_ERROR "${SCENE} parts from ${REFERENCE}:\n${diff_output}")
endif()
message(STATUS "${SCENE} matches ${REFERENCE}:\n${diff_output}")
