-- SPDX-License-Identifier: MIT
-- posemorph for LÖVE 11 (and any LuaJIT): the runtime's C API through
-- LuaJIT's FFI, and a LÖVE renderer that draws every list of a character
-- (body and attachments, back to front) with a shader that cross-fades up
-- to eight drawings in premultiplied alpha, as posemorph-view does.
--
--   local posemorph = require("posemorph")   -- loads libposemorph (POSEMORPH_LIBRARY overrides the path)
--   local rig = posemorph.load("pell-face.pmrig")            -- error "FILE: problem" if refused
--   local crowd = rig:crowd(200)
--   crowd:evaluate(points, channel_points, transforms)      -- Lua arrays, 1-based
--   local drawer = posemorph.drawer(rig, "drawings/")       -- LÖVE: texture pages, meshes, shader
--   drawer:draw(crowd, k)                                   -- character k (1-based), under the current transform
--
-- Memory: every buffer the runtime writes is an FFI array the rig or crowd
-- holds (freed by the garbage collector with it); the rig handle is freed
-- by ffi.gc. Values read from a crowd are copies.
local ffi = require("ffi")

ffi.cdef [[
typedef struct pm_rig pm_rig;
typedef struct pm_error { int code; char message[256]; } pm_error;
typedef struct pm_rig_info { uint32_t vertex_count, triangle_count, pose_count, path_count; double default_sigma, size; } pm_rig_info;
typedef struct pm_part { uint32_t first_triangle, triangle_count; int32_t draw_order; } pm_part;
typedef struct pm_canvas { double width, height, pivot_x, pivot_y; } pm_canvas;
typedef struct pm_transform { float a, b, c, d, tx, ty; } pm_transform;
typedef struct pm_blended_drawing { uint32_t pose; float weight; const float* uvs; } pm_blended_drawing;
typedef struct pm_colour { float r, g, b, a; } pm_colour;
typedef struct pm_draw_list {
  const float* positions; const uint32_t* indices; uint32_t vertex_count, index_count; uint32_t drawing_count;
  pm_blended_drawing drawings[8]; pm_transform transform; int mirrored; const uint32_t* parts; uint32_t part_count;
  pm_colour colour; float part_opacity[64];
} pm_draw_list;
typedef struct pm_draw_options { double sigma; int limit_weights; int linear; uint32_t max_drawings;
  const pm_colour* colours; const float* part_opacities; } pm_draw_options;
typedef struct pm_list_info { uint32_t vertex_count, triangle_count, pose_count, part_count, channel; } pm_list_info;
typedef struct pm_character_buffer_sizes { size_t workspace_doubles, position_floats, attached_position_floats, attached_lists; } pm_character_buffer_sizes;
typedef struct pm_character_inputs { const double* points; const double* channel_points;
  const double *weights, *limited_weights, *texture_weights;
  const double *attached_weights, *attached_limited_weights, *attached_texture_weights;
  const pm_transform* transforms; } pm_character_inputs;
typedef struct pm_draw_step { uint32_t list, part; } pm_draw_step;
typedef struct pm_page { uint32_t width, height; int atlas; int premultiplied; } pm_page;
typedef struct pm_region { uint32_t page; float scale_u, offset_u, scale_v, offset_v; uint32_t x, y, width, height; } pm_region;
const char* pm_version(void);
int pm_rig_load(const void* bytes, size_t size, pm_rig** out_rig, pm_error* err);
void pm_rig_free(pm_rig* rig);
void pm_rig_get_info(const pm_rig* rig, pm_rig_info* info);
int pm_rig_pose_point(const pm_rig* rig, uint32_t pose, double* x, double* y);
uint32_t pm_rig_channel_count(const pm_rig* rig);
int pm_rig_channel_poses(const pm_rig* rig, uint32_t channel, uint32_t* pose_count, double* points, size_t capacity);
uint32_t pm_rig_attachment_count(const pm_rig* rig);
uint32_t pm_channel_path_count(const pm_rig* rig, uint32_t channel);
int pm_channel_path_find(const pm_rig* rig, uint32_t channel, const char* name);
int pm_channel_path_sample(const pm_rig* rig, uint32_t channel, uint32_t path, double time, double* x, double* y);
int pm_channel_path_name(const pm_rig* rig, uint32_t channel, uint32_t path, char* out, size_t capacity, size_t* length);
uint32_t pm_character_list_count(const pm_rig* rig);
int pm_character_list(const pm_rig* rig, uint32_t list, pm_list_info* out);
int pm_character_part(const pm_rig* rig, uint32_t list, uint32_t part, pm_part* out);
int pm_character_part_image(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, char* out, size_t capacity, size_t* length);
int pm_character_texture_filter(const pm_rig* rig, uint32_t list);
int pm_rig_has_atlas(const pm_rig* rig);
uint32_t pm_character_page_count(const pm_rig* rig, uint32_t list);
int pm_character_page(const pm_rig* rig, uint32_t list, uint32_t page, pm_page* out);
int pm_character_page_name(const pm_rig* rig, uint32_t list, uint32_t page, char* out, size_t capacity, size_t* length);
int pm_character_part_region(const pm_rig* rig, uint32_t list, uint32_t part, uint32_t pose, pm_region* out);
const uint32_t* pm_rig_triangles(const pm_rig* rig);
const double* pm_rig_pose_positions(const pm_rig* rig, uint32_t pose);
const uint32_t* pm_rig_attachment_triangles(const pm_rig* rig, uint32_t attachment);
void pm_draw_options_default(pm_draw_options* out);
void pm_transform_make(double x, double y, double radians, double scale_x, double scale_y, int flip_x, pm_transform* out);
void pm_transform_compose(const pm_transform* outer, const pm_transform* inner, pm_transform* out);
void pm_transform_place(const pm_rig* rig, double x, double y, double radians, double scale, int face_left, pm_transform* out);
int pm_rig_placement(const pm_rig* rig, double* anchor_x, double* anchor_y, int* facing_left);
int pm_character_buffers(const pm_rig* rig, size_t count, pm_character_buffer_sizes* out);
int pm_character_draw_lists(const pm_rig* rig, const pm_draw_options* options, size_t count, const pm_character_inputs* inputs,
  double* workspace, size_t workspace_capacity, float* positions, size_t positions_capacity, float* attached_positions,
  size_t attached_positions_capacity, pm_draw_list* out, size_t out_capacity, pm_draw_list* attached_out, size_t attached_out_capacity);
uint32_t pm_character_draw_steps(const pm_rig* rig, const pm_draw_list* body, const pm_draw_list* attached, pm_draw_step* out, uint32_t capacity);
]]

