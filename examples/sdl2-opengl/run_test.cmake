# SPDX-License-Identifier: MIT
# The SDL2 + OpenGL example under Xvfb (Mesa's llvmpipe): its frame of Pip at
# a pose-space point against posemorph-view's (lavapipe) at the same point,
# the same tinted and half transparent, Pell with a face (parts and
# attachments, drawn by integrations/opengl step by step) against the
# viewer's, a crowd of 200 on a path, and its messages for bad drawings.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(run ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${RIG})

execute_process(COMMAND ${run} --images ${IMAGES} --at 0.5,0.5 --size 256x256 --frames 3 --screenshot ${WORK}/sdl2.png
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the example failed (${status})")
endif()
execute_process(COMMAND ${VIEW} ${RIG} --images ${IMAGES} --headless --at 0.5,0.5 --size 256x256 -o ${WORK}/view.png
                RESULT_VARIABLE status)
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2.png ${WORK}/view.png 0.01 RESULT_VARIABLE status OUTPUT_VARIABLE out)
message("SDL2 + OpenGL against posemorph-view at (0.5, 0.5): ${out}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the example's frame differs from the viewer's")
endif()
file(COPY ${WORK}/sdl2.png DESTINATION ${SHOTS})

# Tinted and half transparent: both renderers apply the draw list's colour.
execute_process(COMMAND ${run} --images ${IMAGES} --at 0.5,0.5 --size 256x256 --tint 1,0.5,0.25,0.6 --frames 3
                        --screenshot ${WORK}/sdl2-tint.png RESULT_VARIABLE status)
execute_process(COMMAND ${VIEW} ${RIG} --images ${IMAGES} --headless --at 0.5,0.5 --size 256x256 --tint 1,0.5,0.25,0.6
                        -o ${WORK}/view-tint.png RESULT_VARIABLE view_status)
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2-tint.png ${WORK}/view-tint.png 0.01 RESULT_VARIABLE compared
                OUTPUT_VARIABLE out)
message("SDL2 + OpenGL against posemorph-view, tinted 1,0.5,0.25 at opacity 0.6: ${out}")
if(NOT status EQUAL 0 OR NOT view_status EQUAL 0 OR NOT compared EQUAL 0)
  message(FATAL_ERROR "the tinted frames differ (${status}, ${view_status}, ${compared})")
endif()
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2-tint.png ${WORK}/sdl2.png 0.01 RESULT_VARIABLE same OUTPUT_VARIABLE out)
if(same EQUAL 0)
  message(FATAL_ERROR "the tint changed nothing: ${out}")
endif()

# A layered character with attachments: 7 draw calls (4 body parts, 3 face parts), the viewer's picture.
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${FACE_RIG} --images ${FACE_IMAGES}
                        --at 0.3,0.2 --size 256x256 --frames 3 --screenshot ${WORK}/sdl2-face.png
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
execute_process(COMMAND ${VIEW} ${FACE_RIG} --images ${FACE_IMAGES} --headless --at 0.3,0.2 --size 256x256
                        -o ${WORK}/view-face.png RESULT_VARIABLE view_status)
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2-face.png ${WORK}/view-face.png 0.01 RESULT_VARIABLE compared
                OUTPUT_VARIABLE compare_out)
message("SDL2 + OpenGL against posemorph-view, Pell with a face at (0.3, 0.2): ${compare_out}${out}${err}")
if(NOT status EQUAL 0 OR NOT view_status EQUAL 0 OR NOT compared EQUAL 0 OR NOT out MATCHES "7 draw calls a frame")
  message(FATAL_ERROR "Pell with a face differs or draws otherwise (${status}, ${view_status}, ${compared})")
endif()

execute_process(COMMAND ${run} --images ${IMAGES} --crowd 200 --size 800x600 --frames 120 --screenshot ${WORK}/crowd.png
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status EQUAL 0 OR NOT out MATCHES "120 frames of 200 character")
  message(FATAL_ERROR "the crowd failed (${status})")
endif()
file(COPY ${WORK}/crowd.png DESTINATION ${SHOTS})

# Bad drawings: one missing, one of another size. One message naming the file, exit status 1.
file(COPY ${IMAGES}/ DESTINATION ${WORK}/missing)
file(REMOVE ${WORK}/missing/wave.png)
file(COPY ${IMAGES}/ DESTINATION ${WORK}/resized)
configure_file(${WRONG_SIZE_PNG} ${WORK}/resized/rest.png COPYONLY)
foreach(case "missing|missing/wave.png: cannot read the PNG" "resized|resized/rest.png: the drawing is [0-9]+x[0-9]+, the rig was baked from 256x256")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 folder)
  list(GET parts 1 expected)
  execute_process(COMMAND ${run} --images ${WORK}/${folder} --frames 1 RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 1 OR NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${folder}: expected status 1 and '${expected}', got ${status}: ${err}")
  endif()
endforeach()
