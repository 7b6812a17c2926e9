#include "viz/gl_canvas.hpp"

// OSMesa and legacy OpenGL stay in this file: nothing of them reaches the header.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "viz/internal/polyline.hpp"
#include "viz/render_error.hpp"

// GCC says __SANITIZE_ADDRESS__, Clang __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define RETRACE_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RETRACE_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(RETRACE_ADDRESS_SANITIZER)
// Mesa's OSMesa keeps a few hundred bytes per process that it never frees (its buffer list),
// which LeakSanitizer reports at exit. Every program that renders links this file, so the
// suppression lives here rather than in each test and in the command-line program. Defined
// only in sanitizer builds; a program that needs its own suppressions must add this line.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
// LeakSanitizer lists the suppressions it used on stderr at exit; a command-line error must
// stay one line, so the list is not printed.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace retrace::viz {
namespace {

// One OSMesa context per thread, created on first use. OSMesa renders into an internal
// framebuffer and copies it to the bound user buffer on glFinish; binding another buffer of
// the same size reuses that framebuffer, so `current` remembers whose pixels it holds.
struct ThreadGl {
  OSMesaContext context = nullptr;
  const void* current = nullptr;          // the GlCanvas::Impl bound to `context`, if any
  std::array<std::uint8_t, 4> parking{};  // a 1x1 buffer to bind when a canvas goes away

  ~ThreadGl() {
    if (context != nullptr) {
      OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);  // unbind first, so Mesa releases the buffer
      OSMesaDestroyContext(context);
    }
  }
};

// This thread's state, without creating a context (safe in destructors).
ThreadGl& TlsState() {
  thread_local ThreadGl gl;
  return gl;
}

// This thread's state with a context; throws RenderError if OSMesa cannot make one.
ThreadGl& Tls() {
  ThreadGl& gl = TlsState();
  if (gl.context == nullptr) {
    // RGBA colour, no depth (painter's order), 8 stencil bits for polygon fills and
    // single-coverage translucent lines, no accumulation buffer.
    gl.context = OSMesaCreateContextExt(OSMESA_RGBA, 0, 8, 0, nullptr);
    if (gl.context == nullptr) {
      throw RenderError(
          "OSMesa could not create an off-screen OpenGL context (is Mesa's libOSMesa installed "
          "and working?); figures and videos are not rendered");
    }
  }
  return gl;
}

struct Vertex {
  float x;
  float y;
};

using Triangles = std::vector<Vertex>;

void AddTriangle(Triangles& t, const Vec2& a, const Vec2& b, const Vec2& c) {
  t.push_back({static_cast<float>(a.x()), static_cast<float>(a.y())});
  t.push_back({static_cast<float>(b.x()), static_cast<float>(b.y())});
  t.push_back({static_cast<float>(c.x()), static_cast<float>(c.y())});
}

void AddQuad(Triangles& t, const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  AddTriangle(t, a, b, c);
  AddTriangle(t, a, c, d);
}

// A regular polygon of `n` sides around c (pixels) as a triangle fan.
void AddDisc(Triangles& t, const Vec2& c, double r, int n) {
  Vec2 prev = c + Vec2(r, 0.0);
  for (int i = 1; i <= n; ++i) {
    const double a = 2.0 * core::kPi * i / n;
    const Vec2 next = c + r * Vec2(std::cos(a), std::sin(a));
    AddTriangle(t, c, prev, next);
    prev = next;
  }
}

int DiscSides(double r_px) {
  return std::clamp(static_cast<int>(std::ceil(2.0 * core::kPi * r_px / 2.5)), 8, 256);
}

void Draw(const Triangles& t, Rgba color) {
  if (t.empty()) return;
  glColor4ub(color.r, color.g, color.b, color.a);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, t.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(t.size()));
  glDisableClientState(GL_VERTEX_ARRAY);
}

void DrawColored(const Triangles& t, const std::vector<Rgba>& colors) {
  if (t.empty()) return;
  RETRACE_CHECK(colors.size() == t.size());
  static_assert(sizeof(Rgba) == 4);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, t.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colors.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(t.size()));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

