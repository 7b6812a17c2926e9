#include "io/ros_map.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "core/check.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/limits.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/decoded_image.hpp"
#include "io/internal/image_header.hpp"
#include "io/internal/png_reader.hpp"
#include "io/png.hpp"
#include "io/read_file.hpp"

namespace retrace::io {
namespace {

// ---------------------------------------------------------------------------------------------
// Netpbm: PGM (P2 ASCII, P5 binary), PBM (P1, P4) and PPM (P3, P6), parsed strictly here rather
// than by a decoder that prints its complaints: the pixel data must hold exactly what the header
// declares, 8-bit samples only.

class NetpbmParser {
 public:
  NetpbmParser(const std::string& bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {
    RETRACE_CHECK(bytes_.size() >= 2 && bytes_[0] == 'P' && bytes_[1] >= '1' && bytes_[1] <= '6');
    const char kind = bytes_[1];
    bitmap_ = kind == '1' || kind == '4';
    binary_ = kind >= '4';
    channels_ = kind == '3' || kind == '6' ? 3 : 1;
    name_ = bitmap_ ? "PBM" : channels_ == 3 ? "PPM" : "PGM";
  }

  DecodedImage Parse() {
    pos_ = 2;
    const std::int64_t width = HeaderNumber("width");
    const std::int64_t height = HeaderNumber("height");
    const std::int64_t maxval = bitmap_ ? 1 : HeaderNumber("maxval");
    if (width == 0 || height == 0) {
      Fail(name_ + " header gives an empty image (" + std::to_string(width) + " x " +
           std::to_string(height) + ")");
    }
    if (width > core::kMaxMapCells || height > core::kMaxMapCells ||
        width * height > core::kMaxMapCells) {
      Fail(name_ + " header declares " + std::to_string(width) + " x " + std::to_string(height) +
           " pixels; retrace's limit for a map is " +
           std::to_string(core::kMaxMapCells / 1'000'000) + " million cells");
    }
    if (maxval == 0 || maxval > 255) {
      Fail(name_ + " maxval " + std::to_string(maxval) +
           " is not supported: only 8-bit images (maxval 1..255) are");
    }
    // Exactly one whitespace character separates the header from the pixel data.
    if (pos_ >= bytes_.size()) Fail(name_ + " has no pixel data after its header");
    if (!IsSpace(bytes_[pos_])) Fail("malformed " + name_ + " header after its last number");
    ++pos_;

    const std::uint64_t expected = static_cast<std::uint64_t>(width) *
                                   static_cast<std::uint64_t>(height) *
                                   static_cast<std::uint64_t>(channels_);
    std::vector<std::uint8_t> values;
    if (bitmap_) {
      values = binary_ ? PackedBits(width, height) : AsciiValues(expected, width, height);
      for (std::uint8_t& v : values) v = v != 0 ? 0 : 255;  // 1 is black
    } else {
      values =
          binary_ ? BinaryValues(expected, width, height) : AsciiValues(expected, width, height);
      for (std::uint8_t& v : values) {
        if (v > maxval) {
          Fail(name_ + " pixel value " + std::to_string(v) + " exceeds the header's maxval " +
               std::to_string(maxval));
        }
        // Stretch to 0..255 the way map_server's image loader (SDL_image) does.
        if (maxval < 255) v = static_cast<std::uint8_t>(v * 255 / maxval);
      }
    }
    DecodedImage image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.channels = channels_;
    image.data = std::move(values);
    return image;
  }

 private:
  static bool IsSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw core::IoError(path_.string() + ": " + what);
  }

  // `bytes` for an error message: unprintable ones as \xNN.
  static std::string Printable(const std::string& bytes) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string shown;
    for (const char ch : bytes) {
      const auto c = static_cast<unsigned char>(ch);
      if (std::isprint(c) != 0) {
        shown += ch;
      } else {
        shown += "\\x";
        shown += kHex[c >> 4];
        shown += kHex[c & 15];
      }
    }
    return shown;
  }

  void SkipSpaceAndComments() {
    while (pos_ < bytes_.size()) {
      if (IsSpace(bytes_[pos_])) {
        ++pos_;
      } else if (bytes_[pos_] == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
      } else {
        break;
      }
    }
  }

