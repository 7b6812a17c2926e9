#include "io/ros_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

const float kOccupied = static_cast<float>(core::Logit(kRosMapOccupiedProbability));
const float kFree = static_cast<float>(core::Logit(kRosMapFreeProbability));

enum class Cls { kFreeCell, kUnknownCell, kOccupiedCell };

Cls ClassOf(float log_odds) {
  const double p = core::InverseLogit(log_odds);
  if (p > 0.65) return Cls::kOccupiedCell;
  if (p < 0.196) return Cls::kFreeCell;
  return Cls::kUnknownCell;
}

// A non-square grid with every class in a pattern that tells rows, columns and flips apart.
core::OccupancyGrid PatternGrid() {
  core::OccupancyGrid grid(7, 4, 0.05, core::Vec2(-1.25, 2.5));
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const int k = (x + 2 * y + x * y) % 3;
      grid.SetLogOdds({x, y}, k == 0   ? static_cast<float>(core::Logit(0.9))
                              : k == 1 ? static_cast<float>(core::Logit(0.1))
                                       : 0.0f);
    }
  }
  return grid;
}

class RosMapTest : public ::testing::Test {
 protected:
  // A map YAML for `image` with extra lines appended.
  fs::path WriteYaml(const std::string& image, const std::string& extra = "",
                     const std::string& name = "map.yaml") const {
    return tmp_.Write(name,
                      "image: " + image + "\nresolution: 0.1\norigin: [-2.0, 3.0, 0.0]\n" + extra);
  }

  // The message of the exception ReadRosMap throws (of type E), or "" if none.
  template <class E>
  std::string ErrorOf(const fs::path& yaml) const {
    try {
      ReadRosMap(yaml);
    } catch (const E& e) {
      return e.what();
    } catch (const std::exception& e) {
      return std::string("wrong exception type: ") + e.what();
    }
    return "";
  }

  retrace::testing::TempDir tmp_;
};

void ExpectSameGeometry(const core::OccupancyGrid& a, const core::OccupancyGrid& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  EXPECT_EQ(a.resolution(), b.resolution());
  EXPECT_EQ(a.origin(), b.origin());
}

void ExpectSameClasses(const core::OccupancyGrid& written, const core::OccupancyGrid& read) {
  ExpectSameGeometry(written, read);
  for (int y = 0; y < written.height(); ++y) {
    for (int x = 0; x < written.width(); ++x) {
      const Cls c = ClassOf(written.LogOdds({x, y}));
      const float expected = c == Cls::kOccupiedCell ? kOccupied
                             : c == Cls::kFreeCell   ? kFree
                                                     : 0.0f;
      EXPECT_EQ(read.LogOdds({x, y}), expected) << "cell " << x << ", " << y;
    }
  }
}

TEST_F(RosMapTest, TrinaryPgmRoundTripKeepsClassesAndGeometry) {
  const core::OccupancyGrid grid = PatternGrid();
  WriteRosMap(tmp_.path() / "maps" / "ogm_0.yaml", grid);
  EXPECT_TRUE(fs::exists(tmp_.path() / "maps" / "ogm_0.pgm"));
  ExpectSameClasses(grid, ReadRosMap(tmp_.path() / "maps" / "ogm_0.yaml"));

  const RosMapMetadata meta = ReadRosMapMetadata(tmp_.path() / "maps" / "ogm_0.yaml");
  EXPECT_EQ(meta.image, "ogm_0.pgm");
  EXPECT_EQ(meta.resolution, 0.05);
  EXPECT_EQ(meta.origin, (std::array<double, 3>{-1.25, 2.5, 0.0}));
  EXPECT_EQ(meta.mode, RosMapMode::kTrinary);
  EXPECT_EQ(meta.negate, 0);
  EXPECT_EQ(meta.occupied_thresh, 0.65);
  EXPECT_EQ(meta.free_thresh, 0.196);
}

