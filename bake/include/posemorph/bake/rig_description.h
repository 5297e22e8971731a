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

struct PoseDescription {
  std::string name;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> vertices;
  std::string image;                      // as written in the description
  std::vector<Eigen::Vector2f> uvs;       // empty, or one per vertex
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

// Checks everything the math needs (counts, indices, orientation, finiteness,
// connectivity, distinct pose points); throws BakeError naming the pose and
// triangle. Reorients a mesh given clockwise so pose 0 is counter-clockwise.
void ValidateRigDescription(RigDescription& rig);

}  // namespace posemorph::bake
