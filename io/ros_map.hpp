#pragma once
// ROS map_server maps: a YAML metadata file next to a PGM or PNG image, read and written with
// map_server's semantics. Image row 0 is the top of the map (largest y); the grid's row 0 is
// the lowest y, so rows are flipped on I/O. The grid origin is the world position (m) of the
// lower-left corner of the lower-left pixel, as in the YAML's `origin`.
//
// Reading: a pixel value v (0..255; the mean of the colour channels for colour images) has
// occupancy p = (255 - v) / 255, or v / 255 with `negate: 1`.
//   trinary: p > occupied_thresh → occupied, p < free_thresh → free, otherwise unknown.
//   scale:   occupied and free as in trinary; in between the cell keeps p as its probability.
//   raw:     v (after negate) is an occupancy percentage 0..100; 255 is unknown.
// Cells are stored as log-odds: occupied = Logit(kRosMapOccupiedProbability), free =
// Logit(kRosMapFreeProbability), unknown = 0; scale and raw probabilities are clamped into
// [kRosMapFreeProbability, kRosMapOccupiedProbability]. Alpha follows nav2_map_server: in
// scale mode a pixel that is not fully opaque is unknown; trinary and raw modes ignore alpha.

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "core/config.hpp"
#include "core/occupancy_grid.hpp"

namespace retrace::io {

/// Probability given to occupied cells of a map read from file (log-odds about +2.94).
inline constexpr double kRosMapOccupiedProbability = 0.95;
/// Probability given to free cells of a map read from file (log-odds about -2.94).
inline constexpr double kRosMapFreeProbability = 0.05;
/// A cell is known free below map_saver's default free threshold (trinary maps store 0.05 for
/// free, 0.5 for unknown and 0.95 for occupied cells).
inline constexpr double kRosMapKnownFreeBelow = 0.196;

/// How map_server interprets pixel values (the YAML's `mode`).
enum class RosMapMode { kTrinary, kScale, kRaw };

}  // namespace retrace::io

namespace retrace::core {
template <>
struct EnumTraits<io::RosMapMode> {
  static constexpr std::array<std::pair<io::RosMapMode, std::string_view>, 3> kNames = {{
      {io::RosMapMode::kTrinary, "trinary"},
      {io::RosMapMode::kScale, "scale"},
      {io::RosMapMode::kRaw, "raw"},
  }};
};
}  // namespace retrace::core

namespace retrace::io {

/// The map_server YAML file. `image`, `resolution` and `origin` are required in files.
struct RosMapMetadata {
  std::string image;                      ///< image path, relative to the YAML's folder
  double resolution = 0.05;               ///< m per pixel
  std::array<double, 3> origin{0, 0, 0};  ///< x (m), y (m), yaw (rad) of the lower-left pixel
  int negate = 0;                         ///< 1: white is occupied
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  RosMapMode mode = RosMapMode::kTrinary;

  template <class V>
  void Reflect(V& v) {
    v("image", image);
    v("resolution", resolution);
    v("origin", origin);
    v("negate", negate);
    v("occupied_thresh", occupied_thresh);
    v("free_thresh", free_thresh);
    v("mode", mode);
  }
  /// Throws core::ConfigError for an empty image name, a non-positive resolution, negate not
  /// 0 or 1, thresholds outside [0, 1] or free_thresh >= occupied_thresh.
  void Validate() const;
};

/// Reads and validates a map YAML strictly (unknown keys are errors, as are missing required
/// keys). A non-zero origin yaw is accepted here; ReadRosMap refuses it.
/// Throws core::IoError if the file cannot be read, core::ConfigError (with file and line)
/// for invalid content.
RosMapMetadata ReadRosMapMetadata(const std::filesystem::path& yaml);

/// Reads a map (YAML + PGM/PNG/any image OpenCV decodes) into a log-odds grid in the map
/// frame. PGM (P5 binary and P2 ASCII, maxval <= 255) is parsed strictly: pixel data shorter
/// or longer than width x height is an error. Throws core::ConfigError (file:line) for
/// invalid metadata, including a non-zero origin yaw (not supported by OccupancyGrid), and
/// core::IoError for a missing, undecodable or malformed image, a 16-bit image, or (raw
/// mode) a value in 101..254.
core::OccupancyGrid ReadRosMap(const std::filesystem::path& yaml);

enum class RosMapImageFormat { kPgm, kPng };

struct RosMapWriteOptions {
  RosMapImageFormat image_format = RosMapImageFormat::kPgm;
  /// trinary (0 occupied, 254 free, 205 unknown, as map_saver and AutoNavi write) or scale;
  /// raw is not supported for writing.
  RosMapMode mode = RosMapMode::kTrinary;
  /// A cell with probability above this is occupied, below free_thresh free. In scale mode
  /// they are also written into the YAML and cells in between keep their probability. In
  /// trinary mode the YAML gets map_saver's 0.65 / 0.196, which classify 0 / 205 / 254.
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
};

/// Writes `grid` as `yaml` plus an image of the same stem beside it (`ogm_0.yaml` →
/// `ogm_0.pgm` or `ogm_0.png`), origin yaw 0. Each file is written atomically, the image
/// first, so the YAML never names a missing or partial image. Reading back reproduces the
/// cell classes (trinary) or, in scale mode, the in-between probabilities within 1/510.
/// Throws core::ConfigError for invalid options, core::IoError for an empty grid or if a file
/// cannot be written.
void WriteRosMap(const std::filesystem::path& yaml, const core::OccupancyGrid& grid,
                 const RosMapWriteOptions& options = {});

}  // namespace retrace::io
