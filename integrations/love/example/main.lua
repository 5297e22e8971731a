-- SPDX-License-Identifier: MIT
-- posemorph in a LÖVE 11 game: a crowd walks the rig's paths (every
-- channel on its own), or one character follows the mouse through pose
-- space; each is drawn from its draw lists by integrations/love/posemorph.lua.
--
--   love integrations/love/example RIG.pmrig --images DIR [--crowd N] [--at X,Y] [--size WxH]
--        [--frames F --screenshot OUT.png]     the test's frame, written as a PNG, then quit
--   love integrations/love/example RIG.pmrig --digest K   print the character digest of K characters, quit
--   love integrations/love/example RIG.pmrig --load-only  load the rig (a refused one: its message, status 1)
local here = love.filesystem.getSource()
package.path = here .. "/../?.lua;" .. package.path
local posemorph = require("posemorph")

local o = { crowd = 1, width = 640, height = 640, frames = 0 }
local rig, crowd, drawer, places, frame, view = nil, nil, nil, {}, 0, nil

local function fail(message)
  io.stderr:write("love example: " .. message .. "\n")
  love.event.quit(1)
end

local function parse(args)
  local i = 1
  while i <= #args do
    local a, v = args[i], args[i + 1]
    if a:sub(1, 2) ~= "--" then o.rig = a; i = i - 1
    elseif a == "--load-only" then o.load_only = true; i = i - 1
    elseif a == "--images" then o.images = v
    elseif a == "--crowd" then o.crowd = tonumber(v)
    elseif a == "--digest" then o.digest = tonumber(v)
    elseif a == "--frames" then o.frames = tonumber(v)
    elseif a == "--screenshot" then o.screenshot = v
    elseif a == "--at" then o.at_x, o.at_y = v:match("([-%d.e]+),([-%d.e]+)"); o.at_x, o.at_y = tonumber(o.at_x), tonumber(o.at_y)
    elseif a == "--size" then o.width, o.height = v:match("(%d+)x(%d+)"); o.width, o.height = tonumber(o.width), tonumber(o.height)
    else return "unknown option " .. a end
    i = i + 2
  end
  if not o.rig then return "usage: love example RIG.pmrig --images DIR [--crowd N] [--at X,Y] [--size WxH] [--frames F --screenshot OUT.png]" end
end

-- Where each character stands: a grid, alternate ones facing left, fitted to the window (as posemorph-view frames one).
local function place_characters()
  local x0, y0, x1, y1 = rig:bounds()
  local margin = 0.06 * math.max(x1 - x0, y1 - y0)
  local cw, ch = x1 - x0 + 2 * margin, y1 - y0 + 2 * margin
  local columns = math.ceil(math.sqrt(o.crowd))
  local rows = math.ceil(o.crowd / columns)
  for k = 0, o.crowd - 1 do
    local centre = posemorph.transform(-(x0 + x1) / 2, -(y0 + y1) / 2)
    local at = posemorph.transform(cw * (k % columns), -ch * math.floor(k / columns), 0, 1, 1, k % 2 == 1)
    places[k + 1] = posemorph.compose(at, centre)
  end
  local zoom = math.min(o.width / (cw * columns), o.height / (ch * rows))
  view = { zoom = zoom, cx = cw * (columns - 1) / 2, cy = -ch * (rows - 1) / 2 }
end

-- Pose-space points: a crowd walks the paths; one character is at --at or under the mouse.
local function points_at(t)
  local points, channel_points = {}, {}
  for k = 0, o.crowd - 1 do
    local x, y
    if o.at_x then
      x, y = o.at_x, o.at_y
    elseif o.crowd > 1 and rig.path_count > 0 then
      x, y = rig:sample_path(0, 0, t + 0.37 * k)
    else
      local mx, my = love.mouse.getPosition()
      local x0, y0 = rig:pose_point(0, 0)
      x, y = x0 + (mx / o.width - 0.5) * 2, y0 + (0.5 - my / o.height) * 2
    end
    points[#points + 1], points[#points + 2] = x, y
    for c = 1, rig.channel_count - 1 do
      local cx, cy
      if rig:path_count_of(c) > 0 and not o.at_x then cx, cy = rig:sample_path(c, 0, t * 0.8 + 0.23 * k * c)
      else cx, cy = rig:pose_point(c, 0) end
      channel_points[#channel_points + 1], channel_points[#channel_points + 2] = cx, cy
    end
  end
  return points, channel_points
end

function love.load(args)
  local problem = parse(args)
  if problem then return fail(problem) end
  local ok, loaded = pcall(posemorph.load, o.rig)
  if not ok then
    print(loaded)  -- the runtime's message, naming the file
    return love.event.quit(1)
  end
  rig = loaded
  if o.load_only then print(o.rig .. ": loaded"); return love.event.quit(0) end
  if o.digest then
    o.crowd = o.digest
    local c = rig:crowd(o.digest)
    local points, channel_points = {}, {}
    for k = 0, o.digest - 1 do
      local x, y
      if rig.path_count > 0 then x, y = rig:sample_path(0, 0, 0.37 * k) else x, y = rig:pose_point(0, k % rig.pose_count) end
      points[#points + 1], points[#points + 2] = x, y
      for ch = 1, rig.channel_count - 1 do
        local cx, cy
        if rig:path_count_of(ch) > 0 then cx, cy = rig:sample_path(ch, 0, 0.23 * k * ch) else cx, cy = rig:pose_point(ch, 0) end
        channel_points[#channel_points + 1], channel_points[#channel_points + 2] = cx, cy
      end
    end
    c:evaluate(points, rig.channel_count > 1 and channel_points or nil)
    print(c:digest())
    return love.event.quit(0)
  end
  if not o.images then return fail("--images DIR: where the rig's drawings are") end
  love.window.setMode(o.width, o.height)
  local ok2, d = pcall(posemorph.drawer, rig, o.images)
  if not ok2 then return fail(tostring(d)) end
  drawer = d
  crowd = rig:crowd(o.crowd)
  place_characters()
end

function love.update(dt)
  if not crowd then return end
  local points, channel_points = points_at(frame / 60)
  crowd:evaluate(points, channel_points, places)
end

function love.draw()
  if not crowd then return end
  love.graphics.clear(0.93, 0.94, 0.95, 1)
  love.graphics.push()
  love.graphics.translate(o.width / 2, o.height / 2)
  love.graphics.scale(view.zoom, -view.zoom)  -- rig units, y up
  love.graphics.translate(-view.cx, -view.cy)
  for k = 1, o.crowd do drawer:draw(crowd, k) end
  love.graphics.pop()
  frame = frame + 1
  if o.frames > 0 and frame == o.frames then
    if o.screenshot then
      love.graphics.captureScreenshot(function(image)
        local f = io.open(o.screenshot, "wb")
        f:write(image:encode("png"):getString())
        f:close()
        print(string.format("%d frames of %d character(s), %d texture(s); screenshot %s", frame, o.crowd,
                            drawer:texture_count(), o.screenshot))
        love.event.quit(0)
      end)
    else
      print(string.format("%d frames of %d character(s)", frame, o.crowd))
      love.event.quit(0)
    end
  end
end

-- An error (a refused frame, a bug) ends the game with its message and status 1, instead of LÖVE's error screen.
function love.errorhandler(message)
  io.stderr:write("love example: " .. tostring(message) .. "\n" .. debug.traceback() .. "\n")
  return function() return 1 end
end
