// SPDX-License-Identifier: MIT
// A character's drawings from layered files (layered_character.h).
#include "posemorph/bake/import/layered_character.h"

#include <png.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_image.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/bake/output_file.h"

namespace posemorph::bake::import {
namespace {

// A name as a file name (layered_character.h), without the " #N" that GIMP
// appends to keep an image's layer names unique ("mouth #1" in a second
// pose's group is the part "mouth").
std::string Safe(std::string name, bool dash) {
  name = WithoutCopyNumber(std::move(name));
  std::string out;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                      (c == '.' && !out.empty()) || (c == '-' && dash && !out.empty());
    out += keep ? c : '_';
  }
  if (out.empty()) out = "layer";
  return out;
}

// One pose's entries: the visible children of a group or a file's top level.
struct PoseSource {
  std::string name, file, where;  // where: "" (the file's top level) or "group 'NAME'"
  const std::vector<Layer>* entries;
};

std::string Describe(const PoseSource& p) { return p.where.empty() ? p.file : p.file + ": " + p.where; }

}  // namespace

std::string SafeName(const std::string& name, bool dash) { return Safe(name, dash); }

std::string LayeredCharacter::FileName(std::size_t pose, std::size_t part) const {
  return parts.empty() ? poses[pose] + ".png" : poses[pose] + "-" + parts[part] + ".png";
}

LayeredCharacter ImportLayeredCharacter(const std::vector<std::string>& paths, bool flatten) {
  if (paths.empty()) throw BakeError("", "no layered file to import");
  std::vector<LayeredImage> files;
  for (const std::string& path : paths) files.push_back(ReadLayeredImage(path));
  LayeredCharacter c;
  c.width = files[0].width, c.height = files[0].height;
  for (LayeredImage& f : files) {
    if (f.width != c.width || f.height != c.height)
      throw BakeError(f.file, "a canvas of " + std::to_string(f.width) + " x " + std::to_string(f.height) + ", but " +
                                  files[0].file + "'s is " + std::to_string(c.width) + " x " +
                                  std::to_string(c.height) + ": a character's poses share one canvas");
    c.notes.insert(c.notes.end(), f.notes.begin(), f.notes.end());
  }
  auto note_hidden = [&](const std::string& file, const std::vector<Layer>& entries) {
    for (const Layer& e : entries)
      if (!e.visible)
        c.notes.push_back(file + ": " + (e.group ? "group '" : "layer '") + e.name + "' is hidden: not imported");
  };

  // One file whose visible top-level entries are all groups, two or more:
  // a file of poses. Otherwise each file is a pose.
  std::vector<PoseSource> poses;
  std::size_t groups = 0, visible_entries = 0;
  for (const Layer& e : files[0].layers) visible_entries += e.visible, groups += e.visible && e.group;
  if (files.size() == 1 && groups >= 2 && groups == visible_entries) {
    const LayeredImage& f = files[0];
    note_hidden(f.file, f.layers);
    for (const Layer& e : f.layers) {
      if (!e.visible) continue;
      poses.push_back({e.name, f.file, "group '" + e.name + "'", &e.children});
      note_hidden(f.file + ": group '" + e.name + "'", e.children);
    }
  } else {
    for (std::size_t k = 0; k < files.size(); ++k) {
      note_hidden(files[k].file, files[k].layers);
      poses.push_back({std::filesystem::path(files[k].file).stem().string(), files[k].file, "", &files[k].layers});
    }
  }
  for (const PoseSource& p : poses) {
    std::string name = Safe(p.name, false);
    for (int n = 2; std::find(c.poses.begin(), c.poses.end(), name) != c.poses.end(); ++n)
      name = Safe(p.name, false) + "_" + std::to_string(n);
    c.poses.push_back(name);
  }

  auto visible = [](const std::vector<Layer>& entries) {
    std::vector<const Layer*> out;
    for (const Layer& e : entries)
      if (e.visible) out.push_back(&e);
    return out;
  };
  bool single = true;
  for (const PoseSource& p : poses) {
    const std::vector<const Layer*> v = visible(*p.entries);
    if (v.empty()) throw BakeError(p.file, (p.where.empty() ? "" : p.where + ": ") + "holds no visible layer");
    single = single && v.size() == 1;
  }
  if (flatten || single) {
    for (const PoseSource& p : poses) {
      c.drawings.push_back(Composite(*p.entries, c.width, c.height));
      c.sources.push_back(Describe(p) + (flatten ? ": every visible layer" : ""));
    }
    return c;
  }
  // Parts: the first pose's entries, top first; every pose must draw them.
  for (const Layer* e : visible(*poses[0].entries)) {
    const std::string part = Safe(e->name, true);
    if (std::find(c.parts.begin(), c.parts.end(), part) != c.parts.end())
      throw BakeError(Describe(poses[0]),
                      "two parts are named '" + part + "' (layer names as file names): name each part once");
    c.parts.push_back(part);
  }
  c.drawings.resize(poses.size() * c.parts.size());
  c.sources.resize(c.drawings.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    std::vector<bool> found(c.parts.size(), false);
    for (const Layer* e : visible(*poses[i].entries)) {
      const std::string part = Safe(e->name, true);
      const auto it = std::find(c.parts.begin(), c.parts.end(), part);
      if (it == c.parts.end())
        throw BakeError(Describe(poses[i]), (e->group ? "group '" : "layer '") + e->name + "' is not a part of pose '" +
                                                c.poses[0] + "' (" + Describe(poses[0]) +
                                                "): every pose draws the same parts, named alike");
      const std::size_t q = std::size_t(it - c.parts.begin());
      if (found[q]) throw BakeError(Describe(poses[i]), "two parts are named '" + part + "': name each part once");
      found[q] = true;
      c.drawings[i * c.parts.size() + q] = Composite(*e, c.width, c.height);
      c.sources[i * c.parts.size() + q] =
          Describe(poses[i]) + ": " + (e->group ? "group '" : "layer '") + e->name + "'";
    }
    for (std::size_t q = 0; q < c.parts.size(); ++q)
      if (!found[q])
        throw BakeError(Describe(poses[i]), "has no visible layer or group '" + c.parts[q] + "', which pose '" +
                                                c.poses[0] +
                                                "' has: every part is drawn in every pose (one that should vanish "
                                                "is drawn tiny, or hidden behind another by its order)");
  }
  return c;
}

