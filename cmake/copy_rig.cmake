# SPDX-License-Identifier: MIT
# Copies a baked rig and its atlas pages (NAME.page0.png ..., written beside
# it by posemorph-bake) from FROM to TO:
#   cmake -DFROM=DIR -DTO=DIR -DNAME=pip.compact -P copy_rig.cmake
file(MAKE_DIRECTORY ${TO})
file(COPY ${FROM}/${NAME}.pmrig DESTINATION ${TO})
file(GLOB pages ${FROM}/${NAME}.page*.png)
foreach(page ${pages})
  file(COPY ${page} DESTINATION ${TO})
endforeach()