TEST_F(RosMapTest, TrinaryPgmUsesMapSaverValuesAndTopRowFirst) {
  core::OccupancyGrid grid(3, 2, 0.1, core::Vec2(0, 0));
  grid.SetProbability({0, 1}, 0.9);  // top-left in the image
  grid.SetProbability({1, 1}, 0.1);
  grid.SetProbability({2, 0}, 0.9);  // bottom-right in the image
  WriteRosMap(tmp_.path() / "m.yaml", grid);
  const std::string pgm = tmp_.Read(tmp_.path() / "m.pgm");
  ASSERT_GE(pgm.size(), 6u);
  EXPECT_EQ(pgm.substr(0, 3), "P5\n");
  const std::string pixels = pgm.substr(pgm.size() - 6);
  EXPECT_EQ(pixels, std::string("\x00\xfe\xcd\xcd\xcd\x00", 6));  // 0 occupied, 254, 205
  EXPECT_NE(pgm.find("\n3 2\n255\n"), std::string::npos);
}

TEST_F(RosMapTest, TrinaryPngRoundTripKeepsClasses) {
  const core::OccupancyGrid grid = PatternGrid();
  RosMapWriteOptions options;
  options.image_format = RosMapImageFormat::kPng;
  WriteRosMap(tmp_.path() / "ogm_1.yaml", grid, options);
  EXPECT_TRUE(fs::exists(tmp_.path() / "ogm_1.png"));
  EXPECT_FALSE(fs::exists(tmp_.path() / "ogm_1.pgm"));
  EXPECT_EQ(tmp_.Read(tmp_.path() / "ogm_1.png").substr(1, 3), "PNG");
  ExpectSameClasses(grid, ReadRosMap(tmp_.path() / "ogm_1.yaml"));
}

// A grid whose cells span every probability, for scale mode.
core::OccupancyGrid GradientGrid() {
  core::OccupancyGrid grid(31, 9, 0.25, core::Vec2(10.0, -4.0));
  int i = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x, ++i) {
      grid.SetProbability({x, y}, 0.001 + 0.998 * (i % 97) / 96.0);
    }
  }
  grid.SetLogOdds({0, 0}, 0.0f);
  return grid;
}

void ExpectScaleRoundTrip(const core::OccupancyGrid& grid, const core::OccupancyGrid& read) {
  ExpectSameGeometry(grid, read);
  int in_between = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double p = grid.Probability({x, y});
      const float l = read.LogOdds({x, y});
      if (p > 0.65) {
        EXPECT_EQ(l, kOccupied) << x << ", " << y;
      } else if (p < 0.196) {
        EXPECT_EQ(l, kFree) << x << ", " << y;
      } else {
        ++in_between;
        EXPECT_NEAR(core::InverseLogit(l), p, 1.0 / 510.0 + 1e-6) << x << ", " << y;
      }
    }
  }
  EXPECT_GT(in_between, 50);
}

TEST_F(RosMapTest, ScalePgmRoundTripKeepsProbabilitiesWithinQuantisation) {
  const core::OccupancyGrid grid = GradientGrid();
  RosMapWriteOptions options;
  options.mode = RosMapMode::kScale;
  WriteRosMap(tmp_.path() / "s.yaml", grid, options);
  EXPECT_EQ(ReadRosMapMetadata(tmp_.path() / "s.yaml").mode, RosMapMode::kScale);
  ExpectScaleRoundTrip(grid, ReadRosMap(tmp_.path() / "s.yaml"));
}

TEST_F(RosMapTest, ScalePngRoundTripKeepsProbabilitiesWithinQuantisation) {
  const core::OccupancyGrid grid = GradientGrid();
  RosMapWriteOptions options;
  options.mode = RosMapMode::kScale;
  options.image_format = RosMapImageFormat::kPng;
  WriteRosMap(tmp_.path() / "s.yaml", grid, options);
  ExpectScaleRoundTrip(grid, ReadRosMap(tmp_.path() / "s.yaml"));
}

