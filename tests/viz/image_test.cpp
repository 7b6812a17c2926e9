#include "viz/image.hpp"

#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/png.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::viz {
namespace {

using ImageTest = retrace::testing::TempDirTest;

Image Gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 3;
      img.rgb[i] = static_cast<std::uint8_t>(x);
      img.rgb[i + 1] = static_cast<std::uint8_t>(y);
      img.rgb[i + 2] = 7;
    }
  }
  return img;
}

TEST_F(ImageTest, PngRoundTripKeepsEveryPixel) {
  const Image img = Gradient(50, 30);
  const auto png = tmp_.path() / "sub" / "g.png";
  WritePng(img, png);
  EXPECT_EQ(ReadPng(png), img);
  EXPECT_EQ(img.At(10, 20), (Rgba{10, 20, 7}));
}

// The PNG bytes of a fixed image are pinned: the same pixels give the same file in any process
// (figures are compared byte for byte across runs). If a libpng or zlib update changes the
// encoding, check that the round trip above still holds and paste the new values printed.
TEST_F(ImageTest, EncodingOfAFixedImageIsPinned) {
  constexpr std::size_t kPinnedSize = 107;
  constexpr std::uint64_t kPinnedHash = 0x27d00d455bd437e7ULL;
  const std::vector<std::uint8_t> png = EncodePng(Gradient(40, 40));
  const std::uint64_t hash = core::HashBytes(png.data(), png.size());
  EXPECT_EQ(png.size(), kPinnedSize);
  EXPECT_EQ(hash, kPinnedHash) << "new hash: 0x" << std::hex << hash;
}

TEST_F(ImageTest, AGreyPngIsReadAsGreyInEveryChannel) {
  const std::vector<std::uint8_t> grey{0, 100, 200, 255, 50, 60};
  tmp_.Write("grey.png", io::EncodePng(grey, 3, 2, 1));
  const Image img = ReadPng(tmp_.path() / "grey.png");
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 2);
  EXPECT_EQ(img.At(1, 0), (Rgba{100, 100, 100}));
  EXPECT_EQ(img.At(2, 1), (Rgba{60, 60, 60}));
  tmp_.Write("not.png", "P5\n1 1\n255\n\x01");
  EXPECT_THROW(ReadPng(tmp_.path() / "not.png"), core::IoError);
  EXPECT_THROW(io::EncodePng(grey, 4, 2, 1), core::IoError);  // 6 bytes are not 4 x 2 pixels
}

TEST_F(ImageTest, UnwritablePathGivesIoError) {
  tmp_.Write("file", "x");
  EXPECT_THROW(WritePng(Gradient(4, 4), tmp_.path() / "file" / "a.png"), core::IoError);
  EXPECT_THROW(WritePng(Image(), tmp_.path() / "empty.png"), core::IoError);
  EXPECT_THROW(ReadPng(tmp_.path() / "missing.png"), core::IoError);
}

TEST(ComposeGrid, PlacesTilesInRowsWithGaps) {
  const Image a(10, 5, {255, 0, 0});
  const Image b(6, 8, {0, 255, 0});
  const Image c(4, 4, {0, 0, 255});
  const Image g = ComposeGrid({a, b, c}, 2, 2, {0, 0, 0});
  EXPECT_EQ(g.width, 10 + 2 + 6);
  EXPECT_EQ(g.height, 8 + 2 + 4);
  EXPECT_EQ(g.At(0, 0), (Rgba{255, 0, 0}));
  EXPECT_EQ(g.At(12, 7), (Rgba{0, 255, 0}));
  EXPECT_EQ(g.At(11, 0), (Rgba{0, 0, 0}));  // the gap
  EXPECT_EQ(g.At(3, 13), (Rgba{0, 0, 255}));
  EXPECT_TRUE(ComposeGrid({}, 3).empty());
}

}  // namespace
}  // namespace retrace::viz
