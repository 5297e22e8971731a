// SPDX-License-Identifier: MIT
// posemorph-bake sheet RIG.pmrig: a contact sheet of frames across pose space.
#include "commands.h"

#include <algorithm>
#include <optional>

#include "command_args.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/command_line.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/drawing_folder.h"
#include "posemorph/rig.h"
#include "preview.h"
#include "textured_sheet.h"

namespace posemorph::bake::cli {

namespace {

// --tint R,G,B[,A] and --part-opacity NAME=A (repeatable), each in 0..1.
SheetColour ReadSheetColour(const Args& args, const Rig& rig) {
  SheetColour out;
  if (const std::string* t = args.Get("--tint")) {
    const auto n = ParseNumbers(*t, ',');
    if (!n || n->size() < 3 || n->size() > 4 ||
        std::any_of(n->begin(), n->end(), [](double c) { return !(c >= 0 && c <= 1); }))
      throw UsageError("--tint wants R,G,B or R,G,B,A, each in 0..1");
    out.colour = {float((*n)[0]), float((*n)[1]), float((*n)[2]), n->size() == 4 ? float((*n)[3]) : 1.0f};
  }
  for (const auto& [name, value] : args.options) {
    if (name != "--part-opacity") continue;
    const std::size_t eq = value.find('=');
    const auto a = eq == std::string::npos ? std::nullopt : ParseNumber(value.substr(eq + 1));
    if (!a || !(*a >= 0 && *a <= 1)) throw UsageError("--part-opacity wants NAME=A, A in 0..1");
    int found = -1;
    for (std::uint32_t p = 0; p < rig.part_count() && rig.part_count() > 1; ++p)
      if (std::string(rig.part(p).name.data, rig.part(p).name.size) == value.substr(0, eq)) found = int(p);
    if (found < 0)
      throw UsageError(rig.part_count() > 1 ? "--part-opacity: the rig has no part '" + value.substr(0, eq) + "'"
                                            : std::string("--part-opacity: the rig has no parts"));
    out.part_opacities.resize(rig.part_count(), 1.0f);
    out.part_opacities[std::size_t(found)] = float(*a);
  }
  return out;
}

}  // namespace

int SheetCommand(const std::vector<std::string>& a, std::size_t from, std::ostream& out) {
  const Args args = Args::Parse(
      a, from,
      {"-o", "--columns", "--rows", "--sigma", "--images", "--filter", "--channel", "--tint", "--part-opacity"},
      {"--no-weight-limit", "--no-shear-limit", "--linear", "--textured"});
  if (args.positional.empty()) throw UsageError("no rig file given");
  const std::string* output = args.Get("-o");
  const bool textured = args.switches.count("--textured") > 0;
  if (!output || Extension(*output) != (textured ? "png" : "svg"))
    throw UsageError(textured ? "sheet --textured needs -o OUT.png" : "sheet needs -o OUT.svg");
  if (!textured && (args.Get("--images") || args.Get("--filter") || args.Get("--channel") || args.Get("--tint") ||
                    args.Get("--part-opacity")))
    throw UsageError("--images, --filter, --channel, --tint and --part-opacity go with --textured");
  const int columns = args.Get("--columns") ? CountOption("--columns", *args.Get("--columns"), 2, 32) : 7;
  const int rows = args.Get("--rows") ? CountOption("--rows", *args.Get("--rows"), 1, 32) : 5;
  const Rig rig = LoadRigFile(args.positional);
  if (textured) {
    TextureFilter filter = rig.texture_filter();
    if (const std::string* f = args.Get("--filter")) {
      if (*f != "linear" && *f != "nearest") throw UsageError("--filter wants linear or nearest");
      filter = *f == "nearest" ? TextureFilter::kNearest : TextureFilter::kLinear;
    }
    std::string images = DefaultDrawingFolder(args.positional, rig);
    if (const std::string* i = args.Get("--images")) images = *i;
    std::uint32_t channel = 0;
    if (const std::string* c = args.Get("--channel")) {
      const int found = rig.FindChannel(c->c_str());
      if (found < 0)
        throw BakeError(args.positional, rig.channel_count() < 2
                                             ? "has one control channel; --channel names one of several"
                                             : "has no channel '" + *c + "'");
      channel = std::uint32_t(found);
    }
    const SheetColour colour = ReadSheetColour(args, rig);
    const std::vector<RgbaImage> drawings = ReadPoseDrawings(rig, args.positional, images);
    const std::vector<std::vector<RgbaImage>> attached = ReadAttachmentDrawings(rig, args.positional, images);
    TexturedSheetLayout layout;
    const RgbaImage sheet = TexturedSheet(rig, drawings, columns, rows, ReadEvalOptions(args), filter, 160, &layout,
                                          channel, attached, colour);
    WriteFileAtomic(*output, EncodePng(sheet, *output));
    const std::string name(rig.channel_name(channel).data, rig.channel_name(channel).size);
    out << "wrote " << *output << " (" << sheet.width << " x " << sheet.height << ": "
        << rig.channel_rig(channel)->pose_count() << " poses"
        << (rig.channel_count() > 1 ? " of channel '" + name + "', the others at their first pose" : "") << ", then "
        << columns << "x" << layout.rows << " samples, drawings sampled "
        << (filter == TextureFilter::kNearest ? "nearest" : "linear") << ")\n";
    return 0;
  }
  WriteText(*output,
            ContactSheetSvg(rig, args.positional + ": poses across pose space", columns, rows, ReadEvalOptions(args)));
  out << "wrote " << *output << " (" << rig.pose_count() << " poses, " << columns << "x" << rows << " samples)\n";
  return 0;
}

}  // namespace posemorph::bake::cli