// Draws translucent triangles so that each pixel is blended once however often they overlap:
// the first coverage marks the stencil, later ones fail the test; a second pass clears the
// marks (the stencil is all zero between primitives).
void DrawOnce(const Triangles& t, Rgba color) {
  if (color.a == 255) {
    Draw(t, color);
    return;
  }
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  Draw(t, color);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
  Draw(t, color);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_STENCIL_TEST);
}

std::uint8_t Lerp(std::uint8_t a, std::uint8_t b, double t) {
  return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * t));
}

Rgba Lerp(Rgba a, Rgba b, double t) {
  return {Lerp(a.r, b.r, t), Lerp(a.g, b.g, t), Lerp(a.b, b.b, t), Lerp(a.a, b.a, t)};
}

}  // namespace

Rgba GridCellColor(float log_odds, const GridStyle& style) {
  const Rgba unknown = style.unknown_transparent ? style.unknown.WithAlpha(0) : style.unknown;
  if (log_odds == 0.0f) return unknown;
  const double p = core::InverseLogit(log_odds);
  if (p <= style.free_probability) return style.free;
  if (p >= style.occupied_probability) return style.occupied;
  if (p < 0.5) {
    return Lerp(style.free, unknown, (p - style.free_probability) / (0.5 - style.free_probability));
  }
  return Lerp(unknown, style.occupied, (p - 0.5) / (style.occupied_probability - 0.5));
}

class GlCanvas::Impl {
 public:
  Impl(int width, int height, int supersample, Rgba background)
      : width_(width), height_(height), ss_(supersample), background_(background) {
    if (width <= 0 || height <= 0) {
      throw RenderError("canvas size must be positive, got " + std::to_string(width) + " x " +
                        std::to_string(height) + " px");
    }
    if (supersample < 1 || supersample > 4) {
      throw RenderError("canvas supersampling must be 1..4, got " + std::to_string(supersample));
    }
    if (static_cast<long long>(width) * supersample > kMaxCanvasSide ||
        static_cast<long long>(height) * supersample > kMaxCanvasSide) {
      throw RenderError("canvas of " + std::to_string(width) + " x " + std::to_string(height) +
                        " px at " + std::to_string(supersample) +
                        "x supersampling exceeds OSMesa's limit of " +
                        std::to_string(kMaxCanvasSide) + " px per side");
    }
    buffer_.assign(static_cast<std::size_t>(W()) * static_cast<std::size_t>(H()) * 4, 0);
    view_ = View::Fit(Box2::Of(Vec2(-0.5, -0.5), Vec2(0.5, 0.5)), width, height);
    view_ss_ = view_.Scaled(ss_);
    Bind();
  }

  ~Impl() {
    ThreadGl& gl = TlsState();
    if (gl.current == this) {
      // Detach so that a later flush never writes into this buffer after it is freed.
      glFinish();
      OSMesaMakeCurrent(gl.context, gl.parking.data(), GL_UNSIGNED_BYTE, 1, 1);
      gl.current = nullptr;
    }
  }

  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  int W() const { return width_ * ss_; }
  int H() const { return height_ * ss_; }