  // A non-negative decimal integer token; `what` names it in error messages.
  std::int64_t Number(const std::string& what, bool in_header) {
    SkipSpaceAndComments();
    if (pos_ >= bytes_.size()) {
      Fail(in_header ? "truncated " + name_ + " header: the file ends before the " + what
                     : name_ + " pixel data ends early");
    }
    const std::size_t start = pos_;
    std::int64_t value = 0;
    while (pos_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[pos_]))) {
      value = value * 10 + (bytes_[pos_] - '0');
      if (value > std::numeric_limits<int>::max()) Fail(name_ + " " + what + " is too large");
      ++pos_;
    }
    if (pos_ == start || (pos_ < bytes_.size() && !IsSpace(bytes_[pos_]) && bytes_[pos_] != '#')) {
      std::size_t end = start;
      while (end < bytes_.size() && !IsSpace(bytes_[end]) && end - start < 16) ++end;
      Fail("malformed " + name_ + " " + std::string(in_header ? "header" : "pixel data") +
           ": the " + what + " '" + Printable(bytes_.substr(start, end - start)) +
           "' is not a non-negative integer");
    }
    return value;
  }

  std::int64_t HeaderNumber(const std::string& what) { return Number(what, true); }

  // `got` pixel-data units (bytes or values) where the header's size needs `expected`.
  [[noreturn]] void FailSize(std::uint64_t got, std::uint64_t expected, std::int64_t width,
                             std::int64_t height, const char* unit) const {
    std::string need = std::to_string(width) + " x " + std::to_string(height);
    if (channels_ == 3) need += " x 3 samples";
    need += bitmap_ && binary_
                ? " pixels, " + std::to_string(expected) + " bytes packed"
                : " = " + std::to_string(expected) + (channels_ == 3 ? "" : " pixels");
    Fail(name_ + " has the wrong size: its pixel data holds " + std::to_string(got) + " " + unit +
         " but the header says " + need + " (" +
         (got < expected ? "the file is truncated" : "there is extra data after the image") +
         ", or the header is wrong)");
  }

  std::vector<std::uint8_t> BinaryValues(std::uint64_t expected, std::int64_t width,
                                         std::int64_t height) const {
    const std::uint64_t got = bytes_.size() - pos_;
    if (got != expected) FailSize(got, expected, width, height, "bytes");
    return std::vector<std::uint8_t>(bytes_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                     bytes_.end());
  }

  // P4: rows of ceil(width / 8) bytes, the most significant bit first.
  std::vector<std::uint8_t> PackedBits(std::int64_t width, std::int64_t height) const {
    const std::uint64_t row = static_cast<std::uint64_t>(width + 7) / 8;
    const std::uint64_t got = bytes_.size() - pos_;
    const std::uint64_t expected = row * static_cast<std::uint64_t>(height);
    if (got != expected) FailSize(got, expected, width, height, "bytes");
    std::vector<std::uint8_t> values(static_cast<std::size_t>(width * height));
    for (std::int64_t y = 0; y < height; ++y) {
      for (std::int64_t x = 0; x < width; ++x) {
        const auto byte = static_cast<unsigned char>(
            bytes_[pos_ + static_cast<std::size_t>(y) * row + static_cast<std::size_t>(x / 8)]);
        values[static_cast<std::size_t>(y * width + x)] =
            static_cast<std::uint8_t>((byte >> (7 - x % 8)) & 1);
      }
    }
    return values;
  }

  // P1: one character '0' or '1' per pixel; whitespace between them is optional.
  std::int64_t BitCharacter() {
    const char c = bytes_[pos_++];
    if (c != '0' && c != '1') {
      Fail("malformed PBM pixel data: '" + Printable(std::string(1, c)) + "' is not 0 or 1");
    }
    return c - '0';
  }

  // P1, P2, P3: whitespace-separated values.
  std::vector<std::uint8_t> AsciiValues(std::uint64_t expected, std::int64_t width,
                                        std::int64_t height) {
    std::vector<std::uint8_t> values;
    std::uint64_t count = 0;
    while (true) {
      SkipSpaceAndComments();
      if (pos_ >= bytes_.size()) break;
      const std::int64_t v = bitmap_ ? BitCharacter() : Number("pixel value", false);
      if (v > 255) Fail(name_ + " pixel value " + std::to_string(v) + " exceeds 255");
      // Only store what fits, so a lying header cannot make us allocate without bound.
      if (count < expected) values.push_back(static_cast<std::uint8_t>(v));
      ++count;
    }
    if (count != expected) FailSize(count, expected, width, height, "values");
    return values;
  }

  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::string name_;
  bool bitmap_ = false;
  bool binary_ = false;
  int channels_ = 1;
  std::size_t pos_ = 0;
};

