// Shared by the sample tests: load a sample's scene file, build it, play a clip headless, and
// find out what a mutated copy of the scene is refused with.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "wirerig/anim/playback.h"
#include "wirerig/anim/scene.h"

#ifndef WIRERIG_SAMPLES_DIR
#define WIRERIG_SAMPLES_DIR "samples"
#endif

namespace wirerig::samples {

inline std::filesystem::path SampleScenePath(const std::string& relative) {
  return std::filesystem::path(WIRERIG_SAMPLES_DIR) / relative;
}

inline nlohmann::json ReadJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A built scene and a playback of one of its clips (the playback points into the scene, so
// both live behind one pointer and never move).
struct PlayedScene {
  BuiltScene scene;
  std::unique_ptr<Playback> playback;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<PartWarnings> warnings;

  // Evaluates the clip at t; the deformed wires are then in playback->workspace().
  void Evaluate(double t) {
    const Status s = playback->Evaluate(t, positions, normals, warnings);
    ASSERT_TRUE(s.ok()) << ToString(s);
  }
  std::size_t Part(const std::string& name) const {
    for (std::size_t i = 0; i < scene.model.parts.size(); ++i)
      if (scene.model.parts[i].name == name) return i;
    ADD_FAILURE() << "no part " << name;
    return 0;
  }
};

// Builds a scene description and makes a playback of `clip` (the first if empty); null after a
// test failure naming what went wrong.
inline std::unique_ptr<PlayedScene> PlayDescription(const Result<SceneDescription>& description,
                                                    const std::string& clip = "") {
  if (!description) {
    ADD_FAILURE() << description.error();
    return nullptr;
  }
  Result<BuiltScene> built = BuildScene(description.value());
  if (!built) {
    ADD_FAILURE() << built.error();
    return nullptr;
  }
  auto played = std::make_unique<PlayedScene>();
  played->scene = std::move(built).value();
  const Clip* found = played->scene.FindClip(clip);
  if (found == nullptr) {
    ADD_FAILURE() << "no clip " << clip;
    return nullptr;
  }
  Result<Playback> playback =
      Playback::Make(played->scene.model, *found, played->scene.description.playback);
  if (!playback) {
    ADD_FAILURE() << playback.error();
    return nullptr;
  }
  played->playback = std::make_unique<Playback>(std::move(playback).value());
  played->positions.resize(played->scene.model.vertices.size());
  played->normals.resize(played->positions.size());
  played->warnings.resize(played->scene.model.parts.size());
  return played;
}

// The sample's scene file, loaded, built and played.
inline std::unique_ptr<PlayedScene> PlaySample(const std::string& relative,
                                               const std::string& clip = "") {
  return PlayDescription(LoadScene(SampleScenePath(relative)), clip);
}

// A (mutated) scene document, parsed as if it were in the samples folder, built and played.
inline std::unique_ptr<PlayedScene> PlayDocument(const nlohmann::json& document,
                                                 const std::string& clip = "") {
  return PlayDescription(ParseScene(document, WIRERIG_SAMPLES_DIR), clip);
}

// What a (mutated) scene document is refused with, by ParseScene or then BuildScene; "ok" if it
// is accepted. Relative paths resolve against the samples folder.
inline std::string SceneError(const nlohmann::json& document) {
  Result<SceneDescription> parsed = ParseScene(document, WIRERIG_SAMPLES_DIR);
  if (!parsed) return parsed.error();
  Result<BuiltScene> built = BuildScene(parsed.value());
  return built ? "ok" : built.error();
}

// The largest extent of a point set's bounding box (a body's size), m.
inline double BodySize(const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).maxCoeff();
}

// Arc length of the stretch [from, to] of a closed profile (points at u = q / m), at rest.
inline double StretchLength(const ProfileModel& profile, double from, double to) {
  const std::size_t m = profile.local_points.size();
  double length = 0.0;
  for (std::size_t q = 0; q < m; ++q) {
    const double u0 = double(q) / double(m), u1 = double(q + 1) / double(m);
    const double overlap = std::min(u1, to) - std::max(u0, from);
    if (overlap > 0.0)
      length += (profile.local_points[(q + 1) % m] - profile.local_points[q]).norm() * overlap *
                double(m);
  }
  return length;
}

}  // namespace wirerig::samples