TEST_F(RosMapTest, NegatedImageReadsLikeTheOriginal) {
  for (RosMapMode mode : {RosMapMode::kTrinary, RosMapMode::kScale}) {
    const core::OccupancyGrid grid = mode == RosMapMode::kScale ? GradientGrid() : PatternGrid();
    RosMapWriteOptions options;
    options.mode = mode;
    WriteRosMap(tmp_.path() / "plain.yaml", grid, options);
    // Invert the pixels and say so with negate: 1.
    std::string pgm = tmp_.Read(tmp_.path() / "plain.pgm");
    const std::size_t n = static_cast<std::size_t>(grid.width() * grid.height());
    for (std::size_t i = pgm.size() - n; i < pgm.size(); ++i) {
      pgm[i] = static_cast<char>(255 - static_cast<unsigned char>(pgm[i]));
    }
    tmp_.Write("negated.pgm", pgm);
    std::string yaml = tmp_.Read(tmp_.path() / "plain.yaml");
    const auto at = yaml.find("negate: 0");
    ASSERT_NE(at, std::string::npos) << yaml;
    yaml.replace(at, 9, "negate: 1");
    yaml.replace(yaml.find("plain.pgm"), 9, "negated.pgm");
    tmp_.Write("negated.yaml", yaml);

    const core::OccupancyGrid plain = ReadRosMap(tmp_.path() / "plain.yaml");
    const core::OccupancyGrid negated = ReadRosMap(tmp_.path() / "negated.yaml");
    ExpectSameGeometry(plain, negated);
    EXPECT_EQ(plain.log_odds(), negated.log_odds()) << core::EnumName(mode);
  }
}

TEST_F(RosMapTest, ImageRowZeroIsTheTopOfTheMap) {
  tmp_.Write("col.pgm", std::string("P5\n1 2\n255\n\x00\xfe", 13));
  const auto grid = ReadRosMap(WriteYaml("col.pgm"));
  ASSERT_EQ(grid.width(), 1);
  ASSERT_EQ(grid.height(), 2);
  EXPECT_EQ(grid.LogOdds({0, 1}), kOccupied);  // image row 0
  EXPECT_EQ(grid.LogOdds({0, 0}), kFree);
  EXPECT_EQ(grid.origin(), core::Vec2(-2.0, 3.0));
  EXPECT_EQ(grid.resolution(), 0.1);
  EXPECT_EQ(grid.WorldToCell(core::Vec2(-1.95, 3.15)), (core::CellIndex{0, 1}));
}

TEST_F(RosMapTest, AsciiPgmWithCommentsAndTrinaryThresholds) {
  // p = (255 - v) / 255: 89 -> 0.651 (occupied), 90 -> 0.647 (unknown),
  // 205 -> 0.19608 (unknown), 206 -> 0.192 (free).
  tmp_.Write("a.pgm",
             "P2\n# made by hand\n4 2\n# max\n255\n89 90 205 206\n0 255 128 # last row\n 1\n");
  const auto grid = ReadRosMap(WriteYaml("a.pgm"));
  EXPECT_EQ(grid.LogOdds({0, 1}), kOccupied);
  EXPECT_EQ(grid.LogOdds({1, 1}), 0.0f);
  EXPECT_EQ(grid.LogOdds({2, 1}), 0.0f);
  EXPECT_EQ(grid.LogOdds({3, 1}), kFree);
  EXPECT_EQ(grid.LogOdds({0, 0}), kOccupied);
  EXPECT_EQ(grid.LogOdds({1, 0}), kFree);
  EXPECT_EQ(grid.LogOdds({2, 0}), 0.0f);
  EXPECT_EQ(grid.LogOdds({3, 0}), kOccupied);
}

TEST_F(RosMapTest, SmallMaxvalIsStretchedToFullRange) {
  tmp_.Write("b.pgm", "P2 2 1 1 0 1");
  const auto grid = ReadRosMap(WriteYaml("b.pgm"));
  EXPECT_EQ(grid.LogOdds({0, 0}), kOccupied);
  EXPECT_EQ(grid.LogOdds({1, 0}), kFree);
}

TEST_F(RosMapTest, ScaleModeKeepsInBetweenProbability) {
  tmp_.Write("s.pgm", std::string("P5\n3 1\n255\n\x00\x80\xfe", 14));
  const auto grid = ReadRosMap(WriteYaml("s.pgm", "mode: scale\n"));
  EXPECT_EQ(grid.LogOdds({0, 0}), kOccupied);
  EXPECT_FLOAT_EQ(grid.LogOdds({1, 0}), static_cast<float>(core::Logit(127.0 / 255.0)));
  EXPECT_EQ(grid.LogOdds({2, 0}), kFree);
}

