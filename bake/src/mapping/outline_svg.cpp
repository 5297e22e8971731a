// SPDX-License-Identifier: MIT
// Drawing (SVG) -> outline: one <path> or <polygon>, curves flattened.
// The XML is read with tinyxml2; only the path-data grammar is parsed here.
#include <tinyxml2.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "geometry.h"
#include "posemorph/bake/mapping/outline_svg.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/input_file.h"

namespace posemorph::bake::mapping {
namespace {

struct PathScanner {
  const std::string& d;
  const ErrorSource& source;
  std::size_t i = 0;

  void SkipSeparators() {
    while (i < d.size() && (std::isspace(static_cast<unsigned char>(d[i])) || d[i] == ',')) ++i;
  }
  bool AtNumber() {
    SkipSeparators();
    if (i >= d.size()) return false;
    const char c = d[i];
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  double Number() {
    SkipSeparators();
    const char* begin = d.c_str() + i;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v))
      throw source.Error("path data: expected a number at character " + std::to_string(i));
    // The mapping refuses outlines beyond +-1e9 anyway; refusing larger
    // numbers here keeps every sum and midpoint of the flattening finite.
    if (!(std::abs(v) <= 1e9))
      throw source.Error("path data: the number at character " + std::to_string(i) +
                         " lies beyond +-1e9 drawing units");
    i += std::size_t(end - begin);
    return v;
  }
};

void FlattenCubic(const Point& p0, const Point& p1, const Point& p2, const Point& p3, double tol, int depth,
                  Polygon& out) {
  const Point chord = p3 - p0;
  const double len = chord.norm();
  auto dist = [&](const Point& q) {
    if (len == 0) return (q - p0).norm();
    return std::abs(chord.x() * (q - p0).y() - chord.y() * (q - p0).x()) / len;
  };
  if (depth >= 18 || std::max(dist(p1), dist(p2)) <= tol) {
    out.push_back(p3);
    return;
  }
  const Point a = (p0 + p1) / 2, b = (p1 + p2) / 2, c = (p2 + p3) / 2;
  const Point ab = (a + b) / 2, bc = (b + c) / 2, mid = (ab + bc) / 2;
  FlattenCubic(p0, a, ab, mid, tol, depth + 1, out);
  FlattenCubic(mid, bc, c, p3, tol, depth + 1, out);
}

Polygon Deduplicated(Polygon p) {
  Polygon out;
  for (const Point& q : p)
    if (out.empty() || (q - out.back()).norm() > 0) out.push_back(q);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

std::string FormatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

double Length(const char* text) {  // "120", "120px"
  if (!text) return 0;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  return end == text ? 0 : v;
}

// The pen along path data: where it is, where its subpath started, the
// last control point (for S and T), the previous command.
struct Pen {
  PathScanner& s;
  double tol;
  const ErrorSource& source;
  Polygon& out;
  Point cur{0, 0}, start{0, 0}, last_control{0, 0};
  char previous = 0;
  bool begun = false;

  Point Pt(bool rel) {
    const double x = s.Number(), y = s.Number();
    return rel ? Point(cur + Point(x, y)) : Point(x, y);
  }

  // One command (`up`: its upper-case letter) with its arguments.
  void Draw(char cmd, char up, bool rel) {
    switch (up) {
      case 'M':
        cur = start = Pt(rel);
        out.push_back(cur);
        begun = true;
        break;
      case 'L':
        cur = Pt(rel);
        out.push_back(cur);
        break;
      case 'H': {
        const double x = s.Number();
        cur = Point(rel ? cur.x() + x : x, cur.y());
        out.push_back(cur);
        break;
      }
      case 'V': {
        const double y = s.Number();
        cur = Point(cur.x(), rel ? cur.y() + y : y);
        out.push_back(cur);
        break;
      }
      case 'C':
      case 'S': {
        Point c1;
        const char pu = char(std::toupper(static_cast<unsigned char>(previous)));
        if (up == 'C')
          c1 = Pt(rel);
        else
          c1 = (pu == 'C' || pu == 'S') ? Point(2 * cur - last_control) : cur;
        const Point c2 = Pt(rel), end = Pt(rel);
        FlattenCubic(cur, c1, c2, end, tol, 0, out);
        last_control = c2;
        cur = end;
        break;
      }
      case 'Q':
      case 'T': {
        Point c;
        const char pu = char(std::toupper(static_cast<unsigned char>(previous)));
        if (up == 'Q')
          c = Pt(rel);
        else
          c = (pu == 'Q' || pu == 'T') ? Point(2 * cur - last_control) : cur;
        const Point end = Pt(rel);
        FlattenCubic(cur, cur + 2.0 / 3 * (c - cur), end + 2.0 / 3 * (c - end), end, tol, 0, out);
        last_control = c;
        cur = end;
        break;
      }
      case 'Z':
        cur = start;
        break;
      case 'A':
        throw source.Error("path data: arcs (A) are not supported in an outline; use curves (C, Q)");
      default:
        throw source.Error(std::string("path data: unknown command '") + cmd + "'");
    }
  }
};

}  // namespace

Polygon FlattenSvgPath(const std::string& d, double tol, const ErrorSource& source) {
  if (!(tol > 0)) throw source.Error("curve flattening tolerance must be positive");
  PathScanner s{d, source};
  Polygon out;
  Pen pen{s, tol, source, out};
  char& previous = pen.previous;
  const bool& begun = pen.begun;
  for (;;) {
    s.SkipSeparators();
    if (s.i >= d.size()) break;
    char cmd = d[s.i];
    if (std::isalpha(static_cast<unsigned char>(cmd))) {
      ++s.i;
    } else if (previous != 0 && previous != 'Z' && previous != 'z') {
      cmd = previous == 'M' ? 'L' : previous == 'm' ? 'l' : previous;  // repeated arguments
    } else {
      throw source.Error("path data: expected a command at character " + std::to_string(s.i));
    }
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const char up = char(std::toupper(static_cast<unsigned char>(cmd)));
    if (!begun && up != 'M') throw source.Error("path data must start with M");
    if (begun && up == 'M') break;  // the outline is the first subpath
    pen.Draw(cmd, up, rel);
    previous = cmd;
    if (out.size() > kMaxOutlinePoints)
      throw source.Error("the path flattens to more than " + std::to_string(kMaxOutlinePoints) +
                         " outline points (the limit; mapping.curve_tolerance " + FormatNumber(tol) +
                         " sets how finely curves are cut)");
    if (up == 'Z') {
      s.SkipSeparators();
      if (s.i < d.size()) break;  // only the first closed subpath
    }
  }
  return Deduplicated(std::move(out));
}

namespace {

// The groups named `name` (inkscape:label or id), every group name in
// document order, and how many groups are Inkscape layers.
void FindGroups(const tinyxml2::XMLElement* root, const std::string& name,
                std::vector<const tinyxml2::XMLElement*>* matches, std::vector<std::string>* names,
                int* inkscape_layers) {
  std::vector<const tinyxml2::XMLElement*> stack{root};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    if (std::string(e->Name()) == "g") {
      const char* label = e->Attribute("inkscape:label");
      const char* id = e->Attribute("id");
      if ((label && name == label) || (id && name == id)) matches->push_back(e);
      if (e->Attribute("inkscape:groupmode", "layer")) ++*inkscape_layers;
      if (label) names->push_back(label);
      if (id && (!label || std::string(id) != label)) names->push_back(id);
    }
    std::vector<const tinyxml2::XMLElement*> children;
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) children.push_back(c);
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
  }
}