std::vector<std::string> WriteLayeredDrawings(const LayeredCharacter& c, const std::string& folder, bool overwrite) {
  const std::size_t per_pose = c.parts.empty() ? 1 : c.parts.size();
  std::vector<std::string> paths;
  std::vector<std::vector<unsigned char>> pngs;
  std::vector<bool> same;
  for (std::size_t i = 0; i < c.poses.size(); ++i)
    for (std::size_t q = 0; q < per_pose; ++q) {
      const std::string path = (std::filesystem::path(folder) / c.FileName(i, q)).string();
      CheckOutputPath(path, {});
      std::vector<unsigned char> png = EncodeRgbaPng(c.drawings[i * per_pose + q], c.width, c.height, path);
      bool unchanged = false;
      if (std::filesystem::exists(path)) {
        try {
          unchanged = ReadInputFile(path, kMaxLayeredFileBytes, "a drawing") == png;
        } catch (const BakeError&) {
        }
        if (!unchanged && !overwrite)
          throw BakeError(
              path, "exists, and the drawing of " + c.sources[i * per_pose + q] + " would replace it (--force does)");
      }
      paths.push_back(path);
      pngs.push_back(std::move(png));
      same.push_back(unchanged);
    }
  for (std::size_t k = 0; k < paths.size(); ++k)
    if (!same[k]) WriteFileAtomic(paths[k], pngs[k]);
  return paths;
}

std::vector<std::string> ImportAgain(const std::vector<std::string>& files, bool channels, bool flatten,
                                     const std::string& folder, std::vector<std::string>* notes) {
  std::vector<LayeredCharacter> characters;
  if (channels) {
    for (const std::string& f : files) characters.push_back(ImportLayeredCharacter({f}, false));
  } else {
    characters.push_back(ImportLayeredCharacter(files, flatten));
  }
  std::vector<std::string> paths;
  for (const LayeredCharacter& c : characters) {
    notes->insert(notes->end(), c.notes.begin(), c.notes.end());
    for (std::string& p : WriteLayeredDrawings(c, folder, true)) paths.push_back(std::move(p));
  }
  return paths;
}

}  // namespace posemorph::bake::import