local C = ffi.load(os.getenv("POSEMORPH_LIBRARY") or "posemorph")
local M = { version = ffi.string(C.pm_version()), MAX_DRAWINGS = 8 }

local Rig, Crowd, Drawer = {}, {}, {}
Rig.__index, Crowd.__index, Drawer.__index = Rig, Crowd, Drawer

local function string_of(call)
  local buf, n = ffi.new("char[256]"), ffi.new("size_t[1]")
  if call(buf, 256, n) ~= 0 then return nil end
  return ffi.string(buf, n[0])
end

-- A rig from a file (or its bytes, named `name` in errors). Errors are Lua
-- errors "FILE: problem", the loader's own message.
function M.load(path, bytes)
  if not bytes then
    local f, why = io.open(path, "rb")
    if not f then error(path .. ": cannot open the file (" .. tostring(why) .. ")", 2) end
    bytes = f:read("*a")
    f:close()
  end
  local out, err = ffi.new("pm_rig*[1]"), ffi.new("pm_error")
  if C.pm_rig_load(bytes, #bytes, out, err) ~= 0 then error(path .. ": " .. ffi.string(err.message), 2) end
  local rig = setmetatable({ handle = ffi.gc(out[0], C.pm_rig_free), file = path }, Rig)
  local info = ffi.new("pm_rig_info")
  C.pm_rig_get_info(rig.handle, info)
  rig.vertex_count, rig.triangle_count, rig.pose_count, rig.path_count =
    info.vertex_count, info.triangle_count, info.pose_count, info.path_count
  rig.channel_count = C.pm_rig_channel_count(rig.handle)
  rig.attachment_count = C.pm_rig_attachment_count(rig.handle)
  rig.list_count = C.pm_character_list_count(rig.handle)
  return rig
end

-- A pose's point in channel c (0: the body), 0-based pose.
function Rig:pose_point(channel, pose)
  local n = ffi.new("uint32_t[1]")
  C.pm_rig_channel_poses(self.handle, channel, n, nil, 0)
  local points = ffi.new("double[?]", 2 * n[0])
  C.pm_rig_channel_poses(self.handle, channel, n, points, 2 * n[0])
  return points[2 * pose], points[2 * pose + 1]
end
function Rig:path_count_of(channel) return C.pm_channel_path_count(self.handle, channel) end
function Rig:find_path(name, channel) return C.pm_channel_path_find(self.handle, channel or 0, name) end
function Rig:path_name(channel, path)
  return string_of(function(b, c, n) return C.pm_channel_path_name(self.handle, channel, path, b, c, n) end)
end
-- A point on channel c's path at time t seconds.
function Rig:sample_path(channel, path, t)
  local x, y = ffi.new("double[1]"), ffi.new("double[1]")
  if C.pm_channel_path_sample(self.handle, channel, path, t, x, y) ~= 0 then
    error(self.file .. ": channel " .. channel .. " has no path " .. path, 2)
  end
  return x[0], y[0]
end
-- The body's bounds over its poses (rig units, y up): x0, y0, x1, y1.
function Rig:bounds()
  local x0, y0, x1, y1 = math.huge, math.huge, -math.huge, -math.huge
  for pose = 0, self.pose_count - 1 do
    local p = C.pm_rig_pose_positions(self.handle, pose)
    for i = 0, self.vertex_count - 1 do
      local x, y = p[2 * i], p[2 * i + 1]
      x0, x1, y0, y1 = math.min(x0, x), math.max(x1, x), math.min(y0, y), math.max(y1, y)
    end
  end
  return x0, y0, x1, y1
end
-- List l (0: the body, a + 1: attachment a): counts and its triangles.
function Rig:list(l)
  local info = ffi.new("pm_list_info")
  if C.pm_character_list(self.handle, l, info) ~= 0 then error(self.file .. ": no list " .. l, 2) end
  return info
end
function Rig:part(l, p)
  local part = ffi.new("pm_part")
  if C.pm_character_part(self.handle, l, p, part) ~= 0 then error(self.file .. ": no part " .. p, 2) end
  return part
end
function Rig:part_image(l, p, pose)
  return string_of(function(b, c, n) return C.pm_character_part_image(self.handle, l, p, pose, b, c, n) end)
end
-- Texture page k of list l (an atlas page beside the rig file, or one
-- drawing): its name and pm_page; and part p's region in a pose on it.
function Rig:page(l, k)
  local page = ffi.new("pm_page")
  if C.pm_character_page(self.handle, l, k, page) ~= 0 then error(self.file .. ": no page " .. k, 2) end
  return string_of(function(b, c, n) return C.pm_character_page_name(self.handle, l, k, b, c, n) end), page
end
function Rig:page_count(l) return C.pm_character_page_count(self.handle, l) end
function Rig:has_atlas() return C.pm_rig_has_atlas(self.handle) == 1 end
function Rig:region(l, p, pose)
  local r = ffi.new("pm_region")
  if C.pm_character_part_region(self.handle, l, p, pose, r) ~= 0 then error(self.file .. ": no part " .. p, 2) end
  return r
end
function Rig:triangles(l)
  if l == 0 then return C.pm_rig_triangles(self.handle) end
  return C.pm_rig_attachment_triangles(self.handle, l - 1)
end
-- A transform (pm_transform_make): scale, flip, rotate, move.
function M.transform(x, y, radians, sx, sy, flip)
  local t = ffi.new("pm_transform")
  C.pm_transform_make(x, y, radians or 0, sx or 1, sy or 1, flip and 1 or 0, t)
  return t
end

-- The rig's anchor (the point it stands on) at world (x, y), turned and
-- scaled about it, facing left when face_left (pm_transform_place).
function Rig:place(x, y, radians, scale, face_left)
  local t = ffi.new("pm_transform")
  C.pm_transform_place(self.handle, x, y, radians or 0, scale or 1, face_left and 1 or 0, t)
  return t
end
-- Where the character stands (rig units) and whether its drawings face left.
function Rig:placement()
  local x, y, left = ffi.new("double[1]"), ffi.new("double[1]"), ffi.new("int[1]")
  C.pm_rig_placement(self.handle, x, y, left)
  return x[0], y[0], left[0] ~= 0
end
-- outer after inner (pm_transform_compose).
function M.compose(outer, inner)
  local t = ffi.new("pm_transform")
  C.pm_transform_compose(outer, inner, t)
  return t
end

-- Draw lists for `count` characters.
function Rig:crowd(count)
  local sizes = ffi.new("pm_character_buffer_sizes")
  if C.pm_character_buffers(self.handle, count, sizes) ~= 0 then
    error(self.file .. ": no buffers for " .. count .. " characters", 2)
  end
  local later = self.channel_count - 1
  return setmetatable({
    rig = self, count = count, sizes = sizes,
    work = ffi.new("double[?]", sizes.workspace_doubles),
    positions = ffi.new("float[?]", sizes.position_floats),
    attached_positions = ffi.new("float[?]", math.max(1, tonumber(sizes.attached_position_floats))),
    lists = ffi.new("pm_draw_list[?]", count),
    attached = ffi.new("pm_draw_list[?]", math.max(1, tonumber(sizes.attached_lists))),
    points = ffi.new("double[?]", 2 * count),
    channel_points = ffi.new("double[?]", math.max(1, 2 * count * later)),
    transforms = ffi.new("pm_transform[?]", count),
    step_buffer = ffi.new("pm_draw_step[?]", 129),
    inputs = ffi.new("pm_character_inputs"),
    options = ffi.new("pm_draw_options"),
  }, Crowd)
end

-- Every character at its points: points {x1, y1, x2, y2, ...} (the body's
-- space), channel_points per character channels 1 .. C-1's x, y (nil: their
-- first poses), transforms a Lua array of pm_transform (nil: identity).
function Crowd:evaluate(points, channel_points, transforms)
  local n, rig = self.count, self.rig
  if #points < 2 * n then error(rig.file .. ": " .. n .. " characters need " .. 2 * n .. " point values", 2) end
  for i = 0, 2 * n - 1 do self.points[i] = points[i + 1] end
  local inputs = self.inputs
  inputs.points = self.points
  inputs.channel_points = nil
  if channel_points and rig.channel_count > 1 then
    for i = 0, 2 * n * (rig.channel_count - 1) - 1 do self.channel_points[i] = channel_points[i + 1] end
    inputs.channel_points = self.channel_points
  end
  inputs.transforms = nil
  if transforms then
    for k = 0, n - 1 do self.transforms[k] = transforms[k + 1] end
    inputs.transforms = self.transforms
  end
  C.pm_draw_options_default(self.options)
  self.options.max_drawings = M.MAX_DRAWINGS
  local s = self.sizes
  local status = C.pm_character_draw_lists(rig.handle, self.options, n, inputs, self.work, s.workspace_doubles,
    self.positions, s.position_floats, rig.attachment_count > 0 and self.attached_positions or nil,
    s.attached_position_floats, self.lists, n, rig.attachment_count > 0 and self.attached or nil, s.attached_lists)
  if status ~= 0 then error(rig.file .. ": the frame was refused (code " .. status .. ")", 2) end
