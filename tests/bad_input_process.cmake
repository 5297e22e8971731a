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

# Inputs the bake reads only within limits, outputs it refuses to replace:
# one line naming the file and why, exit status 1, nothing written.
function(expect_refusal label expected)
  execute_process(COMMAND ${BAKE} ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCHALL "\n" lines "${err}")
  list(LENGTH lines line_count)
  if(NOT status EQUAL 1 OR NOT err MATCHES "${expected}" OR NOT line_count EQUAL 1)
    message(FATAL_ERROR "${label}: status '${status}', message: ${err}")
  endif()
endfunction()
expect_refusal("a device as the description" "/dev/zero: is not a regular file" /dev/zero -o ${WORK}/zero.pmrig)
execute_process(COMMAND mkfifo ${WORK}/pipe.json)
expect_refusal("a pipe as the description" "pipe.json: is not a regular file" ${WORK}/pipe.json -o ${WORK}/pipe.pmrig)
expect_refusal("a folder as the description" "bad-input: is not a regular file" ${WORK} -o ${WORK}/folder.pmrig)
execute_process(COMMAND truncate -s 65M ${WORK}/huge.json)
expect_refusal("a 65 MiB description" "huge.json: is 68157440 bytes, more than the limit of 67108864 for a rig description"
               ${WORK}/huge.json -o ${WORK}/huge.pmrig)
file(REMOVE ${WORK}/huge.json)
file(WRITE ${WORK}/mesh-from-device.json [=[{"posemorph": 1, "poses": [{"name": "a", "point": [0, 0], "mesh": "/dev/zero"},
 {"name": "b", "point": [1, 0], "mesh": "/dev/zero"}]}]=])
expect_refusal("a device as a mesh file" "/dev/zero: is not a regular file .*named in .*mesh-from-device.json"
               ${WORK}/mesh-from-device.json -o ${WORK}/mesh.pmrig)
file(COPY_FILE ${WORK}/ok.json ${WORK}/self.json)
expect_refusal("-o naming the input" "self.json: is the input .*self.json; refusing to overwrite it" ${WORK}/self.json -o ${WORK}/self.json)
file(READ ${WORK}/self.json after)
file(READ ${WORK}/ok.json before)
if(NOT after STREQUAL before)
  message(FATAL_ERROR "-o naming the input changed it")
endif()
expect_refusal("-o a device" "/dev/null: exists and is not a regular file" ${WORK}/ok.json -o /dev/null)
expect_refusal("-o a folder" "bad-input: is a directory" ${WORK}/ok.json -o ${WORK})
file(CREATE_LINK ${WORK}/ok.json ${WORK}/link.pmrig SYMBOLIC)
expect_refusal("-o a symbolic link" "link.pmrig: exists and is not a regular file" ${WORK}/ok.json -o ${WORK}/link.pmrig)
foreach(left zero.pmrig pipe.pmrig folder.pmrig huge.pmrig mesh.pmrig)
  if(EXISTS ${WORK}/${left})
    message(FATAL_ERROR "a refused bake wrote ${left}")
  endif()
endforeach()
# A 65-byte PNG whose header claims 8192 x 2049 pixels: refused from the
# header, before anything is decoded.
file(COPY_FILE ${DATA}/bomb-8192x2049.png ${WORK}/bomb.png)
file(WRITE ${WORK}/bomb.json [=[{"posemorph": 1, "poses": [
 {"name": "a", "point": [0, 0], "drawing": "bomb.png", "landmarks": [[0, 0], [10, 0], [10, 10]]},
 {"name": "b", "point": [1, 0], "drawing": "bomb.png", "landmarks": [[0, 0], [10, 0], [10, 10]]}]}]=])
expect_refusal("a decompression bomb" "bomb.json: pose 'a' \\(index 0\\): .*bomb.png: PNG size 8192 x 2049 is outside 1..16384 per side or above the limit of 16777216 pixels"
               ${WORK}/bomb.json -o ${WORK}/bomb.pmrig)

# Names that cannot be written are refused before any work: an empty -o, a
# file name beyond the 255 bytes a file system allows (the message shows
# the path shortened).
find_program(SH sh REQUIRED)  # CMake drops an empty argument: the shell passes it
execute_process(COMMAND ${SH} -c "exec \"$0\" \"$1\" -o ''" ${BAKE} ${WORK}/ok.json
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT status EQUAL 1 OR NOT err MATCHES "^posemorph-bake: error: cannot write: the output file name is empty\n$")
  message(FATAL_ERROR "-o '': status '${status}', message: ${err}")
endif()
string(REPEAT "n" 300 long)
expect_refusal("-o a 300-byte name" "\\.\\.\\. \\([0-9]+ bytes\\): cannot write: the file name is 300 bytes long; a file system allows 255"
               ${WORK}/ok.json -o ${WORK}/${long})
# A 250-byte name is written (its temporary's name is shortened to fit).
string(REPEAT "m" 250 fits)
execute_process(COMMAND ${BAKE} ${WORK}/ok.json -o ${WORK}/${fits} RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK}/${fits})
  message(FATAL_ERROR "a 250-byte name: status '${status}', message: ${err}")
endif()

# A write past the process's file-size limit (ulimit -f 1: 1024 bytes, less
# than the exact rig) fails with the system's cause, exit status 1, and
# leaves neither the file nor its temporary (SIGXFSZ would have ended the
# process before it could remove it).
execute_process(COMMAND ${SH} -c "ulimit -f 1 && exec \"$0\" \"$1\" --precision exact -o \"$2\"" ${BAKE}
                        ${WORK}/ok.json ${WORK}/limited.pmrig
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
file(GLOB leftovers ${WORK}/.limited*)
if(NOT status EQUAL 1 OR NOT err MATCHES "limited.pmrig: cannot write the file: File too large" OR EXISTS ${WORK}/limited.pmrig
   OR leftovers)
  message(FATAL_ERROR "ulimit -f 1: status '${status}', message: ${err}, left: ${leftovers}")
endif()
