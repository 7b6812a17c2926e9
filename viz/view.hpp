#pragma once
// The world-to-pixel mapping of a canvas or a figure panel: world coordinates in metres with y
// up, pixels with x to the right and y down, uniform scale (no distortion).

#include "core/pose2.hpp"

namespace retrace::viz {

using core::Vec2;

/// An axis-aligned box (m). Empty (min > max) until something is added.
struct Box2 {
  Vec2 min{1.0, 1.0};
  Vec2 max{-1.0, -1.0};

  static Box2 Of(const Vec2& a, const Vec2& b) { return {a.cwiseMin(b), a.cwiseMax(b)}; }
  bool IsEmpty() const { return !(min.x() <= max.x() && min.y() <= max.y()); }
  /// Grows the box to hold a disc of radius r (m) at p; non-finite points are ignored.
  void Extend(const Vec2& p, double r = 0.0);
  void Extend(const Box2& other);
  /// The box grown by m metres on every side (unchanged if empty).
  Box2 Inflated(double m) const;
  Vec2 Size() const { return IsEmpty() ? Vec2::Zero() : Vec2(max - min); }
  Vec2 Center() const { return 0.5 * (min + max); }
  bool Contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
};

/// Pixel coordinates: (0, 0) is the top-left corner of the top-left pixel, so pixel (column c,
/// row r) covers [c, c+1) x [r, r+1) and its centre is (c + 0.5, r + 0.5).
class View {
 public:
  View() = default;

  /// The largest scale that shows `box_W` whole in a width x height image with at least
  /// `margin_px` pixels on every side, centred. An empty or degenerate box is shown as a 1 m
  /// square around its centre.
  static View Fit(const Box2& box_W, int width, int height, double margin_px = 0.0);
  /// `center_W` at the centre of a width x height image, at `pixels_per_meter`.
  static View Centered(const Vec2& center_W, double pixels_per_meter, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  double pixels_per_meter() const { return pixels_per_meter_; }
  const Vec2& center() const { return center_W_; }

  /// The pixel position of a world point (m).
  Vec2 ToPixel(const Vec2& p_W) const;
  /// The world point (m) at a pixel position.
  Vec2 ToWorld(const Vec2& px) const;
  /// The part of the world the image shows (m).
  Box2 VisibleBox() const;
  /// The same region in an image `factor` times larger in each direction.
  View Scaled(int factor) const;

 private:
  Vec2 center_W_ = Vec2::Zero();
  double pixels_per_meter_ = 1.0;
  int width_ = 1;
  int height_ = 1;
};

}  // namespace retrace::viz
