// The C API (wirerig.h) over the runtime: rig assets, per-thread contexts, evaluation.
#include "wirerig/wirerig.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "wirerig/runtime/clip_asset.h"
#include "wirerig/runtime/joint.h"
#include "wirerig/runtime/rig_asset.h"
#include "wirerig/runtime/rig_evaluation.h"

struct wr_rig {
  wirerig::RigAsset asset;
  std::shared_ptr<const wirerig::RigEvaluationPlan> plan;  // shared by every context
};

struct wr_clip {
  wirerig::SampledClip clip;
};

struct wr_context {
  const wr_rig* rig = nullptr;
  std::vector<wirerig::Quat> transform_rotation;       // per part
  std::vector<wirerig::Vec3> transform_translation;    // per part
  std::vector<wirerig::Vec3> joint_degrees;            // per part
  std::vector<std::vector<wirerig::PointLoad>> loads;  // per part
  std::vector<wirerig::PartPose> poses;                // per part, filled at evaluation
  wirerig::RigWorkspace workspace;
  const wr_clip* clip = nullptr;  // playing, or null
  double clip_time = 0.0;
  wirerig::ClipPlaybackBuffers clip_buffers;  // made for `clip`
  wirerig::NormalMode normal_mode = wirerig::NormalMode::kFromTriangles;
};

namespace {

thread_local std::string last_error;

wr_status Fail(wr_status status, std::string message) {
  last_error = std::move(message);
  return status;
}

// `status` with "<function>: <what>" as the message, or an empty message when even that cannot
// be allocated: never throws.
wr_status Caught(wr_status status, const char* function, const char* what) noexcept {
  try {
    last_error.assign(function).append(": ").append(what);
  } catch (...) {
    last_error.clear();
  }
  return status;
}

// Runs `body`, turning an allocation failure or any other exception into a status: nothing
// escapes across the C boundary.
template <class Body>
wr_status Guarded(const char* function, Body&& body) {
  try {
    last_error.clear();
    return body();
  } catch (const std::bad_alloc&) {
    return Caught(WR_OUT_OF_MEMORY, function, "out of memory");
  } catch (const std::exception& e) {
    return Caught(WR_INVALID_ARGUMENT, function, e.what());
  }
}

bool Finite(const float* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

wr_status CheckPart(const char* function, const wr_context* context, uint32_t part) {
  if (context == nullptr)
    return Fail(WR_INVALID_ARGUMENT, std::string(function) + ": context is null");
  if (part >= context->rig->asset.model.parts.size())
    return Fail(WR_INVALID_ARGUMENT, std::string(function) + ": part " + std::to_string(part) +
                                         " is out of range (the rig has " +
                                         std::to_string(context->rig->asset.model.parts.size()) +
                                         " parts)");
  return WR_OK;
}

// The bytes of a regular file of at most 2 GiB, or a status with the message set. What is not a
// regular file (a directory, a FIFO that would block, a device that never ends) is refused by
// its type before it is opened.
wr_status ReadFile(const char* path, std::vector<std::uint8_t>* bytes) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
    return Fail(WR_IO_ERROR, std::string(path) + ": no such file");
  if (!std::filesystem::is_regular_file(status))
    return Fail(WR_IO_ERROR, std::string(path) + ": not a regular file");
  if (std::filesystem::file_size(path, error) > (std::uintmax_t(1) << 31) || error)
    return Fail(WR_IO_ERROR, std::string(path) + ": larger than 2 GiB, or of unknown size");
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) return Fail(WR_IO_ERROR, std::string(path) + ": cannot open");
  const std::streamoff size = file.tellg();
  if (size < 0) return Fail(WR_IO_ERROR, std::string(path) + ": not a regular file");
  bytes->resize(static_cast<std::size_t>(size));
  file.seekg(0);
  if (!file.read(reinterpret_cast<char*>(bytes->data()), size))
    return Fail(WR_IO_ERROR, std::string(path) + ": cannot read");
  return WR_OK;
}

}  // namespace