TEST_F(RosMapTest, RawModeReadsPercentagesAndRejectsOtherValues) {
  tmp_.Write("r.pgm", std::string("P5\n5 1\n255\n\x00\x64\x32\xff\x41", 16));
  const auto grid = ReadRosMap(WriteYaml("r.pgm", "mode: raw\n"));
  EXPECT_EQ(grid.LogOdds({0, 0}), kFree);      // 0
  EXPECT_EQ(grid.LogOdds({1, 0}), kOccupied);  // 100
  EXPECT_EQ(grid.LogOdds({2, 0}), 0.0f);       // 50
  EXPECT_EQ(grid.LogOdds({3, 0}), 0.0f);       // 255 unknown
  EXPECT_FLOAT_EQ(grid.LogOdds({4, 0}), static_cast<float>(core::Logit(0.65)));

  tmp_.Write("bad.pgm", std::string("P5\n2 1\n255\n\x00\x96", 13));
  const std::string msg = ErrorOf<core::IoError>(WriteYaml("bad.pgm", "mode: raw\n", "bad.yaml"));
  EXPECT_NE(msg.find("pixel (1, 0) has value 150"), std::string::npos) << msg;
}

TEST_F(RosMapTest, PngAlphaFollowsNav2MapServer) {
  // io_alpha_map.png, 5 x 1 RGBA: opaque black, opaque 254, opaque 128, transparent black,
  // opaque colour (30, 60, 90) whose mean 60 is occupied.
  const std::string image = std::string(RETRACE_SOURCE_DIR) + "/tests/data/io_alpha_map.png";
  const auto scale = ReadRosMap(WriteYaml(image, "mode: scale\n", "scale.yaml"));
  ASSERT_EQ(scale.width(), 5);
  ASSERT_EQ(scale.height(), 1);
  EXPECT_EQ(scale.LogOdds({0, 0}), kOccupied);
  EXPECT_EQ(scale.LogOdds({1, 0}), kFree);
  EXPECT_FLOAT_EQ(scale.LogOdds({2, 0}), static_cast<float>(core::Logit(127.0 / 255.0)));
  EXPECT_EQ(scale.LogOdds({3, 0}), 0.0f);  // not opaque: unknown in scale mode
  EXPECT_EQ(scale.LogOdds({4, 0}), kOccupied);

  const auto trinary = ReadRosMap(WriteYaml(image, "", "trinary.yaml"));
  EXPECT_EQ(trinary.LogOdds({2, 0}), 0.0f);
  EXPECT_EQ(trinary.LogOdds({3, 0}), kOccupied);  // trinary ignores alpha
}

TEST_F(RosMapTest, NetpbmAndPngVariantsDecode) {
  const auto classes = [&](const std::string& image) {
    const auto grid = ReadRosMap(WriteYaml(image, "", "variant.yaml"));
    std::vector<Cls> out;
    for (int x = 0; x < grid.width(); ++x) out.push_back(ClassOf(grid.LogOdds({x, 0})));
    return out;
  };
  const std::vector<Cls> black_white_black = {Cls::kOccupiedCell, Cls::kFreeCell,
                                              Cls::kOccupiedCell};
  tmp_.Write("a.pbm", "P1\n3 1\n1 0\n1\n");
  EXPECT_EQ(classes("a.pbm"), black_white_black);
  tmp_.Write("b.pbm", "P1\n3 1\n101\n");  // PBM's digits need no spaces between them
  EXPECT_EQ(classes("b.pbm"), black_white_black);
  tmp_.Write("c.pbm", "P4\n3 1\n\xa0");  // 101 packed, most significant bit first
  EXPECT_EQ(classes("c.pbm"), black_white_black);
  const std::vector<Cls> black_white_grey = {Cls::kOccupiedCell, Cls::kFreeCell,
                                             Cls::kUnknownCell};
  tmp_.Write("d.ppm", "P3\n3 1\n255\n0 0 0  255 255 255  100 128 160\n");
  EXPECT_EQ(classes("d.ppm"), black_white_grey);
  tmp_.Write("e.ppm", std::string("P6\n3 1\n255\n\x00\x00\x00\xff\xff\xff\x64\x80\xa0", 20));
  EXPECT_EQ(classes("e.ppm"), black_white_grey);
  // A palette PNG (black, white) and a 1-bit grey PNG (0x0f: four black, four white pixels).
  const std::string data = std::string(RETRACE_SOURCE_DIR) + "/tests/data/";
  EXPECT_EQ(classes(data + "io_palette_map.png"),
            (std::vector<Cls>{Cls::kOccupiedCell, Cls::kFreeCell}));
  std::vector<Cls> half(8, Cls::kOccupiedCell);
  std::fill(half.begin() + 4, half.end(), Cls::kFreeCell);
  EXPECT_EQ(classes(data + "io_1bit_map.png"), half);
}

