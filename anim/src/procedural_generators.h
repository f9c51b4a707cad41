// The procedural meshes a scene may name ("mesh": {"procedural": NAME, "parameters": {...}}):
// one registry entry per generator with the parameters it reads, whether it brings its own rig
// description (a scene's rig "from": "procedural"), the colour its material gets, and how it
// is made. Scene reading (scene_file.cpp) and building (scene_build.cpp) both ask it.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "wirerig/anim/scene.h"
#include "wirerig/rig/rig_description.h"

namespace wirerig::detail {

struct GeneratedMesh {
  Mesh mesh;
  RigDescription description;  // the generator's own (the octopus and the props), else empty
};

struct ProceduralGenerator {
  std::string_view name;
  std::vector<std::string> parameters;  // every parameter it reads; the rest keep defaults
  bool describes_rig = false;           // brings its own rig description
  Vec4 base_color;                      // linear RGBA of its matte material
  // Errors name the parameter ("/mesh/parameters/height: must be a positive length (m)").
  Result<GeneratedMesh> (*generate)(const MeshSource& source) = nullptr;
};

std::span<const ProceduralGenerator> ProceduralGenerators();
const ProceduralGenerator* FindProceduralGenerator(std::string_view name);
// "octopus, cylinder, ..." (every generator), or only those that describe their rig.
std::string ProceduralGeneratorNames(bool describing_rig_only);

}  // namespace wirerig::detail