DecodedImage ReadImage(const std::filesystem::path& path) {
  const std::string bytes = ReadFileBytes(path);
  if (bytes.empty()) throw core::IoError(path.string() + ": the image file is empty");
  // The declared size and structure are checked before any decoder allocates for them.
  const internal::ImageHeader header = internal::CheckImageHeader(bytes, path);
  if (header.format == internal::ImageFormat::kPng) return internal::ReadPng(bytes, path);
  return NetpbmParser(bytes, path).Parse();
}

// ---------------------------------------------------------------------------------------------
// Pixel semantics.

float ClampedLogOdds(double p) {
  return static_cast<float>(
      core::Logit(std::clamp(p, kRosMapFreeProbability, kRosMapOccupiedProbability)));
}

// Log-odds of a pixel whose colour channels sum to `sum` over `colours` channels; NaN marks a
// raw value outside 0..100 and 255.
float PixelLogOdds(int sum, int colours, bool opaque, const RosMapMetadata& meta) {
  double v = static_cast<double>(sum) / colours;  // map_server averages the colour channels
  if (meta.negate != 0) v = 255.0 - v;
  if (meta.mode == RosMapMode::kRaw) {
    const long value = std::lround(v);
    if (value == 255) return 0.0f;
    if (value > 100) return std::numeric_limits<float>::quiet_NaN();
    return ClampedLogOdds(static_cast<double>(value) / 100.0);
  }
  if (meta.mode == RosMapMode::kScale && !opaque) return 0.0f;
  const double p = (255.0 - v) / 255.0;
  if (p > meta.occupied_thresh) return ClampedLogOdds(kRosMapOccupiedProbability);
  if (p < meta.free_thresh) return ClampedLogOdds(kRosMapFreeProbability);
  if (meta.mode == RosMapMode::kTrinary) return 0.0f;
  return ClampedLogOdds(p);
}

core::OccupancyGrid ImageToGrid(const DecodedImage& image, const RosMapMetadata& meta,
                                const std::filesystem::path& image_path) {
  for (const double extent : {meta.origin[0] + image.width * meta.resolution,
                              meta.origin[1] + image.height * meta.resolution}) {
    if (!(std::abs(extent) <= core::kMaxCoordinate)) {
      throw core::IoError(image_path.string() + ": the map reaches " + core::FormatNumber(extent) +
                          " m from the origin (" + std::to_string(image.width) + " x " +
                          std::to_string(image.height) + " cells of " +
                          core::FormatNumber(meta.resolution) + " m); retrace's limit is " +
                          core::FormatNumber(core::kMaxCoordinate) + " m");
    }
  }
  core::OccupancyGrid grid(image.width, image.height, meta.resolution,
                           core::Vec2(meta.origin[0], meta.origin[1]));
  const bool has_alpha = image.channels == 2 || image.channels == 4;
  const int colours = has_alpha ? image.channels - 1 : image.channels;
  // One lookup table per opacity, indexed by the sum of the colour channels.
  std::vector<float> opaque_table(static_cast<std::size_t>(255 * colours + 1));
  std::vector<float> transparent_table(opaque_table.size());
  for (int s = 0; s <= 255 * colours; ++s) {
    opaque_table[static_cast<std::size_t>(s)] = PixelLogOdds(s, colours, true, meta);
    transparent_table[static_cast<std::size_t>(s)] = PixelLogOdds(s, colours, false, meta);
  }
  const std::size_t stride = static_cast<std::size_t>(image.channels);
  for (int row = 0; row < image.height; ++row) {
    const int cy = image.height - 1 - row;  // image row 0 is the top of the map
    for (int col = 0; col < image.width; ++col) {
      const std::uint8_t* px =
          &image.data[(static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) +
                       static_cast<std::size_t>(col)) *
                      stride];
      int sum = 0;
      for (int k = 0; k < colours; ++k) sum += px[k];
      const bool opaque = !has_alpha || px[image.channels - 1] == 255;
      const float l = (opaque ? opaque_table : transparent_table)[static_cast<std::size_t>(sum)];
      if (std::isnan(l)) {
        throw core::IoError(image_path.string() + ": pixel (" + std::to_string(col) + ", " +
                            std::to_string(row) + ") has value " +
                            std::to_string(std::lround(static_cast<double>(sum) / colours)) +
                            ", which is not a raw occupancy (0..100, or 255 for unknown)");
      }
      grid.SetLogOdds({col, cy}, l);
    }
  }
  return grid;
}

