#include "logs/cdr.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/io_error_of.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace cdr_test {

using Buffer = std::vector<std::uint8_t>;

using testing::IoErrorOf;

TEST(CdrReader, ReadsLittleEndianPrimitivesAlignedAfterTheHeader) {
  const Buffer b = {
      0x00, 0x01, 0x00, 0x00,                          // header: CDR little endian
      0x01,                                            // bool true            @0
      0x00,                                            // pad to 2
      0x34, 0x12,                                      // uint16 0x1234        @2
      0x78, 0x56, 0x34, 0x12,                          // uint32 0x12345678    @4
      0xFF,                                            // int8 -1              @8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,        // pad to 16
      0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01,  // uint64               @16
      0x00, 0x00, 0xC0, 0x3F,                          // float 1.5            @24
      0x00, 0x00, 0x00, 0x00,                          // pad to 32
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0xC0,  // double -2.5          @32
      0x03, 0x00, 0x00, 0x00, 'h',  'i',  0x00,        // string "hi"          @40
  };
  CdrReader r(b);
  EXPECT_EQ(r.byte_order(), std::endian::little);
  EXPECT_TRUE(r.ReadBool());
  EXPECT_EQ(r.Read<std::uint16_t>(), 0x1234);
  EXPECT_EQ(r.Read<std::uint32_t>(), 0x12345678u);
  EXPECT_EQ(r.Read<std::int8_t>(), -1);
  EXPECT_EQ(r.Read<std::uint64_t>(), 0x0102030405060708ull);
  EXPECT_EQ(r.Read<float>(), 1.5f);
  EXPECT_EQ(r.Read<double>(), -2.5);
  EXPECT_EQ(r.ReadString(), "hi");
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(CdrReader, ReadsBigEndian) {
  const Buffer b = {
      0x00, 0x00, 0x00, 0x00,                          // header: CDR big endian
      0xFF, 0xFE,                                      // int16 -2
      0x00, 0x00,                                      // pad to 4
      0x00, 0x00, 0x00, 0x02,                          // sequence of 2 floats
      0x3F, 0xC0, 0x00, 0x00,                          // 1.5
      0xC0, 0x20, 0x00, 0x00,                          // -2.5
      0xC0, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // double -2.5 @16
  };
  CdrReader r(b);
  EXPECT_EQ(r.byte_order(), std::endian::big);
  EXPECT_EQ(r.Read<std::int16_t>(), -2);
  EXPECT_EQ(r.ReadFloat32Sequence(), (std::vector<float>{1.5f, -2.5f}));
  EXPECT_EQ(r.Read<double>(), -2.5);
}

TEST(CdrWriter, LaysOutFieldsAsFastCdrDoes) {
  CdrWriter w;
  w.Write<std::uint8_t>(7);
  w.Write<std::uint32_t>(2);
  w.WriteString("ab");
  w.Write<double>(1.0);
  const Buffer expected = {0x00, 0x01, 0x00, 0x00,                           // header
                           0x07, 0x00, 0x00, 0x00,                           // uint8, pad
                           0x02, 0x00, 0x00, 0x00,                           // uint32
                           0x03, 0x00, 0x00, 0x00, 'a',  'b',  0x00,         // string
                           0x00,                                             // pad to 16
                           0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0x3F};  // 1.0
  EXPECT_EQ(w.data(), expected);
}

TEST(CdrWriter, EmptySequenceAddsNoPadding) {
  // uint32 count 0 at 0, then int32 at 4: an empty float64 sequence must not align to 8.
  CdrWriter w;
  w.WriteFloat64Sequence({});
  w.Write<std::int32_t>(-1);
  EXPECT_EQ(w.data().size(), 4u + 8u);
  CdrReader r(w.data());
  EXPECT_TRUE(r.ReadFloat64Sequence().empty());
  EXPECT_EQ(r.Read<std::int32_t>(), -1);
}

TEST(CdrWriter, RoundTripsEveryType) {
  CdrWriter w;
  w.WriteBool(false);
  w.Write<std::int8_t>(-128);
  w.Write<std::uint8_t>(255);
  w.Write<std::int16_t>(-32768);
  w.Write<std::uint16_t>(65535);
  w.Write<std::int32_t>(std::numeric_limits<std::int32_t>::min());
  w.Write<std::uint32_t>(std::numeric_limits<std::uint32_t>::max());
  w.Write<std::int64_t>(std::numeric_limits<std::int64_t>::min());
  w.Write<std::uint64_t>(std::numeric_limits<std::uint64_t>::max());
  w.Write<float>(std::numeric_limits<float>::infinity());
  w.Write<double>(std::numeric_limits<double>::quiet_NaN());
  w.WriteString("");
  w.WriteString("frame");
  const std::vector<float> floats = {1.0f, -0.0f, std::numeric_limits<float>::quiet_NaN()};
  const std::vector<double> doubles = {3.25, -1e300};
  w.WriteFloat32Sequence(floats);
  w.WriteFloat64Sequence(doubles);
  w.WriteFloat64Array(doubles);

  CdrReader r(w.data());
  EXPECT_FALSE(r.ReadBool());
  EXPECT_EQ(r.Read<std::int8_t>(), -128);
  EXPECT_EQ(r.Read<std::uint8_t>(), 255);
  EXPECT_EQ(r.Read<std::int16_t>(), -32768);
  EXPECT_EQ(r.Read<std::uint16_t>(), 65535);
  EXPECT_EQ(r.Read<std::int32_t>(), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(r.Read<std::uint32_t>(), std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(r.Read<std::int64_t>(), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(r.Read<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(r.Read<float>(), std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(r.Read<double>()));
  EXPECT_EQ(r.ReadString(), "");
  EXPECT_EQ(r.ReadString(), "frame");
  const std::vector<float> f = r.ReadFloat32Sequence();
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0], 1.0f);
  EXPECT_TRUE(std::signbit(f[1]));
  EXPECT_TRUE(std::isnan(f[2]));
  EXPECT_EQ(r.ReadFloat64Sequence(), doubles);
  std::vector<double> fixed(2);
  r.ReadFloat64Array(fixed);
  EXPECT_EQ(fixed, doubles);
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(CdrReader, RefusesAnythingButPlainCdr) {
  EXPECT_NE(IoErrorOf([] {
              CdrReader r(Buffer{0x00, 0x03, 0x00, 0x00});
            }).find("unsupported CDR encapsulation 0x00 0x03 (parameter-list CDR)"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              CdrReader r(Buffer{0x00, 0x07, 0x00, 0x00});
            }).find("(XCDR2)"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              CdrReader r(Buffer{0x01, 0x01, 0x00, 0x00});
            }).find("only plain CDR, little or big endian"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] {
              CdrReader r(Buffer{0x00, 0x01});
            }).find("encapsulation header"),
            std::string::npos);
  EXPECT_NE(IoErrorOf([] { CdrReader r(Buffer{}); }).find("truncated"), std::string::npos);
}

TEST(CdrReader, RefusesAStringLengthBeyondTheBuffer) {
  const Buffer b = {0x00, 0x01, 0x00, 0x00, 0x10, 0x00, 0x00, 0x00, 'a', 'b', 0x00};
  CdrReader r(b);
  EXPECT_EQ(IoErrorOf([&] { r.ReadString(); }),
            "string length 16 at byte 0 beyond the end (3 bytes left)");
}

TEST(CdrReader, RefusesAHugeSequenceCountBeforeAllocating) {
  const Buffer b = {0x00, 0x01, 0x00, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x00};
  {
    CdrReader r(b);
    EXPECT_EQ(IoErrorOf([&] { r.ReadFloat32Sequence(); }),
              "sequence of 4294967295 elements at byte 0 needs at least 17179869180 bytes, 4 left");
  }
  {
    CdrReader r(b);
    EXPECT_NE(IoErrorOf([&] { r.ReadFloat64Sequence(); }).find("4294967295 elements"),
              std::string::npos);
  }
  {
    CdrReader r(b);
    EXPECT_NE(IoErrorOf([&] { r.ReadSequenceLength(0); }).find("4294967295 elements"),
              std::string::npos);
  }
}

TEST(CdrReader, RefusesTruncatedPrimitivesAndBadBools) {
  const Buffer b = {0x00, 0x01, 0x00, 0x00, 0x02, 0x00, 0x00};
  EXPECT_EQ(IoErrorOf([&] { CdrReader(b).ReadBool(); }), "bool of value 2 at byte 0");
  EXPECT_EQ(IoErrorOf([&] { CdrReader(b).Read<std::uint32_t>(); }),
            "truncated: needs 4 bytes at byte 0, 3 left");
  EXPECT_EQ(IoErrorOf([&] { CdrReader(b).Read<double>(); }),
            "truncated: needs 8 bytes at byte 0, 3 left");
  CdrReader r(b);
  r.Read<std::uint8_t>();
  EXPECT_EQ(IoErrorOf([&] { r.Read<std::uint32_t>(); }), "truncated: needs 3 bytes at byte 1, 2 left");
}

TEST(CdrReader, EveryPrefixOfAMessageIsRefused) {
  CdrWriter w;
  w.WriteString("laser");
  w.Write<double>(1.0);
  w.WriteFloat32Sequence(std::vector<float>{1, 2, 3});
  const Buffer& full = w.data();
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Buffer prefix(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_NE(IoErrorOf([&] {
                CdrReader r(prefix);
                r.ReadString();
                r.Read<double>();
                r.ReadFloat32Sequence();
              }),
              "")
        << "prefix of " << n << " bytes";
  }
}

}  // namespace cdr_test
}  // namespace retrace::logs