  // Makes this canvas's buffer the context's target, restoring its pixels if another canvas
  // used the context in between.
  void Bind() {
    ThreadGl& gl = Tls();
    if (gl.current == this) return;
    if (gl.current != nullptr) glFinish();  // the other canvas's pixels into its own buffer
    if (OSMesaMakeCurrent(gl.context, buffer_.data(), GL_UNSIGNED_BYTE, W(), H()) == GL_FALSE) {
      gl.current = nullptr;
      throw RenderError("OSMesa could not bind a " + std::to_string(W()) + " x " +
                        std::to_string(H()) + " px off-screen buffer");
    }
    gl.current = this;
    // Row 0 of the buffer is the top of the image, like viz::Image.
    OSMesaPixelStore(OSMESA_Y_UP, 0);
    glViewport(0, 0, W(), H());
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0.0, W(), H(), 0.0, -1.0, 1.0);  // pixel coordinates, y down
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_DITHER);  // dithering would make colours depend on position
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glClearStencil(0);
    if (initialized_) {
      glWindowPos2i(0, H());
      glPixelZoom(1.0f, -1.0f);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glDrawPixels(W(), H(), GL_RGBA, GL_UNSIGNED_BYTE, buffer_.data());
      glPixelZoom(1.0f, 1.0f);
      glClear(GL_STENCIL_BUFFER_BIT);
    } else {
      ClearTo(background_);
      initialized_ = true;
    }
  }

  void ClearTo(Rgba c) {
    glClearColor(c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  }

  Vec2 Px(const Vec2& p_W) const { return view_ss_.ToPixel(p_W); }

  Image ReadBack() {
    Bind();
    glFinish();
    Image out(width_, height_);
    const int s = ss_;
    const int n = s * s;
    const std::size_t stride = static_cast<std::size_t>(W()) * 4;
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) {
        int sum[3] = {0, 0, 0};
        for (int dy = 0; dy < s; ++dy) {
          const std::uint8_t* row = buffer_.data() + static_cast<std::size_t>(y * s + dy) * stride;
          for (int dx = 0; dx < s; ++dx) {
            const std::uint8_t* p = row + static_cast<std::size_t>(x * s + dx) * 4;
            sum[0] += p[0];
            sum[1] += p[1];
            sum[2] += p[2];
          }
        }
        std::uint8_t* o =
            out.rgb.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                              static_cast<std::size_t>(x)) *
                                 3;
        for (int c = 0; c < 3; ++c) o[c] = static_cast<std::uint8_t>((sum[c] + n / 2) / n);
      }
    }
    return out;
  }

  int width_;
  int height_;
  int ss_;
  Rgba background_;
  bool initialized_ = false;
  std::vector<std::uint8_t> buffer_;
  View view_;
  View view_ss_;
};

GlCanvas::GlCanvas(int width, int height, int supersample, Rgba background)
    : impl_(std::make_unique<Impl>(width, height, supersample, background)) {}
GlCanvas::~GlCanvas() = default;
GlCanvas::GlCanvas(GlCanvas&&) noexcept = default;
GlCanvas& GlCanvas::operator=(GlCanvas&&) noexcept = default;

int GlCanvas::width() const { return impl_->width_; }
int GlCanvas::height() const { return impl_->height_; }
int GlCanvas::supersample() const { return impl_->ss_; }

void GlCanvas::SetView(const View& view) {
  RETRACE_CHECK(view.width() == impl_->width_ && view.height() == impl_->height_);
  impl_->view_ = view;
  impl_->view_ss_ = view.Scaled(impl_->ss_);
}

const View& GlCanvas::view() const { return impl_->view_; }

void GlCanvas::Clear(Rgba color) {
  impl_->Bind();
  impl_->ClearTo(color);
}

void GlCanvas::FillPolygon(const std::vector<Vec2>& ring_W, Rgba color) {
  if (ring_W.size() < 3) return;
  impl_->Bind();
  Triangles fan;
  fan.reserve(3 * ring_W.size());
  const Vec2 p0 = impl_->Px(ring_W[0]);
  Box2 box;
  box.Extend(p0);
  for (std::size_t i = 1; i + 1 < ring_W.size(); ++i) {
    const Vec2 a = impl_->Px(ring_W[i]);
    const Vec2 b = impl_->Px(ring_W[i + 1]);
    AddTriangle(fan, p0, a, b);
    box.Extend(a);
    box.Extend(b);
  }
  // Stencil fill (even-odd): every fan triangle toggles the pixels it covers, so a pixel ends
  // set iff it is inside the ring an odd number of times; then one quad paints the set pixels
  // and clears them again. Works for concave and self-intersecting rings without
  // triangulation.
  glEnable(GL_STENCIL_TEST);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INVERT);
  Draw(fan, color);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glStencilFunc(GL_NOTEQUAL, 0, 0xFF);
  glStencilOp(GL_ZERO, GL_ZERO, GL_ZERO);
  Triangles quad;
  AddQuad(quad, box.min, Vec2(box.max.x(), box.min.y()), box.max, Vec2(box.min.x(), box.max.y()));
  Draw(quad, color);
  glDisable(GL_STENCIL_TEST);
}

