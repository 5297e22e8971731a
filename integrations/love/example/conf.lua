-- SPDX-License-Identifier: MIT
function love.conf(t)
  t.identity = "posemorph-example"
  t.window.title = "posemorph in LÖVE"
  t.window.width, t.window.height = 640, 640
  t.modules.audio, t.modules.sound, t.modules.joystick, t.modules.physics = false, false, false, false
end