// The document's <svg> element, parsed into `doc`; BakeError if it is none.
const tinyxml2::XMLElement* SvgRoot(tinyxml2::XMLDocument& doc, const char* text, std::size_t size,
                                    const ErrorSource& source) {
  if (doc.Parse(text, size) != tinyxml2::XML_SUCCESS)
    throw source.Error(std::string("invalid SVG (XML): ") + doc.ErrorStr());
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "svg") throw source.Error("not an SVG document (no <svg> root)");
  return root;
}

}  // namespace

SvgOutline OutlineFromSvgText(const std::string& text, double tol, const ErrorSource& source, const SvgLayer& layer) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* root = SvgRoot(doc, text.c_str(), text.size(), source);

  SvgOutline result;
  if (const char* vb = root->Attribute("viewBox")) {
    std::string t(vb);
    for (char& c : t)
      if (c == ',') c = ' ';
    std::istringstream nums(t);
    double x, y, w, h;
    if (!(nums >> x >> y >> w >> h) || !(w > 0) || !(h > 0)) throw source.Error("viewBox is not \"x y width height\"");
    result.canvas_origin = Point(x, y);
    result.canvas_size = Point(w, h);
  } else {
    result.canvas_size = Point(Length(root->Attribute("width")), Length(root->Attribute("height")));
    if (!(result.canvas_size.x() > 0) || !(result.canvas_size.y() > 0))
      throw source.Error("the <svg> element needs a viewBox or width and height");
  }

  // The layer: a named group, or the whole document.
  const tinyxml2::XMLElement* top = root;
  if (!layer.name.empty()) {
    std::vector<const tinyxml2::XMLElement*> matches;
    std::vector<std::string> names;
    int inkscape_layers = 0;
    FindGroups(root, layer.name, &matches, &names, &inkscape_layers);
    if (matches.size() > 1)
      throw source.Error(std::to_string(matches.size()) + " groups are named '" + layer.name +
                         "' (inkscape:label or id): a layer's name must pick one");
    if (matches.size() == 1) {
      top = matches[0];
    } else if (layer.required || inkscape_layers > 1) {
      // A drawing in several layers, none of them the part's: taking its
      // first path would take another part's outline.
      std::string listed;
      for (std::size_t k = 0; k < names.size() && k < 16; ++k) listed += (k ? ", '" : "'") + names[k] + "'";
      throw source.Error("no layer or group is named '" + layer.name + "' (" +
                         (names.empty() ? std::string("the drawing names no group")
                                        : "its named groups: " + listed + (names.size() > 16 ? ", ..." : "")) +
                         ")" + (layer.required ? "" : "; name the part like its layer, or give the pose a \"layer\""));
    }
  }
  // Depth-first, document order; id="outline" wins.
  const tinyxml2::XMLElement* chosen = nullptr;
  const tinyxml2::XMLElement* first = nullptr;
  std::vector<const tinyxml2::XMLElement*> stack{top};
  while (!stack.empty() && !chosen) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    const std::string name = e->Name();
    if (name == "path" || name == "polygon") {
      if (!first) first = e;
      const char* id = e->Attribute("id");
      if (id && std::string(id) == "outline") chosen = e;
    }
    std::vector<const tinyxml2::XMLElement*> children;
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) children.push_back(c);
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
  }
  if (!chosen) chosen = first;
  if (!chosen)
    throw source.Error(top == root ? std::string("no <path> or <polygon> to take the outline from")
                                   : "layer '" + layer.name + "' has no <path> or <polygon> to take the outline from");
  for (const tinyxml2::XMLNode* n = chosen; n && n->ToElement(); n = n->Parent())
    if (n->ToElement()->Attribute("transform"))
      throw source.Error("the outline element (or a group around it) has a transform; apply it to the coordinates");

  if (std::string(chosen->Name()) == "path") {
    const char* d = chosen->Attribute("d");
    if (!d) throw source.Error("the outline <path> has no d attribute");
    result.outline = FlattenSvgPath(d, tol, source);
  } else {
    const char* pts = chosen->Attribute("points");
    if (!pts) throw source.Error("the outline <polygon> has no points attribute");
    const std::string spts(pts);
    PathScanner s{spts, source};
    Polygon p;
    while (s.AtNumber()) {
      const double x = s.Number(), y = s.Number();
      p.push_back({x, y});
    }
    result.outline = Deduplicated(std::move(p));
  }
  if (result.outline.size() < 3) throw source.Error("the outline has fewer than 3 distinct points");
  return result;
}