end

-- List l of character k (1-based k; l 0: the body, a + 1: attachment a): the C struct (valid until the next evaluate).
function Crowd:list(k, l)
  if l == 0 then return self.lists[k - 1] end
  return self.attached[(k - 1) * self.rig.attachment_count + l - 1]
end
-- The character digest (integrations/README.md) of this crowd's last frame.
function Crowd:digest()
  local h = ffi.new("uint64_t", 14695981039346656037ULL)
  local prime = 1099511628211ULL
  local function u32(v)
    v = ffi.cast("uint32_t", v)
    for i = 0, 3 do h = bit.bxor(h, bit.band(bit.rshift(v, 8 * i), 0xFF)) * prime end
  end
  local words = ffi.cast("const uint32_t*", self.positions)
  for i = 0, tonumber(self.sizes.position_floats) - 1 do u32(words[i]) end
  words = ffi.cast("const uint32_t*", self.attached_positions)
  for i = 0, tonumber(self.sizes.attached_position_floats) - 1 do u32(words[i]) end
  local weight = ffi.new("float[1]")
  local steps = 0
  for k = 1, self.count do
    for l = 0, self.rig.attachment_count do
      local list = self:list(k, l)
      u32(list.drawing_count)
      for i = 0, list.drawing_count - 1 do
        u32(list.drawings[i].pose)
        weight[0] = list.drawings[i].weight
        u32(ffi.cast("uint32_t*", weight)[0])
      end
    end
    for _, s in ipairs(self:steps(k)) do
      u32(s.list)
      u32(s.part)
      steps = steps + 1
    end
  end
  return string.format("character-fnv1a64=%s characters=%d steps=%d", bit.tohex(h, 16), self.count, steps)
