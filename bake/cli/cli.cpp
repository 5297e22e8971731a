// SPDX-License-Identifier: MIT
// posemorph-bake: the usage text, the dispatch to a command, and how each
// kind of failure is reported.
#include "cli.h"

#include <new>
#include <stdexcept>

#include "command_args.h"
#include "commands.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/stage.h"

namespace posemorph::bake {

using namespace cli;

namespace {

const char kUsage[] =
    "usage:\n"
    "  posemorph-bake RIG.json [-o RIG.pmrig] [--precision compact|exact] [--max-error PX] [--allow-folds]\n"
    "        [--no-align] [--map-once] [--quiet] [--no-atlas]\n"
    "        bake a rig description (default output: RIG.pmrig; compact within 0.01 drawing pixels;\n"
    "        an in-between where a triangle turns over fails the bake unless --allow-folds; PNG drawings\n"
    "        align the interiors unless --no-align; where the in-betweens fold or the mesh is poor, the\n"
    "        drawings are mapped again in other ways unless --map-once; on a terminal, a bake over a\n"
    "        second shows its stage on a progress line; --quiet: no progress line and no report, only\n"
    "        warnings and errors; the drawings packed into texture pages RIG.page0.png ... beside the\n"
    "        rig unless --no-atlas)\n"
    "  posemorph-bake info RIG.pmrig [--images DIR] sizes, counts, factor fill, in-betweens, ghosting, pose points,\n"
    "                                             paths (the drawings for the ghosting from DIR, or where the bake\n"
    "                                             found them)\n"
    "  posemorph-bake eval RIG.pmrig (--at X,Y | --path NAME [--time T | --frames K]) -o OUT.svg|.json|.obj\n"
    "        [--sigma S] [--no-weight-limit] [--linear]\n"
    "  posemorph-bake sheet RIG.pmrig -o OUT.svg [--columns C] [--rows R] [--no-weight-limit] [--linear]\n"
    "  posemorph-bake sheet RIG.pmrig --textured -o OUT.png [--images DIR] [--filter linear|nearest] ...\n"
    "        [--channel NAME]   the same frames drawn with the drawings, cross-faded by the texture weights;\n"
    "        a rig with control channels: over channel NAME's pose space (default the first), the others at\n"
    "        their first pose, the attachments drawn too (eval and the SVG sheet show the first channel's parts)\n"
    "        [--tint R,G,B[,A]] [--part-opacity NAME=A]...   every frame tinted (multiplied) at opacity A, a\n"
    "        layered character's part NAME at its own opacity, as DrawListJob's colours and the viewer draw them\n"
    "  posemorph-bake init DRAWING... -o RIG.json [--name NAME] [--flatten] [--channels] [--force]\n"
    "        a description from the drawings (PNG or SVG, one per pose, named after the files; or POSE-PART.png,\n"
    "        one per part and pose: parts glued where drawn over each other; or layered .ora/.psd files, imported\n"
    "        beside RIG.json as by import): the first pose at the pad's centre, the others on the unit circle\n"
    "        clockwise from the top; says whether it bakes. --channels: each layered file one control channel\n"
    "        (named by the file, a group per pose; the first drives the body, the others' parts are glued to it)\n"
    "  posemorph-bake import LAYERED... -o DIR [--flatten]   OpenRaster (.ora) or Photoshop (.psd) files as PNG\n"
    "        drawings: one file per pose (its top-level layers or groups the parts) or one file whose top-level\n"
    "        groups are the poses; DIR/POSE-PART.png per part and pose (POSE.png with --flatten or one layer)\n"
    "  posemorph-bake import SHEET.png -o DIR (--frames COLUMNSxROWS | --cell WIDTHxHEIGHT) [--name NAME]\n"
    "        a sprite sheet's frames, left to right and top to bottom, as DIR/NAME_K.png (NAME: the sheet's\n"
    "        name), each its whole cell, so the frames keep their registration; empty cells left out\n"
    "  posemorph-bake deform RIG.json --pose NAME -o MESH.json  write a deformation-made pose as a plain mesh file\n"
    "  posemorph-bake outline RIG.json -o DIR [--part NAME]   per drawn pose, DIR/INDEX-NAME.png: the drawing scaled "
    "up with\n"
    "        the outline the bake traces, the mesh boundary, the landmarks numbered and their tolerance, the start\n";

// The file a command works on, for messages that do not name one.
std::string InputOf(const std::vector<std::string>& a) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == "info" || a[i] == "eval" || a[i] == "sheet" || a[i] == "deform" || a[i] == "outline" ||
        a[i] == "bake" || a[i] == "init" || a[i] == "import")
      continue;
    if (!a[i].empty() && a[i][0] == '-') {
      ++i;  // an option and its value
      continue;
    }
    return a[i];
  }
  return "posemorph-bake";
}

}  // namespace

int RunBakeCommand(const std::vector<std::string>& a, std::ostream& out, std::ostream& err) {
  // Where a failure without context of its own happened (out of memory, an
  // unexpected exception): the bake stage, or the command.
  auto where = [&]() {
    const std::string stage = CurrentBakeStage();
    return stage.empty() ? std::string() : " while " + stage;
  };
  try {
    BakeStage command("running the command");
    if (a.empty()) throw UsageError("no command given");
    const std::string& cmd = a[0];
    if (cmd == "-h" || cmd == "--help" || cmd == "help") {
      out << kUsage;
      return 0;
    }
    if (cmd == "info") return InfoCommand(a, 1, out);
    if (cmd == "eval") return EvalCommand(a, 1, out);
    if (cmd == "sheet") return SheetCommand(a, 1, out);
    if (cmd == "deform") return DeformCommand(a, 1, out);
    if (cmd == "outline") return OutlineCommand(a, 1, out, err);
    if (cmd == "init") return InitCommand(a, 1, out, err);
    if (cmd == "import") return ImportCommand(a, 1, out, err);
    if (cmd == "bake") return BakeCommand(a, 1, out, err);
    return BakeCommand(a, 0, out, err);
  } catch (const UsageError& e) {
    // One line naming the problem; the whole usage only when nothing was given.
    if (a.empty())
      err << kUsage;
    else
      err << "posemorph-bake: " << Printable(e.what()) << " (posemorph-bake --help lists the commands and options)\n";
    return 2;
  } catch (const BakeError& e) {
    err << "posemorph-bake: error: " << Printable(e.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    err << "posemorph-bake: error: " << Printable(InputOf(a)) << ": out of memory" << where()
        << " (the input asks for more than this machine has)\n";
    return 1;
  } catch (const std::exception& e) {
    err << "posemorph-bake: error: " << Printable(InputOf(a)) << ": internal error" << where() << ": "
        << Printable(e.what()) << "\n";
    return 1;
  }
}

}  // namespace posemorph::bake