RosMapMetadata ParseMetadata(const YAML::Node& root, const std::string& source) {
  if (root.IsMap()) {
    const internal::ReadContext ctx{source, "", nullptr};
    for (const char* key : {"image", "resolution", "origin"}) {
      if (!root[key]) internal::Fail(root, ctx.Child(key), "required key is missing");
    }
  }
  return ReadConfig<RosMapMetadata>(root, source);
}

// Throws core::ConfigError unless the options can be written: trinary or scale, and thresholds
// in [0, 1] with free_thresh below occupied_thresh.
void ValidateWriteOptions(const RosMapWriteOptions& options) {
  if (options.mode == RosMapMode::kRaw) {
    throw core::ConfigError("mode", "raw maps cannot be written; use trinary or scale");
  }
  core::RequireInRange("occupied_thresh", options.occupied_thresh, 0.0, 1.0);
  core::RequireInRange("free_thresh", options.free_thresh, 0.0, 1.0);
  if (!(options.free_thresh < options.occupied_thresh)) {
    throw core::ConfigError("free_thresh", "must be below occupied_thresh");
  }
}

// The image's grey values, top row first: 0 occupied, 254 free, 205 unknown (trinary) or the
// scaled occupancy (scale), by the thresholds of `options`.
std::vector<std::uint8_t> GridToPixels(const core::OccupancyGrid& grid,
                                       const RosMapWriteOptions& options) {
  const int w = grid.width();
  const int h = grid.height();
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int cy = 0; cy < h; ++cy) {
    const int row = h - 1 - cy;
    for (int cx = 0; cx < w; ++cx) {
      const float l = grid.LogOdds({cx, cy});
      RETRACE_CHECK(!std::isnan(l));
      const double q = core::InverseLogit(l);
      std::uint8_t v = 0;
      if (q > options.occupied_thresh) {
        v = 0;
      } else if (q < options.free_thresh) {
        v = 254;
      } else if (options.mode == RosMapMode::kTrinary) {
        v = 205;
      } else {
        v = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - q)));
      }
      pixels[static_cast<std::size_t>(row) * static_cast<std::size_t>(w) +
             static_cast<std::size_t>(cx)] = v;
    }
  }
  return pixels;
}

// The pixels (w x h) as a PNG file's bytes; throws core::IoError naming `path` if encoding fails.
std::string EncodeMapPng(const std::vector<std::uint8_t>& pixels, int w, int h,
                         const std::filesystem::path& path) {
  try {
    return io::EncodePng(pixels, w, h, 1);
  } catch (const core::IoError& e) {
    throw core::IoError(path.string() + ": " + e.what());
  }
}

// The pixels of `grid` as a binary PGM file's bytes, the resolution in its comment.
std::string EncodePgm(const std::vector<std::uint8_t>& pixels, const core::OccupancyGrid& grid) {
  std::string bytes = "P5\n# CREATOR: retrace " + core::FormatNumber(grid.resolution()) +
                      " m/pix\n" + std::to_string(grid.width()) + " " +
                      std::to_string(grid.height()) + "\n255\n";
  bytes.append(pixels.begin(), pixels.end());
  return bytes;
}

