// SPDX-License-Identifier: MIT
// What posemorph-bake's commands share: argument parsing, reading a rig,
// writing a text file, and printing a message safely.
#pragma once
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "posemorph/rig.h"
#include "preview.h"

namespace posemorph::bake::cli {

// A mistake on the command line: exit status 2, one line.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Flags after the positional argument: "--name value" pairs and switches.
struct Args {
  std::string positional;
  std::vector<std::pair<std::string, std::string>> options;
  std::set<std::string> switches;

  static Args Parse(const std::vector<std::string>& a, std::size_t from, const std::set<std::string>& with_value,
                    const std::set<std::string>& switch_names) {
    Args out;
    for (std::size_t i = from; i < a.size(); ++i) {
      if (with_value.count(a[i])) {
        if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
        out.options.push_back({a[i], a[i + 1]});
        ++i;
      } else if (switch_names.count(a[i])) {
        out.switches.insert(a[i]);
      } else if (!a[i].empty() && a[i][0] == '-') {
        throw UsageError("unknown option " + a[i]);
      } else if (out.positional.empty()) {
        out.positional = a[i];
      } else {
        throw UsageError("unexpected argument " + a[i]);
      }
    }
    return out;
  }
  const std::string* Get(const std::string& name) const {
    for (const auto& [k, v] : options)
      if (k == name) return &v;
    return nullptr;
  }
};

std::vector<unsigned char> ReadBytes(const std::string& path);     // a rig file, within kMaxRigFileBytes
Rig LoadRigFile(const std::string& path);                          // throws BakeError naming the file
void WriteText(const std::string& path, const std::string& text);  // atomically
std::string Extension(const std::string& path);                    // lower case, without the dot; "" if none
// A flag's value as bake::ParseNumber / ParseWholeNumber (command_line.h)
// read it; UsageError naming the flag otherwise.
double NumberOption(const std::string& flag, const std::string& s);
int CountOption(const std::string& flag, const std::string& s, int lo, int hi);
EvalOptions ReadEvalOptions(const Args& args);  // --sigma, --no-weight-limit, --linear
std::string Printable(const std::string& message);

}  // namespace posemorph::bake::cli
