// SceneFrame: the picture of a scene being played, as a RenderFrame. It owns float buffers sized
// once for the scene (the deformed mesh, a polyline per profile wire and spine wire, an arrow
// per spine point load) and refills them from a Playback after each Evaluate without
// allocating. Profile wires are blue, spine wires pink, as in the paper's figures.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "wirerig/anim/playback.h"
#include "wirerig/anim/scene.h"
#include "wirerig/viewer/camera.h"
#include "wirerig/viewer/render_frame.h"

namespace wirerig {

// What colours the skin: its base colour, or a per-vertex quantity of the part's spine wire at
// the vertex's place: the bending moment |M| = EI |kappa| (kappa from the deformed spine's turn
// between samples) or the axial strain N / EA.
enum class SceneColoring : int { kBaseColor = 0, kBendingMoment = 1, kAxialStrain = 2 };

class SceneFrame {
 public:
  // The scene must outlive the frame.
  explicit SceneFrame(const BuiltScene& scene);

  // From a playback of this scene's model just evaluated into `positions` and `normals`
  // (#W welded vertices each).
  void Update(const Playback& playback, std::span<const Vec3> positions,
              std::span<const Vec3> normals);

  // Spans into this object's buffers, valid until the next Update.
  RenderFrame frame() const;
  void set_caption(std::string caption) { caption_ = std::move(caption); }
  // Takes effect at the next Update.
  void set_coloring(SceneColoring coloring) { coloring_ = coloring; }
  SceneColoring coloring() const { return coloring_; }

  // The scene's camera hint, or a camera framing the rest mesh, for an image of `size`; a hint
  // that follows a part has its target moved with that part (FollowOffset).
  Camera InitialCamera(Size size) const;
  // How far the camera hint's followed part's spine root has moved from rest at the last
  // Update (zero when the hint follows nothing), m.
  Vec3f FollowOffset() const { return follow_offset_; }

  // Polyline ids: profile wire k of part p, and the spine of part p.
  std::uint32_t ProfileId(std::size_t part, std::size_t profile) const;
  std::uint32_t SpineId(std::size_t part) const;

 private:
  void UpdateColors(const RigWorkspace& workspace);

  const BuiltScene* scene_;
  std::vector<Vec3f> positions_, normals_;
  std::vector<std::vector<Vec3f>> wire_points_;  // per polyline
  std::vector<RenderPolyline> polylines_;
  std::vector<RenderArrow> arrows_;
  std::size_t arrow_count_ = 0;
  std::vector<std::size_t> first_profile_id_;  // per part
  RenderMesh mesh_;
  std::string caption_;
  SceneColoring coloring_ = SceneColoring::kBaseColor;
  int follow_part_ = -1;  // the camera hint's followed part, or -1
  Vec3f follow_offset_ = Vec3f::Zero();
  std::vector<float> scalars_;                     // per vertex, when coloured
  std::vector<std::vector<float>> sample_values_;  // per part, per spine sample
  std::vector<std::pair<std::uint32_t, std::uint32_t>> vertex_sample_;  // (part, sample)
  ScalarLegend legend_;
};

}  // namespace wirerig
