// SPDX-License-Identifier: MIT
#include "command_args.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/command_line.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake::cli {

std::vector<unsigned char> ReadBytes(const std::string& path) {
  return ReadInputFile(path, kMaxRigFileBytes, "a baked rig");
}

Rig LoadRigFile(const std::string& path) {
  const std::vector<unsigned char> bytes = ReadBytes(path);
  Rig rig;
  Error err;
  if (!LoadRig(bytes.data(), bytes.size(), &rig, &err))
    throw BakeError(path, std::string("not a valid rig (") + ErrorCodeName(err.code) + "): " + err.message);
  return rig;
}

void WriteText(const std::string& path, const std::string& text) {
  WriteFileAtomic(path, std::vector<unsigned char>(text.begin(), text.end()));
}

std::string Extension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

double NumberOption(const std::string& flag, const std::string& s) {
  const std::optional<double> v = ParseNumber(s);
  if (!v) throw UsageError(flag + ": \"" + s + "\" is not a finite number");
  return *v;
}

int CountOption(const std::string& flag, const std::string& s, int lo, int hi) {
  NumberOption(flag, s);
  const std::optional<long long> v = ParseWholeNumber(s, lo, hi);
  if (!v) throw UsageError(flag + ": expected a whole number in " + std::to_string(lo) + ".." + std::to_string(hi));
  return int(*v);
}

EvalOptions ReadEvalOptions(const Args& args) {
  EvalOptions o;
  if (const std::string* s = args.Get("--sigma")) {
    o.sigma = NumberOption("--sigma", *s);
    if (o.sigma < 0 || o.sigma > 1) throw UsageError("--sigma must be in [0, 1]");
  }
  // --no-shear-limit: the deprecated name of --no-weight-limit.
  o.limit_weights = !args.switches.count("--no-weight-limit") && !args.switches.count("--no-shear-limit");
  o.interpolation = args.switches.count("--linear") ? Interpolation::kLinear : Interpolation::kRigid;
  return o;
}

// A message as the terminal will show it: control characters (and UTF-8's
// C1 controls) escaped as \xNN, so that a name in a file cannot drive the
// terminal; longer than 1000 characters, its middle elided (a 900 KB pose
// name once came out whole), keeping the file at the start and the problem
// at the end.
std::string Printable(const std::string& message) {
  std::string s;
  char hex[8];
  for (std::size_t i = 0; i < message.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(message[i]);
    const bool c1 = c == 0xC2 && i + 1 < message.size() && static_cast<unsigned char>(message[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(message[i + 1]) <= 0x9F;
    if (c < 0x20 || c == 0x7F) {
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      s += hex;
    } else if (c1) {
      std::snprintf(hex, sizeof(hex), "\\x%02x", static_cast<unsigned char>(message[++i]));
      s += hex;
    } else {
      s += char(c);
    }
  }
  const std::size_t keep = 480;
  if (s.size() > 2 * keep + 40)
    s = s.substr(0, keep) + " [... " + std::to_string(s.size() - 2 * keep) + " characters ...] " +
        s.substr(s.size() - keep);
  return s;
}

}  // namespace posemorph::bake::cli