void GlCanvas::FillDisc(const Vec2& center_W, double radius, Rgba color) {
  if (!(radius > 0.0)) return;
  impl_->Bind();
  const double r = radius * impl_->view_ss_.pixels_per_meter();
  Triangles t;
  AddDisc(t, impl_->Px(center_W), r, DiscSides(r));
  Draw(t, color);
}

void GlCanvas::DrawCircle(const Vec2& center_W, double radius, double width_px, Rgba color) {
  if (!(radius > 0.0) || !(width_px > 0.0)) return;
  impl_->Bind();
  const double r = radius * impl_->view_ss_.pixels_per_meter();
  const double hw = 0.5 * width_px * impl_->ss_;
  const double r_in = std::max(0.0, r - hw);
  const double r_out = r + hw;
  const Vec2 c = impl_->Px(center_W);
  const int n = DiscSides(r_out);
  Triangles t;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2.0 * core::kPi * i / n;
    const double a1 = 2.0 * core::kPi * (i + 1) / n;
    const Vec2 u0(std::cos(a0), std::sin(a0));
    const Vec2 u1(std::cos(a1), std::sin(a1));
    AddQuad(t, c + r_in * u0, c + r_out * u0, c + r_out * u1, c + r_in * u1);
  }
  DrawOnce(t, color);
}

void GlCanvas::DrawPolyline(const std::vector<Vec2>& points_W, double width_px, Rgba color,
                            bool closed) {
  if (points_W.size() < 2 || !(width_px > 0.0)) return;
  impl_->Bind();
  const int ss = impl_->ss_;
  std::vector<Vec2> px;
  px.reserve(points_W.size() + 1);
  for (const Vec2& p : points_W) px.push_back(impl_->Px(p));
  if (closed) px.push_back(px.front());
  px = internal::SimplifyPolyline(px, 0.25 * ss);
  if (px.size() < 2) return;
  const double hw = 0.5 * width_px * ss;
  Triangles t;
  t.reserve(6 * px.size());
  for (std::size_t i = 0; i + 1 < px.size(); ++i) {
    const Vec2 d = px[i + 1] - px[i];
    const double len = d.norm();
    if (len < 1e-9) continue;
    const Vec2 n = Vec2(-d.y(), d.x()) * (hw / len);
    AddQuad(t, px[i] + n, px[i + 1] + n, px[i + 1] - n, px[i] - n);
  }
  // Round joins and caps; under about a pixel the gaps they fill are invisible.
  if (hw > 0.75 * ss) {
    const int sides = DiscSides(hw);
    for (std::size_t i = 0; i < px.size(); ++i) {
      if (i > 0 && i + 1 < px.size()) {
        const Vec2 a = px[i] - px[i - 1];
        const Vec2 b = px[i + 1] - px[i];
        const double c = a.dot(b) / std::max(1e-12, a.norm() * b.norm());
        if (c > 0.999) continue;  // straight on: the quads already meet
      }
      AddDisc(t, px[i], hw, sides);
    }
  }
  DrawOnce(t, color);
}

void GlCanvas::DrawSegments(const std::vector<std::pair<Vec2, Vec2>>& segments_W, double width_px,
                            Rgba color) {
  if (segments_W.empty() || !(width_px > 0.0)) return;
  impl_->Bind();
  const double hw = 0.5 * width_px * impl_->ss_;
  Triangles t;
  t.reserve(6 * segments_W.size());
  for (const auto& [a_W, b_W] : segments_W) {
    const Vec2 a = impl_->Px(a_W);
    const Vec2 b = impl_->Px(b_W);
    const Vec2 d = b - a;
    const double len = d.norm();
    if (!(len > 1e-9)) continue;
    // Extended by half the width at both ends so that chains of edges close their corners.
    const Vec2 u = d * (hw / len);
    const Vec2 n(-u.y(), u.x());
    AddQuad(t, a - u + n, b + u + n, b + u - n, a - u - n);
  }
  DrawOnce(t, color);
}

