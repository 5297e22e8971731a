# SPDX-License-Identifier: MIT
# posemorph-view --inputs on Pell with a face: each bad timeline is refused
# with exit status 1 and one line naming the entry and what it wants, and no
# frame is written; --inputs on a rig without a state machine says so.
foreach(case
    "${FACE}|0:jump|the rig's state machine has no input \"jump\" \\(wave, sway, talking, looking, gaze, ghost, vanish\\)"
    "${FACE}|x:wave|--inputs entry \"x:wave\": wants TIME:NAME\\[=VALUE\\]"
    "${FACE}|-1:wave|--inputs entry \"-1:wave\": wants TIME:NAME"
    "${FACE}|1:wave=false|\"wave\" is a trigger: NAME \\(or NAME=true\\) fires it"
    "${FACE}|1:talking=maybe|\"talking\" is a bool: NAME, !NAME or NAME=true"
    "${FACE}|1:sway|\"sway\" is a number: NAME=VALUE"
    "${FACE}|1:gaze=1|\"gaze\" is a point: NAME=X,Y"
    "${FACE}|1:sway=nan|\"sway\" is a number"
    "${PIP}|0:wave|--inputs needs a rig with a state machine")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 rig)
  list(GET parts 1 timeline)
  list(GET parts 2 expected)
  execute_process(COMMAND ${VIEW} ${rig} --headless -o ${WORK}/never.png --inputs ${timeline}
                  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT status EQUAL 1)
    message(FATAL_ERROR "--inputs ${timeline}: expected exit status 1, got '${status}' (${err})")
  endif()
  if(NOT err MATCHES "${expected}")
    message(FATAL_ERROR "--inputs ${timeline}: expected '${expected}' in: ${err}")
  endif()
  if(EXISTS ${WORK}/never.png)
    message(FATAL_ERROR "--inputs ${timeline}: a refused timeline still wrote a frame")
  endif()
endforeach()