end

-- Character k's draw steps back to front: an array of {list, part}.
function Crowd:steps(k)
  local A = self.rig.attachment_count
  local n = C.pm_character_draw_steps(self.rig.handle, self.lists + (k - 1), A > 0 and self.attached + (k - 1) * A or nil,
                                      self.step_buffer, 129)
  local out = {}
  for s = 0, math.min(n, 129) - 1 do out[#out + 1] = { list = self.step_buffer[s].list, part = self.step_buffer[s].part } end
  return out
end

-- The LÖVE renderer: the drawings of every list, part and pose from `folder`
-- (premultiplied on load), one mesh per list, the cross-fade shader.
local uv_names = { "uv0", "uv1", "uv2", "uv3", "uv4", "uv5", "uv6", "uv7" }
local vertex_code = [[
attribute vec2 uv0; attribute vec2 uv1; attribute vec2 uv2; attribute vec2 uv3;
attribute vec2 uv4; attribute vec2 uv5; attribute vec2 uv6; attribute vec2 uv7;
uniform vec4 map0; uniform vec4 map1; uniform vec4 map2; uniform vec4 map3;
uniform vec4 map4; uniform vec4 map5; uniform vec4 map6; uniform vec4 map7;
varying vec2 v0; varying vec2 v1; varying vec2 v2; varying vec2 v3;
varying vec2 v4; varying vec2 v5; varying vec2 v6; varying vec2 v7;
vec4 position(mat4 transform_projection, vec4 vertex_position) {
  // Each drawing's uvs onto its page (the atlas's region; identity for a drawing of its own).
  v0 = uv0 * map0.xz + map0.yw; v1 = uv1 * map1.xz + map1.yw; v2 = uv2 * map2.xz + map2.yw;
  v3 = uv3 * map3.xz + map3.yw; v4 = uv4 * map4.xz + map4.yw; v5 = uv5 * map5.xz + map5.yw;
  v6 = uv6 * map6.xz + map6.yw; v7 = uv7 * map7.xz + map7.yw;
  return transform_projection * vertex_position;
}]]
-- The exact cross-fade: the weighted sum of premultiplied drawings, times
-- the colour (premultiplied), drawn with the blend mode ("alpha", "premultiplied").
local pixel_code = [[
uniform Image d0; uniform Image d1; uniform Image d2; uniform Image d3;
uniform Image d4; uniform Image d5; uniform Image d6; uniform Image d7;
uniform vec4 weights_a; uniform vec4 weights_b; uniform vec4 tint;
varying vec2 v0; varying vec2 v1; varying vec2 v2; varying vec2 v3;
varying vec2 v4; varying vec2 v5; varying vec2 v6; varying vec2 v7;
vec4 effect(vec4 color, Image tex, vec2 tc, vec2 sc) {
  vec4 c = weights_a.x * Texel(d0, v0) + weights_a.y * Texel(d1, v1) + weights_a.z * Texel(d2, v2)
         + weights_a.w * Texel(d3, v3) + weights_b.x * Texel(d4, v4) + weights_b.y * Texel(d5, v5)
         + weights_b.z * Texel(d6, v6) + weights_b.w * Texel(d7, v7);
  return c * tint;
}]]

local function read_image(path, nearest, premultiplied)
  local f, why = io.open(path, "rb")
  if not f then error(path .. ": cannot read the " .. (premultiplied and "atlas page" or "drawing") .. " (" .. tostring(why) .. ")", 3) end
  local bytes = f:read("*a")
  f:close()
  local ok, data = pcall(love.image.newImageData, love.filesystem.newFileData(bytes, path))
  if not ok then error(path .. ": not a PNG the renderer reads (" .. tostring(data) .. ")", 3) end
  -- Premultiply, through the FFI: what the blend wants, and what linear
  -- filtering of a transparent edge needs (an atlas page is stored so).
  local p = ffi.cast("uint8_t*", data:getFFIPointer())
  for i = 0, premultiplied and -1 or data:getWidth() * data:getHeight() * 4 - 1, 4 do
    local a = p[i + 3]
    p[i] = math.floor((p[i] * a + 127) / 255)
    p[i + 1] = math.floor((p[i + 1] * a + 127) / 255)
    p[i + 2] = math.floor((p[i + 2] * a + 127) / 255)
  end
  local image = love.graphics.newImage(data)
  image:setFilter(nearest and "nearest" or "linear", nearest and "nearest" or "linear")
  return image
end

-- A page's name names a file inside its folder (a rig file is hostile input).
local function stays_inside(name)
  return name ~= "" and not name:find("^/") and not name:find("[\\:%c]") and not ("/" .. name .. "/"):find("/%.%./")
end

-- A drawer for `rig`: its texture pages (the atlas beside the rig file; or,
-- for a rig without one, each part's drawing in each pose, from `folder`),
-- each page read once, and each part's region in each pose.
function M.drawer(rig, folder)
  local d = setmetatable({ rig = rig, pages = {}, regions = {}, meshes = {}, bytes = {}, parts = {}, filled = {},
    weights_a = { 0, 0, 0, 0 }, weights_b = { 0, 0, 0, 0 }, tint = { 1, 1, 1, 1 }, transform = love.math.newTransform(),
    texture_names = { "d0", "d1", "d2", "d3", "d4", "d5", "d6", "d7" },
    map_names = { "map0", "map1", "map2", "map3", "map4", "map5", "map6", "map7" } }, Drawer)
  local steps = 0
  d.shader = love.graphics.newShader(pixel_code, vertex_code)
  local format = { { "VertexPosition", "float", 2 } }
  for _, name in ipairs(uv_names) do format[#format + 1] = { name, "float", 2 } end
  local rig_folder = rig.file:match("^(.*)/[^/]*$") or "."
  local cache = {}
  for l = 0, rig.list_count - 1 do
    local info = rig:list(l)
    local nearest = C.pm_character_texture_filter(rig.handle, l) == 1
    d.pages[l], d.regions[l], d.parts[l] = {}, {}, {}
    steps = steps + info.part_count
    for k = 0, rig:page_count(l) - 1 do
      local name, page = rig:page(l, k)
      if not name or not stays_inside(name) then
        error(rig.file .. ": list " .. l .. " page " .. k .. " has no name, or one that leaves its folder", 2)
      end
      local path = (page.atlas == 1 and rig_folder or folder) .. "/" .. name
      cache[path] = cache[path] or read_image(path, nearest, page.premultiplied == 1)
      d.pages[l][k] = cache[path]
    end
    for p = 0, info.part_count - 1 do
      local part = rig:part(l, p)
      d.parts[l][p] = { part.first_triangle, part.triangle_count }
      d.regions[l][p] = {}
      for pose = 0, info.pose_count - 1 do
        local r = rig:region(l, p, pose)
        d.regions[l][p][pose] = { page = r.page, map = { r.scale_u, r.offset_u, r.scale_v, r.offset_v } }
      end
    end
    local mesh = love.graphics.newMesh(format, info.vertex_count, "triangles", "stream")
    local triangles, map = rig:triangles(l), {}
    for i = 0, 3 * info.triangle_count - 1 do map[i + 1] = triangles[i] + 1 end
    mesh:setVertexMap(map)
    d.meshes[l] = mesh
    d.bytes[l] = love.data.newByteData(info.vertex_count * 72)
  end
  d.step_capacity = math.max(steps, 1)
  d.step_buffer = ffi.new("pm_draw_step[?]", d.step_capacity)
  return d
end

-- The textures the drawer holds (each page once: Pell with a face's atlas is one).
function Drawer:texture_count()
  local seen, n = {}, 0
  for _, pages in pairs(self.pages) do
    for _, image in pairs(pages) do
      if not seen[image] then seen[image], n = true, n + 1 end
    end
  end
  return n
end

-- Character k of the crowd (1-based), back to front, under LÖVE's current
-- transform. Per frame it creates no Lua tables or FFI objects: the steps,
-- parts, weights, tint and transform live in the drawer, made once.
function Drawer:draw(crowd, k)
  local rig, K = self.rig, M.MAX_DRAWINGS
  local A = rig.attachment_count
  local n = C.pm_character_draw_steps(rig.handle, crowd.lists + (k - 1), A > 0 and crowd.attached + (k - 1) * A or nil,
                                      self.step_buffer, self.step_capacity)
  local filled, weights_a, weights_b, tint, m = self.filled, self.weights_a, self.weights_b, self.tint, self.transform
  for l = 0, rig.list_count - 1 do filled[l] = false end
  love.graphics.setShader(self.shader)
  love.graphics.setBlendMode("alpha", "premultiplied")
  for s = 0, math.min(n, self.step_capacity) - 1 do
    local l, p = self.step_buffer[s].list, self.step_buffer[s].part
    local list = crowd:list(k, l)
    local mesh = self.meshes[l]
    if not filled[l] then  -- positions and the picked drawings' uvs, once per list
      local v = ffi.cast("float*", self.bytes[l]:getFFIPointer())
      for i = 0, list.vertex_count - 1 do
        v[18 * i], v[18 * i + 1] = list.positions[2 * i], list.positions[2 * i + 1]
        for d = 0, list.drawing_count - 1 do  -- a slot past them has weight 0: its uvs do not count
          local uvs = list.drawings[d].uvs
          v[18 * i + 2 + 2 * d], v[18 * i + 3 + 2 * d] = uvs[2 * i], uvs[2 * i + 1]
        end
      end
      mesh:setVertices(self.bytes[l])
      filled[l] = true
    end
    local part = self.parts[l][p]
    mesh:setDrawRange(3 * part[1] + 1, 3 * part[2])
    for d = 0, K - 1 do
      local w = d < list.drawing_count and list.drawings[d].weight or 0
      if d < 4 then weights_a[d + 1] = w else weights_b[d - 3] = w end
      local region = self.regions[l][p][list.drawings[d < list.drawing_count and d or 0].pose]
      self.shader:send(self.texture_names[d + 1], self.pages[l][region.page])
      self.shader:send(self.map_names[d + 1], region.map)
    end
    self.shader:send("weights_a", weights_a)
    self.shader:send("weights_b", weights_b)
    local c = list.colour
    local a = c.a * (p < 64 and list.part_opacity[p] or 1)
    tint[1], tint[2], tint[3], tint[4] = c.r * a, c.g * a, c.b * a, a
    self.shader:send("tint", tint)
    local t = list.transform
    m:setMatrix(t.a, t.c, 0, t.tx, t.b, t.d, 0, t.ty, 0, 0, 1, 0, 0, 0, 0, 1)
    love.graphics.draw(mesh, m)
  end
  love.graphics.setShader()
  love.graphics.setBlendMode("alpha", "alphamultiply")
end

return M