// Inputs on which OpenCV's or libpng's decoder printed its own line before retrace's (found by
// fuzz_map_image): now refused with one IoError, and nothing is printed.
TEST_F(RosMapTest, DecodersNeverPrint) {
  const fs::path findings = fs::path(RETRACE_SOURCE_DIR) / "tests/data/fuzz_findings";
  int seen = 0;
  for (const auto& entry : fs::directory_iterator(findings)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("map-image-print-", 0) != 0) continue;
    ++seen;
    ::testing::internal::CaptureStderr();
    const std::string msg = ErrorOf<core::IoError>(WriteYaml(entry.path().string()));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << name;
    EXPECT_NE(msg.find(name + ": "), std::string::npos) << msg;
  }
  EXPECT_EQ(seen, 4);
  // PNGs whose chunks check out but whose row filter or zlib stream is corrupt reach libpng.
  for (const auto& [name, expected] : std::vector<std::pair<std::string, std::string>>{
           {"io_png_bad_filter.png", "cannot decode PNG: bad adaptive filter value"},
           {"io_png_bad_deflate.png", "cannot decode PNG: IDAT: invalid block type"}}) {
    ::testing::internal::CaptureStderr();
    const std::string msg = ErrorOf<core::IoError>(
        WriteYaml((fs::path(RETRACE_SOURCE_DIR) / "tests/data" / name).string()));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << name;
    EXPECT_NE(msg.find(name + ": " + expected), std::string::npos) << msg;
  }
}

TEST_F(RosMapTest, SixteenBitImageIsRefused) {
  const std::string image = std::string(RETRACE_SOURCE_DIR) + "/tests/data/io_16bit_map.png";
  const std::string msg = ErrorOf<core::IoError>(WriteYaml(image));
  EXPECT_NE(msg.find("only 8-bit images"), std::string::npos) << msg;
}

TEST_F(RosMapTest, WrongSizePgmSaysSo) {
  tmp_.Write("short.pgm", "P5\n4 3\n255\n" + std::string(11, '\xfe'));
  std::string msg = ErrorOf<core::IoError>(WriteYaml("short.pgm"));
  EXPECT_NE(msg.find((tmp_.path() / "short.pgm").string() +
                     ": PGM has the wrong size: its pixel data "
                     "holds 11 bytes but the header says 4 x 3 = 12 pixels (the file is "
                     "truncated"),
            std::string::npos)
      << msg;

  tmp_.Write("long.pgm", "P5\n4 3\n255\n" + std::string(13, '\xfe'));
  msg = ErrorOf<core::IoError>(WriteYaml("long.pgm"));
  EXPECT_NE(msg.find("PGM has the wrong size: its pixel data holds 13 bytes but the header "
                     "says 4 x 3 = 12 pixels (there is extra data"),
            std::string::npos)
      << msg;

  tmp_.Write("ascii.pgm", "P2\n2 2\n255\n0 0 0\n");
  msg = ErrorOf<core::IoError>(WriteYaml("ascii.pgm"));
  EXPECT_NE(msg.find("wrong size: its pixel data holds 3 values but the header says 2 x 2 = 4"),
            std::string::npos)
      << msg;

  tmp_.Write("ascii_long.pgm", "P2\n2 2\n255\n0 0 0 0 0\n");
  msg = ErrorOf<core::IoError>(WriteYaml("ascii_long.pgm"));
  EXPECT_NE(msg.find("holds 5 values"), std::string::npos) << msg;
}

