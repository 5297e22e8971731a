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
