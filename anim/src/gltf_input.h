// Checks ExportGltf's input before anything is built or written (the refusals listed on
// ExportGltf). Messages name the field: "bake.positions[12]: not finite".
#pragma once

#include <optional>
#include <string>

#include "wirerig/anim/baked_animation.h"
#include "wirerig/anim/gltf_export.h"
#include "wirerig/rig/mesh.h"

namespace wirerig::gltf {

// The first problem found, or nothing when the input can be exported in `mode`.
std::optional<std::string> CheckExportInput(const Mesh& mesh, const BakedAnimation& bake,
                                            GltfAnimationMode mode);

}  // namespace wirerig::gltf