TEST_F(RosMapTest, MalformedPgmHeadersAreIoErrors) {
  const struct {
    std::string bytes;
    std::string expected;
  } cases[] = {
      {"P5\n4", "truncated PGM header: the file ends before the height"},
      {"P5\n4 3\n", "truncated PGM header: the file ends before the maxval"},
      {"P5 # only a comment", "truncated PGM header: the file ends before the width"},
      {"P5\n4 3\n255", "PGM has no pixel data after its header"},
      {"P5\n4 x 255\n", "the height 'x' is not a non-negative integer"},
      {"P5\n-4 3 255\n", "the width '-4' is not a non-negative integer"},
      {"P5\n4 3 65535\n", "PGM maxval 65535 is not supported"},
      {"P5\n0 3 255\n", "empty image"},
      {"P2\n2 1\n255\n0 x\n", "the pixel value 'x' is not a non-negative integer"},
      {"P2\n2 1\n100\n0 101\n", "PGM pixel value 101 exceeds the header's maxval 100"},
      {"P5\n99999999999 1 255\n", "PGM width is too large"},
  };
  for (const auto& c : cases) {
    tmp_.Write("h.pgm", c.bytes);
    const std::string msg = ErrorOf<core::IoError>(WriteYaml("h.pgm"));
    EXPECT_NE(msg.find((tmp_.path() / "h.pgm").string() + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.bytes << " -> " << msg;
  }
}

// Issue 16: declared sizes and structure are checked before a decoder allocates or prints.
TEST_F(RosMapTest, ImageHeadersAreCheckedBeforeDecoding) {
  // A binary PPM declaring 25554 x 25425 pixels over 64 bytes (OpenCV allocated 3.9 GB).
  tmp_.Write("huge.ppm", std::string("P6\n25554 25425\n65535\n") + std::string(64, '\0'));
  std::string msg = ErrorOf<core::IoError>(WriteYaml("huge.ppm"));
  EXPECT_NE(msg.find("huge.ppm: PPM header declares 25554 x 25425 pixels; retrace's limit"),
            std::string::npos)
      << msg;
  tmp_.Write("huge.pgm", std::string("P5\n20000 20000\n255\n") + std::string(64, '\0'));
  msg = ErrorOf<core::IoError>(WriteYaml("huge.pgm"));
  EXPECT_NE(msg.find("huge.pgm: PGM header declares 20000 x 20000 pixels"), std::string::npos)
      << msg;
  // A PNG map as retrace writes it, then cut short, then with one data byte flipped.
  RosMapWriteOptions options;
  options.image_format = RosMapImageFormat::kPng;
  WriteRosMap(tmp_.path() / "ok.yaml", PatternGrid(), options);
  const std::string whole = tmp_.Read(tmp_.path() / "ok.png");
  EXPECT_EQ(ReadRosMap(tmp_.path() / "ok.yaml").width(), PatternGrid().width());
  tmp_.Write("cut.png", whole.substr(0, whole.size() - 20));
  msg = ErrorOf<core::IoError>(WriteYaml("cut.png"));
  EXPECT_NE(msg.find("cut.png: truncated PNG"), std::string::npos) << msg;
  std::string flipped = whole;
  flipped[whole.size() / 2] = static_cast<char>(flipped[whole.size() / 2] ^ 0x55);
  tmp_.Write("flipped.png", flipped);
  msg = ErrorOf<core::IoError>(WriteYaml("flipped.png"));
  EXPECT_NE(msg.find("flipped.png: corrupt PNG: chunk"), std::string::npos) << msg;
}

TEST_F(RosMapTest, MissingOrUndecodableFilesAreIoErrors) {
  EXPECT_NE(ErrorOf<core::IoError>(tmp_.path() / "nope.yaml").find("cannot open"),
            std::string::npos);

  std::string msg = ErrorOf<core::IoError>(WriteYaml("missing.pgm"));
  EXPECT_NE(msg.find("map.yaml: image 'missing.pgm' not found"), std::string::npos) << msg;

  tmp_.Write("garbage.png", "hello, not an image");
  msg = ErrorOf<core::IoError>(WriteYaml("garbage.png"));
  EXPECT_NE(msg.find("garbage.png: not a map image retrace reads (PGM, PNG, or PBM/PPM)"),
            std::string::npos)
      << msg;

  tmp_.Write("empty.pgm", "");
  msg = ErrorOf<core::IoError>(WriteYaml("empty.pgm"));
  EXPECT_NE(msg.find("the image file is empty"), std::string::npos) << msg;
}

TEST_F(RosMapTest, OriginYawIsRefusedWithLine) {
  tmp_.Write("m.pgm", std::string("P5\n1 1\n255\n\x00", 12));
  const fs::path yaml =
      tmp_.Write("m.yaml", "image: m.pgm\nresolution: 0.05\norigin: [1.0, 2.0, 0.3]\n");
  const std::string msg = ErrorOf<core::ConfigError>(yaml);
  EXPECT_NE(msg.find(yaml.string() + ":3: origin: origin yaw 0.3 rad is not supported: "),
            std::string::npos)
      << msg;
  // The metadata alone is fine.
  EXPECT_EQ(ReadRosMapMetadata(yaml).origin[2], 0.3);
}

TEST_F(RosMapTest, BadMetadataIsConfigErrorWithLine) {
  tmp_.Write("m.pgm", std::string("P5\n1 1\n255\n\x00", 12));
  const struct {
    std::string yaml;
    std::string expected;
  } cases[] = {
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thres: 0.6\n",
       ":4: occupied_thres: unknown key; did you mean 'occupied_thresh'?"},
      {"image: m.pgm\nresolution: .nan\norigin: [0, 0, 0]\n", ":2: resolution: must be a finite"},
      {"image: m.pgm\nresolution: nan\norigin: [0, 0, 0]\n", ":2: resolution: expected a number"},
      {"image: m.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n", ":2: resolution: must be > 0"},
      {"image: m.pgm\nresolution: 0\norigin: [0, 0, 0]\n", ":2: resolution: must be > 0"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 1.5\n",
       ":4: occupied_thresh: must be in [0"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nfree_thresh: -0.1\n",
       ":4: free_thresh: must be in [0"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\noccupied_thresh: 0.5\nfree_thresh: "
       "0.5\n",
       ":5: free_thresh: must be below occupied_thresh (0.5), got 0.5"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: fancy\n",
       ":4: mode: unknown value 'fancy'; expected one of: trinary, scale, raw"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 2\n",
       ":4: negate: must be 0 or 1"},
      {"image: m.pgm\nresolution: 0.05\norigin: [0, 0]\n", ":3: origin: expected a list of 3"},
      {"image: m.pgm\norigin: [0, 0, 0]\n", "resolution: required key is missing"},
      {"resolution: 0.05\norigin: [0, 0, 0]\n", "image: required key is missing"},
      {"image: m.pgm\nresolution: 0.05\n", "origin: required key is missing"},
      {"image: ''\nresolution: 0.05\norigin: [0, 0, 0]\n", ":1: image: must name an image file"},
      {"- just a list\n", "expected a mapping"},
  };
  for (const auto& c : cases) {
    const fs::path yaml = tmp_.Write("bad.yaml", c.yaml);
    const std::string msg = ErrorOf<core::ConfigError>(yaml);
    EXPECT_NE(msg.find(yaml.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.yaml << "-> " << msg;
  }
}

TEST_F(RosMapTest, WriteRejectsRawModeBadThresholdsAndEmptyGrid) {
  const core::OccupancyGrid grid = PatternGrid();
  RosMapWriteOptions raw;
  raw.mode = RosMapMode::kRaw;
  EXPECT_THROW(WriteRosMap(tmp_.path() / "a.yaml", grid, raw), core::ConfigError);
  RosMapWriteOptions inverted;
  inverted.free_thresh = 0.7;
  EXPECT_THROW(WriteRosMap(tmp_.path() / "a.yaml", grid, inverted), core::ConfigError);
  EXPECT_THROW(WriteRosMap(tmp_.path() / "a.yaml", core::OccupancyGrid()), core::IoError);
  EXPECT_TRUE(fs::is_empty(tmp_.path()));
}

TEST_F(RosMapTest, WriteIntoInvalidLocationLeavesNothing) {
  tmp_.Write("blocker", "x");
  EXPECT_THROW(WriteRosMap(tmp_.path() / "blocker" / "ogm_0.yaml", PatternGrid()), core::IoError);
  std::vector<fs::path> entries(fs::directory_iterator(tmp_.path()), fs::directory_iterator{});
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].filename(), "blocker");
}

TEST_F(RosMapTest, RewritingAMapReplacesBothFiles) {
  WriteRosMap(tmp_.path() / "ogm.yaml", GradientGrid());
  const core::OccupancyGrid small = PatternGrid();
  WriteRosMap(tmp_.path() / "ogm.yaml", small);
  ExpectSameClasses(small, ReadRosMap(tmp_.path() / "ogm.yaml"));
  std::vector<fs::path> entries(fs::directory_iterator(tmp_.path()), fs::directory_iterator{});
  EXPECT_EQ(entries.size(), 2u);
}

}  // namespace
}  // namespace retrace::io
