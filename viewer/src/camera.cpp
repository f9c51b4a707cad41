#include "wirerig/viewer/camera.h"

#include <algorithm>
#include <cmath>

namespace wirerig {

Vec3f Camera::Forward() const {
  // The eye sits at target - distance * Forward().
  const float cp = std::cos(pitch);
  return -Vec3f(cp * std::sin(yaw), std::sin(pitch), cp * std::cos(yaw));
}

Vec3f Camera::Eye() const { return target - distance * Forward(); }

Vec3f Camera::Right() const { return Vec3f(std::cos(yaw), 0.0f, -std::sin(yaw)); }

Vec3f Camera::Up() const { return Right().cross(Forward()); }

Mat4f Camera::ViewMatrix() const {
  const Vec3f f = Forward();
  const Vec3f r = Right();
  const Vec3f u = r.cross(f);
  const Vec3f eye = Eye();
  Mat4f view = Mat4f::Identity();
  view.block<1, 3>(0, 0) = r.transpose();
  view.block<1, 3>(1, 0) = u.transpose();
  view.block<1, 3>(2, 0) = -f.transpose();
  view(0, 3) = -r.dot(eye);
  view(1, 3) = -u.dot(eye);
  view(2, 3) = f.dot(eye);
  return view;
}

Mat4f Camera::ProjectionMatrix(float aspect) const {
  const float n = Near();
  const float f = Far();
  const float t = 1.0f / std::tan(0.5f * fov_y);
  Mat4f p = Mat4f::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2.0f * f * n / (n - f);
  p(3, 2) = -1.0f;
  return p;
}

void FrameCamera(Camera& camera, const FrameBounds& bounds, float aspect, float margin) {
  if (bounds.empty) return;
  const float radius = std::max(bounds.Radius(), 1e-3f);
  // The sphere must fit the narrower of the two fields of view.
  const float half_y = 0.5f * camera.fov_y;
  const float half_x = std::atan(std::tan(half_y) * std::max(aspect, 1e-3f));
  const float half = std::min(half_x, half_y);
  camera.target = bounds.Center();
  camera.distance = margin * radius / std::sin(half);
}

bool ProjectToPixel(const Camera& camera, Size size, const Vec3f& point, Vec2f* pixel,
                    float* depth) {
  const Eigen::Vector4f clip =
      camera.ProjectionMatrix(size.Aspect()) * camera.ViewMatrix() * point.homogeneous();
  if (clip.w() <= 1e-9f) return false;
  const float x = clip.x() / clip.w();
  const float y = clip.y() / clip.w();
  *pixel = Vec2f(0.5f * (x + 1.0f) * float(size.width), 0.5f * (1.0f - y) * float(size.height));
  if (depth != nullptr) *depth = clip.w();
  return true;
}

Ray PixelRay(const Camera& camera, Size size, const Vec2f& pixel) {
  const float x = 2.0f * pixel.x() / float(std::max(size.width, 1)) - 1.0f;
  const float y = 1.0f - 2.0f * pixel.y() / float(std::max(size.height, 1));
  const float t = std::tan(0.5f * camera.fov_y);
  Ray ray;
  ray.origin = camera.Eye();
  ray.direction = (camera.Forward() + x * t * size.Aspect() * camera.Right() + y * t * camera.Up())
                      .normalized();
  return ray;
}

Vec3f DragPoint(const Camera& camera, Size size, const Vec2f& pixel, const Vec3f& point_on_plane) {
  const Ray ray = PixelRay(camera, size, pixel);
  const Vec3f normal = camera.Forward();
  const float denom = ray.direction.dot(normal);
  if (std::abs(denom) < 1e-6f) return point_on_plane;
  const float t = (point_on_plane - ray.origin).dot(normal) / denom;
  return ray.origin + t * ray.direction;
}

bool ProjectBounds(const Camera& camera, Size size, const FrameBounds& bounds, Vec2f* min_pixel,
                   Vec2f* max_pixel) {
  Vec2f lo = Vec2f::Constant(1e30f);
  Vec2f hi = Vec2f::Constant(-1e30f);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3f p((corner & 1) ? bounds.max.x() : bounds.min.x(),
                  (corner & 2) ? bounds.max.y() : bounds.min.y(),
                  (corner & 4) ? bounds.max.z() : bounds.min.z());
    Vec2f pixel;
    if (!ProjectToPixel(camera, size, p, &pixel)) return false;
    lo = lo.cwiseMin(pixel);
    hi = hi.cwiseMax(pixel);
  }
  *min_pixel = lo;
  *max_pixel = hi;
  return true;
}

}  // namespace wirerig
