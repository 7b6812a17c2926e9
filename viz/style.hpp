#pragma once
// The palette shared by every figure and video, so that one concept has one colour everywhere:
// the taught (target) path is black, ground truth green, the estimate blue, odometry orange,
// particles magenta, pedestrians purple, rejected (dynamic) scan points red, static scan points
// sky blue, map-switch points gold. Runs, partial maps and map modes each have their own
// cycle. Colours are mostly Okabe-Ito and Paul Tol's, chosen to stay apart for colour-blind
// readers and in greyscale print.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace retrace::viz {

/// An 8-bit sRGB colour with opacity (a = 255: opaque).
struct Rgba {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  std::uint8_t a = 255;

  constexpr Rgba WithAlpha(std::uint8_t alpha) const { return {r, g, b, alpha}; }
  bool operator==(const Rgba&) const = default;
};

namespace palette {

inline constexpr Rgba kBackground{255, 255, 255};
inline constexpr Rgba kText{20, 20, 20};
inline constexpr Rgba kAxis{60, 60, 60};
inline constexpr Rgba kGridLine{225, 225, 225};

// The world's static geometry (buildings, walls, trees) under trajectories.
inline constexpr Rgba kWorldSolid{178, 178, 178};
inline constexpr Rgba kWorldEdge{120, 120, 120};

// Occupancy grids: free white, unknown light grey, occupied near black, as map_server images.
inline constexpr Rgba kMapFree{255, 255, 255};
inline constexpr Rgba kMapUnknown{212, 212, 212};
inline constexpr Rgba kMapOccupied{30, 30, 30};

inline constexpr Rgba kTaughtPath{0, 0, 0};
inline constexpr Rgba kTruth{0, 158, 115};
inline constexpr Rgba kEstimate{0, 114, 178};
inline constexpr Rgba kOdometry{230, 159, 0};
inline constexpr Rgba kParticle{225, 40, 160};
inline constexpr Rgba kPedestrian{117, 82, 180};
inline constexpr Rgba kRejectedPoint{220, 20, 20};
inline constexpr Rgba kStaticPoint{86, 180, 233};
inline constexpr Rgba kStart{255, 255, 255};  ///< filled, with a black outline
inline constexpr Rgba kSwitch{255, 200, 0};   ///< filled, with a black outline
inline constexpr Rgba kInsetFrame{200, 0, 90};

/// Playback runs (Tableau 10 without grey).
inline constexpr std::array<Rgba, 9> kRuns{{{31, 119, 180},
                                            {255, 127, 14},
                                            {44, 160, 44},
                                            {214, 39, 40},
                                            {148, 103, 189},
                                            {140, 86, 75},
                                            {227, 119, 194},
                                            {188, 189, 34},
                                            {23, 190, 207}}};

/// Partial maps: the route segment and path of map k (Paul Tol's bright).
inline constexpr std::array<Rgba, 6> kMaps{{{68, 119, 170},
                                            {238, 102, 119},
                                            {34, 136, 51},
                                            {204, 187, 68},
                                            {102, 204, 238},
                                            {170, 51, 119}}};

}  // namespace palette

/// Colour of playback run i (0-based), cycling.
inline constexpr Rgba RunColor(int i) {
  return palette::kRuns[static_cast<std::size_t>(i < 0 ? 0 : i) % palette::kRuns.size()];
}

/// Colour of partial map k (0-based), cycling.
inline constexpr Rgba MapColor(int k) {
  return palette::kMaps[static_cast<std::size_t>(k < 0 ? 0 : k) % palette::kMaps.size()];
}

/// Colour of a map mode: `partial` blue, `single` vermillion, `consistent` green,
/// `scan_matched` reddish purple; any other name gets a colour from its position `index` among
/// the modes shown.
inline constexpr Rgba ModeColor(std::string_view mode, int index) {
  if (mode == "partial") return {0, 114, 178};
  if (mode == "single") return {213, 94, 0};
  if (mode == "consistent") return {0, 158, 115};
  if (mode == "scan_matched") return {204, 121, 167};
  constexpr std::array<Rgba, 3> kOthers{{{86, 180, 233}, {230, 159, 0}, {90, 90, 90}}};
  return kOthers[static_cast<std::size_t>(index < 0 ? 0 : index) % kOthers.size()];
}

/// The maps a mode navigates in, for titles: "partial maps", "one odometry map", "a consistent
/// map", "scan-matched partial maps"; any other name: "<name> maps".
inline std::string ModeMaps(std::string_view mode) {
  if (mode == "partial") return "partial maps";
  if (mode == "scan_matched") return "scan-matched partial maps";
  if (mode == "single") return "one odometry map";
  if (mode == "consistent") return "a consistent map";
  return std::string(mode) + " maps";
}

}  // namespace retrace::viz
