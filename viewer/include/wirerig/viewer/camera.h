// Camera: an orbit camera (target, yaw, pitch, distance, vertical field of view) and the
// matrices, projections and rays the renderer and picking share.
//
// Angles are radians. yaw = 0, pitch = 0 looks from +Z (towards the viewer in glTF axes) at
// the target; positive yaw turns the eye towards +X, positive pitch lifts it above the target.
// Pixel coordinates have their origin at the top-left corner of the image, x right, y down,
// pixel centres at half-integers (as images and mouse positions).
#pragma once

#include <Eigen/Core>

#include "wirerig/viewer/render_frame.h"

namespace wirerig {

using Mat4f = Eigen::Matrix4f;
using Vec2f = Eigen::Vector2f;

// Pixel size of an image or a window.
struct Size {
  int width = 0;
  int height = 0;
  float Aspect() const { return height > 0 ? float(width) / float(height) : 1.0f; }
};

struct Camera {
  Vec3f target = Vec3f::Zero();  // orbit centre, m
  float yaw = 0.6f;              // radians
  float pitch = 0.35f;           // radians, kept inside (-pi/2, pi/2)
  float distance = 3.0f;         // eye to target, m, > 0
  float fov_y = 0.75f;           // vertical field of view, radians, in (0, pi)

  Vec3f Forward() const;  // unit vector from the eye towards the target
  Vec3f Eye() const;      // eye position, m
  Vec3f Right() const;    // unit screen-right vector
  Vec3f Up() const;       // unit screen-up vector
  float Near() const { return 0.01f * distance; }
  float Far() const { return 100.0f * distance; }

  // World to view (right-handed, looking down -Z).
  Mat4f ViewMatrix() const;
  // View to clip, OpenGL convention (depth in [-1, 1]).
  Mat4f ProjectionMatrix(float aspect) const;
};

// Sets target, distance (and keeps yaw, pitch, fov) so that the bounding sphere of `bounds`
// fills the view with a small margin in both directions for an image of aspect `aspect`.
// An empty bounds leaves the camera unchanged.
void FrameCamera(Camera& camera, const FrameBounds& bounds, float aspect, float margin = 1.1f);

// Projects a world point into pixels of an image of `size`. Returns false (and leaves `pixel`
// alone) when the point is behind the eye.
bool ProjectToPixel(const Camera& camera, Size size, const Vec3f& point, Vec2f* pixel,
                    float* depth = nullptr);

struct Ray {
  Vec3f origin = Vec3f::Zero();
  Vec3f direction = Vec3f::UnitZ();  // unit
};
// The ray from the eye through pixel `pixel` of an image of `size`.
Ray PixelRay(const Camera& camera, Size size, const Vec2f& pixel);

// Point on the plane through `point_on_plane` facing the camera that pixel `pixel` looks at:
// how a drag moves a picked point.
Vec3f DragPoint(const Camera& camera, Size size, const Vec2f& pixel, const Vec3f& point_on_plane);

// Screen-space bounds, in pixels, of the 8 projected corners of a box (for tests and HUDs).
// Returns false if a corner is behind the eye.
bool ProjectBounds(const Camera& camera, Size size, const FrameBounds& bounds, Vec2f* min_pixel,
                   Vec2f* max_pixel);

}  // namespace wirerig