extern "C" {

const char* wr_last_error(void) { return last_error.c_str(); }

wr_status wr_rig_load_memory(const void* bytes, size_t size, wr_rig** out) {
  return Guarded("wr_rig_load_memory", [&] {
    if ((bytes == nullptr && size > 0) || out == nullptr)  // no bytes: refused as an asset
      return Fail(WR_INVALID_ARGUMENT,
                  "wr_rig_load_memory: out, and bytes when size > 0, are required");
    auto rig = std::make_unique<wr_rig>();
    const wirerig::Status status = wirerig::ParseRigAsset(
        std::span(static_cast<const std::uint8_t*>(bytes), size), &rig->asset);
    if (!status) return Fail(WR_BAD_ASSET, "rig asset: " + wirerig::ToString(status));
    rig->plan = wirerig::MakeRigEvaluationPlan(rig->asset.model);
    *out = rig.release();
    return WR_OK;
  });
}

wr_status wr_rig_load_file(const char* path, wr_rig** out) {
  return Guarded("wr_rig_load_file", [&] {
    if (path == nullptr || out == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_rig_load_file: path and out are required");
    std::vector<std::uint8_t> bytes;
    if (wr_status read = ReadFile(path, &bytes); read != WR_OK) return read;
    const wr_status status = wr_rig_load_memory(bytes.data(), bytes.size(), out);
    if (status != WR_OK) last_error = std::string(path) + ": " + last_error;
    return status;
  });
}

void wr_rig_free(wr_rig* rig) { delete rig; }

uint32_t wr_rig_part_count(const wr_rig* rig) {
  return rig ? uint32_t(rig->asset.model.parts.size()) : 0;
}

const char* wr_rig_part_name(const wr_rig* rig, uint32_t part) {
  if (rig == nullptr || part >= rig->asset.model.parts.size()) return nullptr;
  return rig->asset.model.parts[part].name.c_str();
}

int32_t wr_rig_find_part(const wr_rig* rig, const char* name) {
  if (rig == nullptr || name == nullptr) return -1;
  const auto& parts = rig->asset.model.parts;
  for (std::size_t p = 0; p < parts.size(); ++p)
    if (parts[p].name == name) return int32_t(p);
  return -1;
}

int32_t wr_rig_part_parent(const wr_rig* rig, uint32_t part) {
  if (rig == nullptr || part >= rig->asset.model.parts.size()) return -1;
  return rig->asset.model.parts[part].parent;
}

uint32_t wr_rig_vertex_count(const wr_rig* rig, wr_vertex_order order) {
  if (rig == nullptr) return 0;
  if (order == WR_ORDER_WELDED) return uint32_t(rig->asset.model.vertices.size());
  if (order == WR_ORDER_SOURCE)
    return uint32_t(rig->asset.vertex_order.empty() ? rig->asset.model.vertices.size()
                                                    : rig->asset.vertex_order.size());
  return 0;
}

uint32_t wr_rig_triangle_count(const wr_rig* rig) {
  return rig ? uint32_t(rig->asset.model.triangles.size()) : 0;
}

wr_status wr_rig_welded_triangles(const wr_rig* rig, uint32_t* indices, size_t capacity) {
  return Guarded("wr_rig_welded_triangles", [&] {
    if (rig == nullptr || indices == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_rig_welded_triangles: rig and indices are required");
    const auto& triangles = rig->asset.model.triangles;
    if (capacity < 3 * triangles.size())
      return Fail(WR_INVALID_ARGUMENT, "wr_rig_welded_triangles: capacity " +
                                           std::to_string(capacity) + " is below the " +
                                           std::to_string(3 * triangles.size()) + " indices");
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) indices[3 * t + std::size_t(k)] = triangles[t][std::size_t(k)];
    last_error.clear();
    return WR_OK;
  });
}

wr_status wr_clip_load_memory(const void* bytes, size_t size, wr_clip** out) {
  return Guarded("wr_clip_load_memory", [&] {
    if ((bytes == nullptr && size > 0) || out == nullptr)  // no bytes: refused as an asset
      return Fail(WR_INVALID_ARGUMENT,
                  "wr_clip_load_memory: out, and bytes when size > 0, are required");
    auto clip = std::make_unique<wr_clip>();
    const wirerig::Status status = wirerig::ParseClipAsset(
        std::span(static_cast<const std::uint8_t*>(bytes), size), &clip->clip);
    if (!status) return Fail(WR_BAD_ASSET, "clip asset: " + wirerig::ToString(status));
    *out = clip.release();
    return WR_OK;
  });
}

wr_status wr_clip_load_file(const char* path, wr_clip** out) {
  return Guarded("wr_clip_load_file", [&] {
    if (path == nullptr || out == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_clip_load_file: path and out are required");
    std::vector<std::uint8_t> bytes;
    if (wr_status read = ReadFile(path, &bytes); read != WR_OK) return read;
    const wr_status status = wr_clip_load_memory(bytes.data(), bytes.size(), out);
    if (status != WR_OK) last_error = std::string(path) + ": " + last_error;
    return status;
  });
}

void wr_clip_free(wr_clip* clip) { delete clip; }

const char* wr_clip_name(const wr_clip* clip) { return clip ? clip->clip.name.c_str() : nullptr; }

double wr_clip_duration(const wr_clip* clip) { return clip ? clip->clip.duration : 0.0; }

wr_status wr_context_set_clip(wr_context* context, const wr_clip* clip, double time) {
  return Guarded("wr_context_set_clip", [&] {
    if (context == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_clip: context is null");
    if (!std::isfinite(time))
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_clip: time must be finite");
    if (clip != nullptr && clip != context->clip) {
      if (wirerig::Status s = wirerig::ValidateSampledClip(clip->clip, &context->rig->asset.model);
          !s)
        return Fail(WR_INVALID_ARGUMENT, "wr_context_set_clip: clip \"" + clip->clip.name +
                                             "\" does not fit this rig: " + wirerig::ToString(s));
      context->clip_buffers = wirerig::MakeClipPlaybackBuffers(clip->clip);
    }
    context->clip = clip;
    context->clip_time = time;
    return WR_OK;
  });
}

wr_status wr_context_create(const wr_rig* rig, wr_context** out) {
  return Guarded("wr_context_create", [&] {
    if (rig == nullptr || out == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_create: rig and out are required");
    auto context = std::make_unique<wr_context>();
    context->rig = rig;
    const std::size_t parts = rig->asset.model.parts.size();
    context->poses.resize(parts);
    context->loads.resize(parts);
    context->workspace = wirerig::MakeRigWorkspace(rig->asset.model, rig->plan);
    wr_context_reset(context.get());
    *out = context.release();
    return WR_OK;
  });
}

void wr_context_free(wr_context* context) { delete context; }

void wr_context_reset(wr_context* context) {
  if (context == nullptr) return;
  const std::size_t parts = context->poses.size();
  context->transform_rotation.assign(parts, wirerig::Quat::Identity());
  context->transform_translation.assign(parts, wirerig::Vec3::Zero());
  context->joint_degrees.assign(parts, wirerig::Vec3::Zero());
  for (auto& loads : context->loads) loads.clear();
  context->clip = nullptr;
}

wr_status wr_context_set_normal_mode(wr_context* context, wr_normal_mode mode) {
  return Guarded("wr_context_set_normal_mode", [&] {
    if (context == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_normal_mode: context is null");
    if (mode != WR_NORMALS_FROM_TRIANGLES && mode != WR_NORMALS_ROTATED)
      return Fail(WR_INVALID_ARGUMENT,
                  "wr_context_set_normal_mode: mode must be from triangles or rotated");
    context->normal_mode = mode == WR_NORMALS_ROTATED ? wirerig::NormalMode::kRotated
                                                      : wirerig::NormalMode::kFromTriangles;
    last_error.clear();
    return WR_OK;
  });
}

wr_status wr_context_set_joint_angles(wr_context* context, uint32_t part, float x_degrees,
                                      float y_degrees, float z_degrees) {
  return Guarded("wr_context_set_joint_angles", [&] {
    if (wr_status s = CheckPart("wr_context_set_joint_angles", context, part); s != WR_OK) return s;
    const float degrees[3] = {x_degrees, y_degrees, z_degrees};
    if (!Finite(degrees, 3))
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_joint_angles: angles must be finite");
    if (context->rig->asset.model.parts[part].parent < 0)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_joint_angles: part " +
                                           context->rig->asset.model.parts[part].name +
                                           " is a root and has no joint");
    context->joint_degrees[part] = wirerig::Vec3(x_degrees, y_degrees, z_degrees);
    last_error.clear();
    return WR_OK;
  });
}

wr_status wr_context_set_part_transform(wr_context* context, uint32_t part,
                                        const float rotation_xyzw[4], const float translation[3]) {
  return Guarded("wr_context_set_part_transform", [&] {
    if (wr_status s = CheckPart("wr_context_set_part_transform", context, part); s != WR_OK)
      return s;
    if (rotation_xyzw == nullptr || translation == nullptr || !Finite(rotation_xyzw, 4) ||
        !Finite(translation, 3))
      return Fail(WR_INVALID_ARGUMENT,
                  "wr_context_set_part_transform: rotation and translation must be finite");
    for (int c = 0; c < 3; ++c)
      if (!(std::abs(translation[c]) <= wirerig::kMaxTranslation))
        return Fail(WR_INVALID_ARGUMENT,
                    "wr_context_set_part_transform: translation must be within 1e6 m");
    const wirerig::Quat q(rotation_xyzw[3], rotation_xyzw[0], rotation_xyzw[1], rotation_xyzw[2]);
    if (!(q.norm() > 1e-6))
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_part_transform: rotation must not be zero");
    context->transform_rotation[part] = q.normalized();
    context->transform_translation[part] =
        wirerig::Vec3(translation[0], translation[1], translation[2]);
    last_error.clear();
    return WR_OK;
  });
}

wr_status wr_context_set_point_loads(wr_context* context, uint32_t part, const float* at,
                                     const float* forces, uint32_t count) {
  return Guarded("wr_context_set_point_loads", [&] {
    if (wr_status s = CheckPart("wr_context_set_point_loads", context, part); s != WR_OK) return s;
    if (count > 0 && (at == nullptr || forces == nullptr))
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_point_loads: at and forces are required");
    const wirerig::PartModel& model = context->rig->asset.model.parts[part];
    if (count > 0 && model.kind != wirerig::SpineKind::kDeformable)  // they would move nothing
      return Fail(WR_INVALID_ARGUMENT, "wr_context_set_point_loads: part " + model.name +
                                           " is rigid: loads bend deformable parts only");
    std::vector<wirerig::PointLoad> loads(count);
    for (uint32_t i = 0; i < count; ++i) {
      if (!(at[i] >= 0.0f && at[i] <= 1.0f) || !Finite(forces + 3 * i, 3))
        return Fail(WR_INVALID_ARGUMENT, "wr_context_set_point_loads: load " + std::to_string(i) +
                                             " needs at in [0, 1] and a finite force");
      loads[i] = {at[i], wirerig::Vec3(forces[3 * i], forces[3 * i + 1], forces[3 * i + 2])};
    }
    context->loads[part] = std::move(loads);
    return WR_OK;
  });
}

wr_status wr_context_evaluate(wr_context* context, wr_vertex_order order, float* positions,
                              size_t position_stride, float* normals, size_t normal_stride,
                              size_t capacity) {
  return Guarded("wr_context_evaluate", [&] {
    if (context == nullptr || positions == nullptr)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_evaluate: context and positions are required");
    if (order != WR_ORDER_SOURCE && order != WR_ORDER_WELDED)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_evaluate: order must be source or welded");
    const wirerig::RigAsset& asset = context->rig->asset;
    std::span<const wirerig::ProfileLoads> profile_loads;
    if (context->clip != nullptr) {
      const wirerig::SampleClipJob sample{&context->clip->clip, context->clip_time,
                                          &context->clip_buffers};
      if (wirerig::Status s = sample.Run(); !s)
        return Fail(WR_INVALID_ARGUMENT, "wr_context_evaluate: " + wirerig::ToString(s));
      std::copy(context->clip_buffers.poses.begin(), context->clip_buffers.poses.end(),
                context->poses.begin());
      profile_loads = context->clip_buffers.used_profile_loads();
    }
    for (std::size_t p = 0; p < context->poses.size(); ++p) {
      wirerig::PartPose& pose = context->poses[p];
      if (context->clip == nullptr) {
        pose.rotation = context->transform_rotation[p];
        pose.translation = context->transform_translation[p];
        pose.loads = {};
        pose.loads.bending_point_loads = context->loads[p];
      }
      if (asset.model.parts[p].parent >= 0 && !context->joint_degrees[p].isZero())
        pose.rotation = (pose.rotation * wirerig::JointRotation(asset.model.parts[p].joint,
                                                                context->joint_degrees[p]))
                            .normalized();
    }
    wirerig::EvaluateRigJob job;
    job.model = &asset.model;
    job.poses = context->poses;
    job.profile_loads = profile_loads;
    job.workspace = &context->workspace;
    job.float_positions = std::span(positions, capacity);
    job.float_position_stride = position_stride;
    if (normals != nullptr) job.float_normals = std::span(normals, capacity);
    job.float_normal_stride = normal_stride;
    if (order == WR_ORDER_SOURCE) job.float_vertex_order = asset.vertex_order;
    job.normal_mode = context->normal_mode;
    const wirerig::Status status = job.Run();
    if (!status)
      return Fail(WR_INVALID_ARGUMENT, "wr_context_evaluate: " + wirerig::ToString(status));
    last_error.clear();
    return WR_OK;
  });
}

}  // extern "C"
