#pragma once
// The error of the renderer: no off-screen OpenGL context, a canvas too large for it, or a video
// that cannot be encoded. Figures are written after the numeric results, so a caller that
// catches RenderError keeps every trajectory and metric it has already written.

#include "core/errors.hpp"

namespace retrace::viz {

/// Rendering failed (OSMesa context, canvas size, video codec). File writes that fail throw
/// core::IoError instead.
class RenderError : public core::Error {
 public:
  using core::Error::Error;
};

}  // namespace retrace::viz
