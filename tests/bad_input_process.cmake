# SPDX-License-Identifier: MIT
# The real process: a flipped triangle gives exit status 1, one message on
# stderr naming the file, pose and triangle, and no output file.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/flipped.json [=[{"posemorph": 1, "triangles": [[0, 1, 2]],
 "poses": [{"name": "up", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]]},
           {"name": "down", "point": [1, 0], "vertices": [[0, 0], [1, 0], [0, -1]]}]}]=])
execute_process(COMMAND ${BAKE} ${WORK}/flipped.json -o ${WORK}/flipped.pmrig
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got '${status}'")
endif()
if(NOT err MATCHES "flipped.json: pose 'down' \\(index 1\\): triangle 0 is flipped")
  message(FATAL_ERROR "unexpected message: ${err}")
endif()
if(EXISTS ${WORK}/flipped.pmrig)
  message(FATAL_ERROR "a failed bake left an output file")
endif()
file(GLOB leftovers ${WORK}/.flipped*)
if(leftovers)
  message(FATAL_ERROR "a failed bake left temporary files: ${leftovers}")
endif()

# The encoding options: a bad --precision is a usage error (status 2), a bad
# bake.max_error in the description names the key; neither writes anything.
file(WRITE ${WORK}/ok.json [=[{"posemorph": 1, "triangles": [[0, 1, 2]],
 "poses": [{"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]]},
           {"name": "b", "point": [1, 0], "vertices": [[0, 0], [1, 0], [0, 1.5]]}]}]=])
execute_process(COMMAND ${BAKE} ${WORK}/ok.json --precision half -o ${WORK}/ok.pmrig
                RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "--precision must be compact or exact" OR EXISTS ${WORK}/ok.pmrig)
  message(FATAL_ERROR "--precision half: status '${status}', message: ${err}")
endif()
file(WRITE ${WORK}/budget.json [=[{"posemorph": 1, "bake": {"max_error": 0}, "triangles": [[0, 1, 2]],
 "poses": [{"name": "a", "point": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]]},
           {"name": "b", "point": [1, 0], "vertices": [[0, 0], [1, 0], [0, 1.5]]}]}]=])
execute_process(COMMAND ${BAKE} ${WORK}/budget.json -o ${WORK}/budget.pmrig RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 1 OR NOT err MATCHES "budget.json: bake.max_error: must be in \\[1e-6, 10\\] pixels" OR EXISTS ${WORK}/budget.pmrig)
  message(FATAL_ERROR "bake.max_error 0: status '${status}', message: ${err}")
endif()
# The same description bakes compact by default and exactly on request.
execute_process(COMMAND ${BAKE} ${WORK}/ok.json -o ${WORK}/ok.pmrig RESULT_VARIABLE status OUTPUT_VARIABLE out)
if(NOT status EQUAL 0 OR NOT out MATCHES "compact encoding: [0-9]+ bytes \\(exact [0-9]+\\); max vertex error")
  message(FATAL_ERROR "compact bake: status '${status}', output: ${out}")
endif()
execute_process(COMMAND ${BAKE} ${WORK}/ok.json --precision exact -o ${WORK}/ok-exact.pmrig RESULT_VARIABLE status OUTPUT_VARIABLE out)
if(NOT status EQUAL 0 OR out MATCHES "compact encoding")
  message(FATAL_ERROR "exact bake: status '${status}', output: ${out}")
endif()

