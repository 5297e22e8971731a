# SPDX-License-Identifier: MIT
# Runs the receiver and the sender at the same time (execute_process runs
# the commands of one call concurrently) and checks both exit statuses and
# what they said. EXPECT: "match" (same rig: every frame bit for bit alike)
# or "refuse" (different rigs: the handshake stops both).
execute_process(
  COMMAND ${RECEIVER} ${RECEIVER_RIG} ${PORT}
  COMMAND ${SENDER} ${SENDER_RIG} ${PORT} ${PATH_NAME} 240
  RESULTS_VARIABLE statuses OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
message("${out}${err}")
if(EXPECT STREQUAL "match")
  if(NOT statuses STREQUAL "0;0")
    message(FATAL_ERROR "expected both peers to exit 0, got ${statuses}")
  endif()
  if(NOT out MATCHES "240 of 240 frames drawn bit for bit alike" OR NOT err MATCHES "drew 240 frames")
    message(FATAL_ERROR "the peers did not agree on every frame")
  endif()
else()
  if(NOT statuses STREQUAL "1;1")
    message(FATAL_ERROR "expected both peers to refuse (1;1), got ${statuses}")
  endif()
  if(NOT err MATCHES "the receiver holds another rig" OR NOT err MATCHES "the sender holds another rig")
    message(FATAL_ERROR "the refusal was not explained")
  endif()
endif()