// The map's YAML for the image `image_name` of `grid`, written with `options`.
RosMapMetadata WrittenMetadata(const std::string& image_name, const core::OccupancyGrid& grid,
                               const RosMapWriteOptions& options) {
  RosMapMetadata meta;
  meta.image = image_name;
  meta.resolution = grid.resolution();
  meta.origin = {grid.origin().x(), grid.origin().y(), 0.0};
  meta.negate = 0;
  meta.mode = options.mode;
  if (options.mode == RosMapMode::kScale) {
    meta.occupied_thresh = options.occupied_thresh;
    meta.free_thresh = options.free_thresh;
  }  // trinary: map_saver's 0.65 / 0.196 (the defaults) classify 0 / 205 / 254 correctly
  return meta;
}

}  // namespace

void RosMapMetadata::Validate() const {
  if (image.empty()) throw core::ConfigError("image", "must name an image file");
  core::RequireWorldLength("resolution", resolution);
  core::RequireCoordinate("origin", origin[0]);
  core::RequireCoordinate("origin", origin[1]);
  if (negate != 0 && negate != 1) {
    throw core::ConfigError("negate", "must be 0 or 1, got " + std::to_string(negate));
  }
  core::RequireInRange("occupied_thresh", occupied_thresh, 0.0, 1.0);
  core::RequireInRange("free_thresh", free_thresh, 0.0, 1.0);
  if (!(free_thresh < occupied_thresh)) {
    throw core::ConfigError("free_thresh", "must be below occupied_thresh (" +
                                               core::FormatNumber(occupied_thresh) + "), got " +
                                               core::FormatNumber(free_thresh));
  }
}

RosMapMetadata ReadRosMapMetadata(const std::filesystem::path& yaml) {
  return ParseMetadata(LoadYamlFile(yaml), yaml.string());
}

core::OccupancyGrid ReadRosMap(const std::filesystem::path& yaml) {
  const YAML::Node root = LoadYamlFile(yaml);
  const RosMapMetadata meta = ParseMetadata(root, yaml.string());
  if (meta.origin[2] != 0.0) {
    const internal::ReadContext ctx{yaml.string(), "origin", nullptr};
    internal::Fail(root["origin"], ctx,
                   "origin yaw " + core::FormatNumber(meta.origin[2]) +
                       " rad is not supported: retrace's occupancy grids are axis-aligned; "
                       "rotate the image and set the yaw to 0");
  }
  std::filesystem::path image_path(meta.image);
  if (image_path.is_relative()) image_path = yaml.parent_path() / image_path;
  std::error_code ec;
  if (!std::filesystem::exists(image_path, ec)) {
    throw core::IoError(yaml.string() + ": image '" + meta.image + "' not found (looked for " +
                        image_path.string() + ")");
  }
  return ImageToGrid(ReadImage(image_path), meta, image_path);
}

void WriteRosMap(const std::filesystem::path& yaml, const core::OccupancyGrid& grid,
                 const RosMapWriteOptions& options) {
  ValidateWriteOptions(options);
  if (grid.empty()) {
    throw core::IoError(yaml.string() + ": cannot write an empty map (" +
                        std::to_string(grid.width()) + " x " + std::to_string(grid.height()) +
                        " cells)");
  }
  std::vector<std::uint8_t> pixels = GridToPixels(grid, options);
  const bool png = options.image_format == RosMapImageFormat::kPng;
  std::filesystem::path image_name = yaml.filename();
  image_name.replace_extension(png ? ".png" : ".pgm");
  const std::filesystem::path image_path = yaml.parent_path() / image_name;
  const std::string image_bytes =
      png ? EncodeMapPng(pixels, grid.width(), grid.height(), image_path) : EncodePgm(pixels, grid);
  const RosMapMetadata meta = WrittenMetadata(image_name.string(), grid, options);
  // Image first: the YAML must never name a missing or partial image.
  WriteFileAtomic(image_path, image_bytes);
  WriteFileAtomic(yaml, ConfigToYaml(meta));
}

}  // namespace retrace::io
