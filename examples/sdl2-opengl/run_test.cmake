# SPDX-License-Identifier: MIT
# The SDL2 + OpenGL example under Xvfb (Mesa's llvmpipe): its frame of Pip at
# a pose-space point against posemorph-view's (lavapipe) at the same point,
# the same tinted and half transparent, Pell with a face (parts and
# attachments, drawn by integrations/opengl step by step) against the
# viewer's, a crowd of 200 on a path, Pip baked without an atlas (its
# drawings one texture each) against Pip with one, and its messages for a
# bad atlas page and bad drawings.
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

# A layered character with attachments: 4 draw calls (the body's 4 parts in one, each face part's list in one),
# one texture (its atlas), the viewer's picture.
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${FACE_RIG} --images ${FACE_IMAGES}
                        --at 0.3,0.2 --size 256x256 --frames 3 --screenshot ${WORK}/sdl2-face.png
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
execute_process(COMMAND ${VIEW} ${FACE_RIG} --images ${FACE_IMAGES} --headless --at 0.3,0.2 --size 256x256
                        -o ${WORK}/view-face.png RESULT_VARIABLE view_status)
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2-face.png ${WORK}/view-face.png 0.01 RESULT_VARIABLE compared
                OUTPUT_VARIABLE compare_out)
message("SDL2 + OpenGL against posemorph-view, Pell with a face at (0.3, 0.2): ${compare_out}${out}${err}")
if(NOT status EQUAL 0 OR NOT view_status EQUAL 0 OR NOT compared EQUAL 0 OR NOT out MATCHES "4 draw calls a frame"
   OR NOT out MATCHES "1 texture\\(s\\) bound, 1 page\\(s\\) \\(an atlas\\)")
  message(FATAL_ERROR "Pell with a face differs or draws otherwise (${status}, ${view_status}, ${compared})")
endif()

execute_process(COMMAND ${run} --images ${IMAGES} --crowd 200 --size 800x600 --frames 120 --screenshot ${WORK}/crowd.png
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status EQUAL 0 OR NOT out MATCHES "120 frames of 200 character")
  message(FATAL_ERROR "the crowd failed (${status})")
endif()
file(COPY ${WORK}/crowd.png DESTINATION ${SHOTS})

# Pip without an atlas: each drawing its own texture, the same picture.
file(MAKE_DIRECTORY ${WORK}/drawn)
execute_process(COMMAND ${BAKE} ${IMAGES}/pip.json --precision exact --no-atlas -o ${WORK}/drawn/pip.pmrig
                RESULT_VARIABLE status OUTPUT_QUIET)
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${WORK}/drawn/pip.pmrig --images ${IMAGES}
                        --at 0.5,0.5 --size 256x256 --frames 3 --screenshot ${WORK}/sdl2-drawn.png
                RESULT_VARIABLE drawn_status OUTPUT_VARIABLE out)
execute_process(COMMAND ${COMPARE} ${WORK}/sdl2-drawn.png ${WORK}/sdl2.png 0.01 RESULT_VARIABLE compared
                OUTPUT_VARIABLE compare_out)
message("Pip without an atlas against Pip with one: ${compare_out}${out}")
if(NOT status EQUAL 0 OR NOT drawn_status EQUAL 0 OR NOT compared EQUAL 0 OR NOT out MATCHES "5 page\\(s\\) \\(one per drawing\\)")
  message(FATAL_ERROR "Pip draws otherwise without an atlas (${status}, ${drawn_status}, ${compared})")
endif()
# And posemorph-view: Pip without an atlas against Pip with one.
execute_process(COMMAND ${VIEW} ${WORK}/drawn/pip.pmrig --images ${IMAGES} --headless --at 0.5,0.5 --size 256x256
                        -o ${WORK}/view-drawn.png RESULT_VARIABLE view_status)
execute_process(COMMAND ${COMPARE} ${WORK}/view-drawn.png ${WORK}/view.png 0.01 RESULT_VARIABLE compared
                OUTPUT_VARIABLE compare_out)
message("posemorph-view: Pip without an atlas against Pip with one: ${compare_out}")
if(NOT view_status EQUAL 0 OR NOT compared EQUAL 0)
  message(FATAL_ERROR "the viewer draws Pip otherwise without an atlas (${view_status}, ${compared})")
endif()

# A bad atlas page: missing, or of another size. One message naming the file, exit status 1.
get_filename_component(rig_name ${RIG} NAME)
get_filename_component(rig_stem ${RIG} NAME_WE)
file(MAKE_DIRECTORY ${WORK}/no-page ${WORK}/small-page)
configure_file(${RIG} ${WORK}/no-page/${rig_name} COPYONLY)
configure_file(${RIG} ${WORK}/small-page/${rig_name} COPYONLY)
configure_file(${WRONG_SIZE_PNG} ${WORK}/small-page/${rig_stem}.page0.png COPYONLY)
foreach(case "no-page|no-page/${rig_stem}.page0.png: cannot read the PNG"
             "small-page|small-page/${rig_stem}.page0.png: the atlas page is [0-9]+x[0-9]+, the rig was baked with 512x512")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 folder)
  list(GET parts 1 expected)
  execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${WORK}/${folder}/${rig_name}
                          --images ${IMAGES} --frames 1 RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 1 OR NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${folder}: expected status 1 and '${expected}', got ${status}: ${err}")
  endif()
endforeach()

# Bad drawings of the rig without an atlas: one missing, one of another size.
file(COPY ${IMAGES}/ DESTINATION ${WORK}/missing)
file(REMOVE ${WORK}/missing/wave.png)
file(COPY ${IMAGES}/ DESTINATION ${WORK}/resized)
configure_file(${WRONG_SIZE_PNG} ${WORK}/resized/rest.png COPYONLY)
foreach(case "missing|missing/wave.png: cannot read the PNG" "resized|resized/rest.png: the drawing is [0-9]+x[0-9]+, the rig was baked from 256x256")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 folder)
  list(GET parts 1 expected)
  execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24" ${EXAMPLE} ${WORK}/drawn/pip.pmrig
                          --images ${WORK}/${folder} --frames 1 RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 1 OR NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${folder}: expected status 1 and '${expected}', got ${status}: ${err}")
  endif()
endforeach()