SvgOutline OutlineFromSvg(const std::string& path, double tol, const ErrorSource& source, const SvgLayer& layer) {
  const std::vector<unsigned char> bytes = ReadInputFile(path, kMaxTextFileBytes, "an SVG drawing", source);
  return OutlineFromSvgText(std::string(bytes.begin(), bytes.end()), tol, source, layer);
}

std::vector<std::string> SvgLayerNames(const std::string& path, const ErrorSource& source) {
  const std::vector<unsigned char> bytes = ReadInputFile(path, kMaxTextFileBytes, "an SVG drawing", source);
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* root = SvgRoot(doc, reinterpret_cast<const char*>(bytes.data()), bytes.size(), source);
  std::vector<std::string> names;
  for (const tinyxml2::XMLElement* g = root->FirstChildElement("g"); g; g = g->NextSiblingElement("g")) {
    const char* style = g->Attribute("style");
    if (style) {
      std::string compact;
      for (const char* c = style; *c; ++c)
        if (*c != ' ') compact += *c;
      if (compact.find("display:none") != std::string::npos) continue;
    }
    const char* label = g->Attribute("inkscape:label");
    const char* id = g->Attribute("id");
    const char* name = label && *label ? label : id;
    if (name && *name) names.emplace_back(name);
  }
  return names;
}

SvgOutline OutlineFromSvg(const std::string& path, double tol) { return OutlineFromSvg(path, tol, ErrorSource(path)); }

}  // namespace posemorph::bake::mapping
