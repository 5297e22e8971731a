# SPDX-License-Identifier: MIT
# posemorph-view's numeric and placement options: each bad value is refused
# with exit status 2 and a message naming the option, before any rendering.
foreach(case
    "--transform;rotate=abc|--transform wants"
    "--transform;scale=0|--transform wants"
    "--transform;move=1e400:0|--transform wants"
    "--transform;spin=3|--transform wants"
    "--camera;0,0|--camera wants"
    "--camera;0,0,1000|--camera wants"
    "--camera;nan,0,1|--camera wants"
    "--frames;-1|--frames wants"
    "--sigma;abc|--sigma wants"
    "--sigma;1.5|--sigma wants"
    "--crowd;0|--crowd wants"
    "--crowd;12x|--crowd wants"
    "--drawings;9|--drawings wants"
    "--blend;soft|--blend wants"
    "--time;inf|--time wants"
    "--tint;1,1|--tint wants"
    "--tint;1,1,2|--tint wants"
    "--tint;1,nan,1,1|--tint wants"
    "--part-opacity;arm|--part-opacity wants"
    "--part-opacity;arm=1.5|--part-opacity wants"
    "--fps;0|--fps wants")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 option)
  list(GET parts 1 value)
  list(GET parts 2 expected)
  execute_process(COMMAND ${VIEW} ${RIG} --headless -o ${WORK}/never.png ${option} ${value}
                  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT status EQUAL 2)
    message(FATAL_ERROR "${option} ${value}: expected exit status 2, got '${status}' (${err})")
  endif()
  if(NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${option} ${value}: expected '${expected}' in: ${err}")
  endif()
  if(EXISTS ${WORK}/never.png)
    message(FATAL_ERROR "${option} ${value}: a refused option still wrote a frame")
  endif()
endforeach()

# --hide-part and --part-opacity on a rig without parts: exit status 1, the rig named, no frame.
execute_process(COMMAND ${VIEW} ${RIG} --headless -o ${WORK}/never.png --part-opacity arm=0.5
                RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT status EQUAL 1 OR NOT err MATCHES "pip.pmrig: has no parts \\(--part-opacity\\)" OR EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "--part-opacity arm=0.5: expected exit status 1 and 'has no parts', got '${status}' (${err})")
endif()
execute_process(COMMAND ${VIEW} ${RIG} --headless -o ${WORK}/never.png --hide-part arm
                RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT status EQUAL 1 OR NOT err MATCHES "pip.pmrig: has no parts, so --hide-part has nothing to hide")
  message(FATAL_ERROR "--hide-part arm: expected exit status 1 and 'has no parts', got '${status}' (${err})")
endif()
if(EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "--hide-part arm: a refused option still wrote a frame")
endif()

# --watch: a description, for the window; each misuse one line, exit status 2.
foreach(case
    "${RIG};--watch|--watch takes a rig description \\(RIG.json\\), not a baked rig"
    "${WORK}/x.json;--watch;--headless;-o;${WORK}/never.png|--watch is for the window \\(not --headless\\)"
    "${WORK}/x.json;--watch;--images;${WORK}|--watch reads the drawings from the description's folder"
    "${RIG};--rebakes;2|--rebakes goes with --watch and --smoke-test"
    "${RIG};--rebakes;0|--rebakes wants a count in 1..1000")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_BACK parts expected)
  execute_process(COMMAND ${VIEW} ${parts} RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT status EQUAL 2 OR NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${parts}: expected exit status 2 and '${expected}', got '${status}' (${err})")
  endif()
endforeach()
# A description that does not bake: the bake's message, exit status 1, no window.
file(WRITE ${WORK}/broken.json "{\"posemorph\": 1, \"poses\": []}")
execute_process(COMMAND ${VIEW} ${WORK}/broken.json --watch RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT status EQUAL 1 OR NOT err MATCHES "posemorph-view: error: ${WORK}/broken.json: ")
  message(FATAL_ERROR "--watch broken.json: expected exit status 1 and the bake's message, got '${status}' (${err})")
endif()
