#include "viz/view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace retrace::viz {

void Box2::Extend(const Vec2& p, double r) {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(r)) return;
  const Vec2 lo = p - Vec2(r, r);
  const Vec2 hi = p + Vec2(r, r);
  if (IsEmpty()) {
    min = lo;
    max = hi;
    return;
  }
  min = min.cwiseMin(lo);
  max = max.cwiseMax(hi);
}

void Box2::Extend(const Box2& other) {
  if (other.IsEmpty()) return;
  Extend(other.min);
  Extend(other.max);
}

Box2 Box2::Inflated(double m) const {
  if (IsEmpty()) return *this;
  return {min - Vec2(m, m), max + Vec2(m, m)};
}

View View::Fit(const Box2& box_W, int width, int height, double margin_px) {
  View v;
  v.width_ = std::max(1, width);
  v.height_ = std::max(1, height);
  Box2 box = box_W;
  if (box.IsEmpty()) box = Box2::Of(Vec2(-0.5, -0.5), Vec2(0.5, 0.5));
  Vec2 size = box.Size();
  // A degenerate box (one point, a straight line) still needs a finite scale.
  if (size.x() < 1e-6 && size.y() < 1e-6) {
    box = box.Inflated(0.5);
    size = box.Size();
  }
  const double usable_w = std::max(1.0, v.width_ - 2.0 * margin_px);
  const double usable_h = std::max(1.0, v.height_ - 2.0 * margin_px);
  const double sx = size.x() > 1e-9 ? usable_w / size.x() : std::numeric_limits<double>::infinity();
  const double sy = size.y() > 1e-9 ? usable_h / size.y() : std::numeric_limits<double>::infinity();
  v.pixels_per_meter_ = std::min(sx, sy);
  v.center_W_ = box.Center();
  return v;
}

View View::Centered(const Vec2& center_W, double pixels_per_meter, int width, int height) {
  View v;
  v.center_W_ = center_W;
  v.pixels_per_meter_ = pixels_per_meter > 0.0 ? pixels_per_meter : 1.0;
  v.width_ = std::max(1, width);
  v.height_ = std::max(1, height);
  return v;
}

Vec2 View::ToPixel(const Vec2& p_W) const {
  return {0.5 * width_ + (p_W.x() - center_W_.x()) * pixels_per_meter_,
          0.5 * height_ - (p_W.y() - center_W_.y()) * pixels_per_meter_};
}

Vec2 View::ToWorld(const Vec2& px) const {
  return {center_W_.x() + (px.x() - 0.5 * width_) / pixels_per_meter_,
          center_W_.y() - (px.y() - 0.5 * height_) / pixels_per_meter_};
}

Box2 View::VisibleBox() const {
  return Box2::Of(ToWorld(Vec2(0.0, static_cast<double>(height_))),
                  ToWorld(Vec2(static_cast<double>(width_), 0.0)));
}

View View::Scaled(int factor) const {
  View v = *this;
  v.pixels_per_meter_ *= factor;
  v.width_ *= factor;
  v.height_ *= factor;
  return v;
}

}  // namespace retrace::viz