namespace {

// The outline of a marker of diameter `size` (pixels) around c, as triangles.
void AddMarker(Triangles& t, Marker marker, const Vec2& c, double size) {
  const double r = 0.5 * size;
  switch (marker) {
    case Marker::kDisc:
      AddDisc(t, c, r, DiscSides(r));
      break;
    case Marker::kSquare: {
      const double h = 0.85 * r;  // about the disc's area
      AddQuad(t, c + Vec2(-h, -h), c + Vec2(h, -h), c + Vec2(h, h), c + Vec2(-h, h));
      break;
    }
    case Marker::kTriangle:  // pointing up (pixel y grows downwards)
      AddTriangle(t, c + Vec2(0.0, -1.15 * r), c + Vec2(1.0 * r, 0.6 * r),
                  c + Vec2(-1.0 * r, 0.6 * r));
      break;
    case Marker::kDiamond:
      AddQuad(t, c + Vec2(0.0, -1.2 * r), c + Vec2(r, 0.0), c + Vec2(0.0, 1.2 * r),
              c + Vec2(-r, 0.0));
      break;
    case Marker::kCross: {
      const double w = 0.3 * r;
      AddQuad(t, c + Vec2(-r, -w), c + Vec2(r, -w), c + Vec2(r, w), c + Vec2(-r, w));
      AddQuad(t, c + Vec2(-w, -r), c + Vec2(w, -r), c + Vec2(w, r), c + Vec2(-w, r));
      break;
    }
  }
}

// A dart of length L (pixels) at c pointing along pixel direction (cos, sin) = u.
void AddDart(Triangles& t, const Vec2& c, const Vec2& u, double L) {
  const Vec2 v(-u.y(), u.x());
  const Vec2 tip = c + 0.55 * L * u;
  const Vec2 left = c - 0.45 * L * u + 0.38 * L * v;
  const Vec2 right = c - 0.45 * L * u - 0.38 * L * v;
  const Vec2 notch = c - 0.2 * L * u;
  AddTriangle(t, tip, left, notch);
  AddTriangle(t, tip, notch, right);
}

}  // namespace

void GlCanvas::DrawMarkers(const std::vector<Vec2>& points_W, Marker marker, double size_px,
                           Rgba fill, double outline_px, Rgba outline) {
  if (points_W.empty() || !(size_px > 0.0)) return;
  impl_->Bind();
  const double size = size_px * impl_->ss_;
  if (outline_px > 0.0) {
    Triangles o;
    for (const Vec2& p : points_W)
      AddMarker(o, marker, impl_->Px(p), size + 2.0 * outline_px * impl_->ss_);
    Draw(o, outline);
  }
  Triangles t;
  for (const Vec2& p : points_W) AddMarker(t, marker, impl_->Px(p), size);
  Draw(t, fill);
}

void GlCanvas::DrawPoseArrows(const std::vector<core::Pose2>& poses_W, double length_px, Rgba color,
                              const std::vector<Rgba>& colors, double outline_px, Rgba outline) {
  if (poses_W.empty() || !(length_px > 0.0)) return;
  impl_->Bind();
  const double L = length_px * impl_->ss_;
  const bool per_pose = colors.size() == poses_W.size();
  auto dir = [](const core::Pose2& X) { return Vec2(std::cos(X.theta), -std::sin(X.theta)); };
  if (outline_px > 0.0) {
    Triangles o;
    const double grow = 2.5 * outline_px * impl_->ss_;
    for (const auto& X : poses_W) AddDart(o, impl_->Px(X.translation()), dir(X), L + grow);
    Draw(o, outline);
  }
  Triangles t;
  t.reserve(6 * poses_W.size());
  std::vector<Rgba> vc;
  if (per_pose) vc.reserve(6 * poses_W.size());
  for (std::size_t i = 0; i < poses_W.size(); ++i) {
    AddDart(t, impl_->Px(poses_W[i].translation()), dir(poses_W[i]), L);
    if (per_pose) vc.insert(vc.end(), 6, colors[i]);
  }
  if (per_pose) {
    DrawColored(t, vc);
  } else {
    Draw(t, color);
  }
}

