// BakedAnimation: a clip sampled at fixed keys, ready for export. Positions and normals are per
// render vertex of the source Mesh (#V, texture seams split), in floats as glTF stores them.
// The spine data lets the skin exporter build a joint chain per spine wire (a joint per spine
// sample) and animate it with the deformed spine frames.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "wirerig/runtime/conventions.h"

namespace wirerig {

using Vec3f = Eigen::Vector3f;
using Vec4f = Eigen::Vector4f;

// One spine wire sampled over the keys. A frame is stored as the rotation whose columns are
// (normal, binormal, tangent) of the spine frame at that sample, world axes.
struct BakedSpine {
  std::string name;      // the part's name
  int parent = -1;       // index into BakedAnimation::spines, -1 for the root
  int parent_joint = 0;  // sample of the parent's spine this spine hangs from (its attachment)
  std::vector<Vec3> rest_points;     // #S samples at rest, m
  std::vector<Quat> rest_rotations;  // #S
  std::vector<Vec3> points;          // #K x #S, key-major: points[k * S + s]
  std::vector<Quat> rotations;       // #K x #S, key-major
  std::size_t SampleCount() const { return rest_points.size(); }
};

struct BakedAnimation {
  std::string name;                // the clip's name
  double fps = 30.0;               // keys per second
  std::vector<double> times;       // #K key times, s, strictly increasing from 0
  std::size_t vertex_count = 0;    // #V render vertices
  std::vector<Vec3f> positions;    // #K x #V, key-major: positions[k * V + v], m
  std::vector<Vec3f> normals;      // #K x #V unit normals, or empty
  std::vector<BakedSpine> spines;  // one per rig part, parents first
  // Skin of every render vertex on the spine joints, at most 4 influences, normalized.
  // Joints are numbered over all spines in order, samples in order (spine 0's samples first).
  std::vector<std::array<std::uint32_t, 4>> skin_joints;  // #V
  std::vector<Vec4f> skin_weights;                        // #V, sum to 1
  // What the bake found, for the modeller: parts whose deflection exceeded their length at
  // some key (DeflectionWarning). Not exported.
  std::vector<std::string> warnings;

  std::size_t KeyCount() const { return times.size(); }
};

}  // namespace wirerig
