// The raw input of a bake: N poses of one triangle mesh, their points in pose
// space, optional drawings, bake parameters, animation paths. Schema:
// bake/RIG_DESCRIPTION.md.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace posemorph::bake {

// A handle of a deformation: a vertex (given by index, or by a point on the
// source mesh that grabs its nearest vertex) and where it goes.
struct HandleDescription {
  bool by_vertex = false;
  std::uint32_t vertex = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
};

// "This pose is pose `from` with these handles dragged" (paper section 3.2).
struct DeformDescription {
  std::string from;
  std::vector<HandleDescription> handles;
};

struct PoseDescription {
  std::string name;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> vertices;
  std::string image;                      // as written in the description
  std::vector<Eigen::Vector2f> uvs;       // empty, or one per vertex
  bool deformed = false;                  // vertices come from `deform` (ResolveDeformedPoses)
  DeformDescription deform;
};

struct PathDescription {
  std::string name;
  bool loop = false;
  bool catmull_rom = false;
  std::vector<std::array<double, 3>> keys;  // t, x, y
};

struct BakeParameters {
  int grid_resolution = 64;  // cells along the longer side of the pose-space domain
  double margin = 1.0;       // domain = points' bounding box grown by margin x its larger side
  // Weight of the gradient term relative to the biharmonic one; the field
  // levels out beyond about spread * sqrt(3 / epsilon) from the points.
  double epsilon = 3.0;
  double sigma = 0.25;       // default texture sharpening
};

struct RigDescription {
  std::string file;  // where it came from, for messages
  std::string name;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<PoseDescription> poses;
  BakeParameters parameters;
  std::vector<PathDescription> paths;
};

// Reads and parses a description; relative mesh paths resolve against its
// folder. Throws BakeError naming the file and the problem.
RigDescription ReadRigDescription(const std::string& path);
RigDescription ParseRigDescription(const std::string& json_text, const std::string& file,
                                   const std::string& base_dir);

// Computes the vertices of every pose made by deformation (in dependency
// order), copying its source's drawing and uvs. Throws BakeError naming the
// pose and the problem: unknown or cyclic source, fewer than 2 handles, a
// handle off the mesh, coinciding handles, a triangle the deformation flips.
void ResolveDeformedPoses(RigDescription& rig);

// Checks everything the math needs (counts, indices, orientation, finiteness,
// connectivity, distinct pose points); throws BakeError naming the pose and
// triangle. Reorients a mesh given clockwise so pose 0 is counter-clockwise.
void ValidateRigDescription(RigDescription& rig);

}  // namespace posemorph::bake