void GlCanvas::DrawRaster(const CellRaster& raster_M, const core::Pose2& X_WM) {
  if (raster_M.width <= 0 || raster_M.height <= 0) return;
  RETRACE_CHECK(raster_M.cells.size() == static_cast<std::size_t>(raster_M.width) *
                                             static_cast<std::size_t>(raster_M.height));
  impl_->Bind();
  // Tiles keep every texture well inside the renderer's limit.
  constexpr int kTile = 4096;
  const double res = raster_M.resolution;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  std::vector<Rgba> tile;
  for (int y0 = 0; y0 < raster_M.height; y0 += kTile) {
    for (int x0 = 0; x0 < raster_M.width; x0 += kTile) {
      const int tw = std::min(kTile, raster_M.width - x0);
      const int th = std::min(kTile, raster_M.height - y0);
      tile.resize(static_cast<std::size_t>(tw) * static_cast<std::size_t>(th));
      for (int y = 0; y < th; ++y) {
        std::copy_n(
            raster_M.cells.begin() + (static_cast<std::ptrdiff_t>(y0 + y) * raster_M.width + x0),
            tw, tile.begin() + static_cast<std::ptrdiff_t>(y) * tw);
      }
      GLuint tex = 0;
      glGenTextures(1, &tex);
      glBindTexture(GL_TEXTURE_2D, tex);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, tile.data());
      // Corners of the tile in M, then W, then pixels; texture row 0 is the raster's lowest y.
      const Vec2 lo = raster_M.origin + Vec2(x0 * res, y0 * res);
      const Vec2 hi = lo + Vec2(tw * res, th * res);
      const std::array<Vec2, 4> corners_M{lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
      const std::array<float, 8> uv{0, 0, 1, 0, 1, 1, 0, 1};
      std::array<float, 8> xy{};
      for (int i = 0; i < 4; ++i) {
        const Vec2 p = impl_->Px(X_WM * corners_M[static_cast<std::size_t>(i)]);
        xy[static_cast<std::size_t>(2 * i)] = static_cast<float>(p.x());
        xy[static_cast<std::size_t>(2 * i + 1)] = static_cast<float>(p.y());
      }
      glColor4ub(255, 255, 255, 255);
      glEnableClientState(GL_VERTEX_ARRAY);
      glEnableClientState(GL_TEXTURE_COORD_ARRAY);
      glVertexPointer(2, GL_FLOAT, 0, xy.data());
      glTexCoordPointer(2, GL_FLOAT, 0, uv.data());
      glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
      glDisableClientState(GL_TEXTURE_COORD_ARRAY);
      glDisableClientState(GL_VERTEX_ARRAY);
      glBindTexture(GL_TEXTURE_2D, 0);
      glDeleteTextures(1, &tex);
    }
  }
  glDisable(GL_TEXTURE_2D);
}

