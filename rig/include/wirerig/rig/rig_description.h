// RigDescription: how a mesh is divided into parts for rigging (paper section 2.1). Each part
// has a rough central curve, from the user's JSON description, from the asset's skeleton
// (one part per bone, skeleton_description.h), or found automatically from the mesh's curve
// skeleton (curve_skeleton.h).
//
// Rules (checked by ValidateRigDescription): part names are unique and not empty; every
// central curve has at least 2 finite points, consecutive points distinct; profile_count >= 2;
// 3 <= points_per_profile <= 1024; a parent names an earlier part; exactly the first part has
// no parent; parents never form a cycle; joints follow ValidateJointDescription; vertex weights,
// when present, are one per welded vertex and never name a skinless part.
// A skinless part ("skin": false, a bone such as a clavicle) has a central curve of exactly 2
// points (its rigid bone, from its joint to its end), no profiles, no mesh parts and no
// vertices; it is not the root and has at least one child (its skin is its children's and its
// nearest skinned ancestor's).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "wirerig/io/result.h"
#include "wirerig/rig/joint_description.h"
#include "wirerig/rig/mesh_import.h"
#include "wirerig/runtime/material.h"

namespace wirerig {

struct PartDescription {
  std::string name;
  // Rough central curve, root end first (the end attached to the parent), metres in the
  // converted mesh frame (+Y up).
  std::vector<Vec3> central_curve;
  int profile_count = 12;       // profile curves along the part (0 when skinless)
  int points_per_profile = 24;  // rays cast per profile
  std::string parent;           // empty for the root part
  // Optional: only these mesh parts (by MeshPart::name) belong to this part.
  std::vector<std::string> mesh_parts;
  JointDescription joint;  // how it turns on its parent (joint_description.h)
  bool skin = true;        // false: a skinless bone (profile counts 0, no vertices)
};

// The most parts a rig may have (a description or a rig file): building is quadratic in them
// (20,000 parts ran for minutes); a character has tens.
inline constexpr std::size_t kMaxRigParts = 1024;
// The most profile points (rays cast) a rig may ask for, all parts together: two parts at their
// largest (4096 profiles of 1024 points). Without it 1024 such parts asked for 4 x 10^9 rays.
inline constexpr std::size_t kMaxRigProfilePoints = std::size_t(2) * 4096 * 1024;

struct RigDescription {
  std::filesystem::path mesh;  // the mesh file; relative paths are relative to the description
  ImportOptions import;        // up axis and unit overrides for the mesh
  Material material{0.1e6, 0.45, 1060.0};  // default material of every wire (soft tissue)
  std::vector<PartDescription> parts;
  // Mesh parts (by MeshPart::name) that follow the rig but never catch profile rays, such as
  // eyes inside a head; their vertices go to the nearest visible part like any other.
  std::vector<std::string> passive_mesh_parts;
  // Optional, from skin weights: vertex_part[w] is the part index of welded vertex w.
  std::vector<int> vertex_part;
  // Clean the nearest-curve assignment (part_assignment.h): a child part's vertices far from
  // its curve go to the nearest part above or beside it, and small islands of a part's skin
  // inside another's join the part around them. Automatic descriptions set it; a written
  // description keeps the nearest-curve assignment unless it asks ("clean_assignment": true).
  bool clean_assignment = false;
};

// Errors read "<json pointer>: <reason>".
Result<RigDescription> ParseRigDescription(const nlohmann::json& document);
// Reads the file; errors read "<path>: <json pointer>: <reason>". Resolves `mesh` against the
// file's folder.
Result<RigDescription> LoadRigDescription(const std::filesystem::path& path);
// Empty when valid, else "<json pointer>: <reason>" naming the first broken rule.
std::string ValidateRigDescription(const RigDescription& description);

}  // namespace wirerig