namespace {

// A rectangle of grid cells, both corners included.
struct CellRange {
  int x0 = 0;
  int y0 = 0;
  int x1 = -1;
  int y1 = -1;
};

// The cells of grid_M under vis_W (the view's box in W) carried into M, one cell of slack
// (x1 < x0 or y1 < y0 when there are none).
CellRange VisibleCells(const core::OccupancyGrid& grid_M, const core::Pose2& X_WM,
                       const Box2& vis_W) {
  const core::Pose2 X_MW = X_WM.Inverse();
  Box2 vis_M;
  for (const Vec2& c : {vis_W.min, vis_W.max, Vec2(vis_W.min.x(), vis_W.max.y()),
                        Vec2(vis_W.max.x(), vis_W.min.y())}) {
    vis_M.Extend(X_MW * c);
  }
  const double res = grid_M.resolution();
  const Vec2& o = grid_M.origin();
  auto clamp_x = [&](double v) {
    return static_cast<int>(std::clamp(v, -1.0, 1.0 * grid_M.width()));
  };
  auto clamp_y = [&](double v) {
    return static_cast<int>(std::clamp(v, -1.0, 1.0 * grid_M.height()));
  };
  CellRange r;
  r.x0 = std::max(0, clamp_x(std::floor((vis_M.min.x() - o.x()) / res)) - 1);
  r.y0 = std::max(0, clamp_y(std::floor((vis_M.min.y() - o.y()) / res)) - 1);
  r.x1 = std::min(grid_M.width() - 1, clamp_x(std::floor((vis_M.max.x() - o.x()) / res)) + 1);
  r.y1 = std::min(grid_M.height() - 1, clamp_y(std::floor((vis_M.max.y() - o.y()) / res)) + 1);
  return r;
}

// The log-odds shown for the block of f x f cells from (bx0, by0): the highest when it reaches
// l_occupied (a wall stays a wall), else the lowest; 0 when no cell of it is known.
float PooledLogOdds(const core::OccupancyGrid& grid_M, int bx0, int by0, int f, float l_occupied) {
  const auto& lo = grid_M.log_odds();
  float l_max = -std::numeric_limits<float>::infinity();
  float l_min = std::numeric_limits<float>::infinity();
  bool known = false;
  const int bx1 = std::min(grid_M.width(), bx0 + f);
  const int by1 = std::min(grid_M.height(), by0 + f);
  for (int y = by0; y < by1; ++y) {
    const float* row =
        lo.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(grid_M.width());
    for (int x = bx0; x < bx1; ++x) {
      const float l = row[x];
      if (l == 0.0f) continue;
      known = true;
      l_max = std::max(l_max, l);
      l_min = std::min(l_min, l);
    }
  }
  return !known ? 0.0f : (l_max >= l_occupied ? l_max : l_min);
}

// The cells from (cells.x0, cells.y0) (a multiple of f) to (cells.x1, cells.y1) coloured, f x
// f cells pooled into each raster cell.
CellRaster PooledRaster(const core::OccupancyGrid& grid_M, const CellRange& cells, int f,
                        const GridStyle& style) {
  const double res = grid_M.resolution();
  CellRaster r;
  r.resolution = res * f;
  r.origin = grid_M.origin() + Vec2(cells.x0 * res, cells.y0 * res);
  r.width = (cells.x1 - cells.x0) / f + 1;
  r.height = (cells.y1 - cells.y0) / f + 1;
  r.cells.resize(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  const float l_occupied = static_cast<float>(core::Logit(style.occupied_probability));
  for (int py = 0; py < r.height; ++py) {
    for (int px = 0; px < r.width; ++px) {
      const float l = PooledLogOdds(grid_M, cells.x0 + px * f, cells.y0 + py * f, f, l_occupied);
      r.cells[static_cast<std::size_t>(py) * static_cast<std::size_t>(r.width) +
              static_cast<std::size_t>(px)] = GridCellColor(l, style);
    }
  }
  return r;
}

}  // namespace

void GlCanvas::DrawGrid(const core::OccupancyGrid& grid_M, const core::Pose2& X_WM,
                        const GridStyle& style) {
  if (grid_M.empty()) return;
  // The visible part of the grid: the view's box carried into M, in cells, one cell of slack.
  CellRange cells = VisibleCells(grid_M, X_WM, impl_->view_.VisibleBox());
  if (cells.x1 < cells.x0 || cells.y1 < cells.y0) return;

  // Pool blocks of f x f cells when a cell is under one (supersampled) pixel; blocks are
  // aligned to the grid, not the view, so a moving view does not make walls shimmer.
  const double cell_px = grid_M.resolution() * impl_->view_ss_.pixels_per_meter();
  const int f = cell_px >= 1.0 ? 1 : std::min(256, static_cast<int>(std::ceil(1.0 / cell_px)));
  cells.x0 -= cells.x0 % f;
  cells.y0 -= cells.y0 % f;
  DrawRaster(PooledRaster(grid_M, cells, f, style), X_WM);
}

Image GlCanvas::ReadBack() { return impl_->ReadBack(); }

}  // namespace retrace::viz
