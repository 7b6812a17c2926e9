#include "sim/lidar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "io/config_yaml.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/special_values.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

using retrace::testing::kInf;
const std::vector<std::uint64_t> kSeeds = {11, 12, 13};

LidarConfig NoiseFreeLidar() {
  LidarConfig config;
  config.noise.sigma0 = 0.0;
  config.noise.sigma1 = 0.0;
  config.noise.dropout_probability = 0.0;
  config.noise.short_probability = 0.0;
  return config;
}

StaticGeometry BoxRoom(double x0, double y0, double x1, double y1) {
  StaticGeometry g;
  g.AddPolygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  return g;
}

// A sensor at the centre of a circular room sees the same true range on every beam.
StaticGeometry CircleRoom(double radius) {
  StaticGeometry g;
  g.AddCircle({{0.0, 0.0}, radius});
  return g;
}

// Distance from p (inside) along heading a to the walls of the box [x0, x1] x [y0, y1].
double BoxRange(const Vec2& p, double a, double x0, double y0, double x1, double y1) {
  const double c = std::cos(a), s = std::sin(a);
  const double tx = c > 0.0 ? (x1 - p.x()) / c : c < 0.0 ? (x0 - p.x()) / c : kInf;
  const double ty = s > 0.0 ? (y1 - p.y()) / s : s < 0.0 ? (y0 - p.y()) / s : kInf;
  return std::min(tx, ty);
}

TEST(LidarConfig, DefaultsAreValidAndDescribeAUtm30lx) {
  const LidarConfig config;
  EXPECT_NO_THROW(config.Validate());
  EXPECT_EQ(config.fov_deg, 270.0);
  EXPECT_EQ(config.beams, 1081);
  EXPECT_EQ(config.range_min, 0.05);
  EXPECT_EQ(config.range_max, 30.0);
  EXPECT_EQ(config.rate_hz, 20.0);
  EXPECT_EQ(config.mount, core::Pose2::Identity());
}

TEST(LidarConfig, ValidateNamesTheOffendingKey) {
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.fov_deg = 0.0; }), "fov_deg");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.fov_deg = 361.0; }), "fov_deg");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.beams = 1; }), "beams");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.range_min = -0.1; }), "range_min");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.range_max = 0.05; }), "range_max");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.range_max = kInf; }), "range_max");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.rate_hz = 0.0; }), "rate_hz");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.mount.x = std::nan(""); }), "mount");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.noise.sigma0 = -0.01; }),
            "noise.sigma0");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.noise.sigma1 = std::nan(""); }),
            "noise.sigma1");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) { c.noise.dropout_probability = 1.5; }),
            "noise.dropout_probability");
  EXPECT_EQ(ValidationErrorKey<LidarConfig>([](auto& c) {
              c.noise.dropout_probability = 0.6;
              c.noise.short_probability = 0.6;
            }),
            "noise.short_probability");
  LidarConfig bad;
  bad.beams = 0;
  EXPECT_THROW(Lidar(bad, StaticGeometry{}).config(), core::ConfigError);
}

TEST(LidarConfig, ReadsFromYamlAndRejectsUnknownKeys) {
  const auto config = io::ReadConfig<LidarConfig>(
      YAML::Load("beams: 541\nmount: [0.2, 0, 0]\nnoise: {sigma0: 0.02, short_probability: 0}\n"),
      "lidar.yaml");
  EXPECT_EQ(config.beams, 541);
  EXPECT_EQ(config.mount, core::Pose2(0.2, 0.0, 0.0));
  EXPECT_EQ(config.noise.sigma0, 0.02);
  EXPECT_EQ(config.noise.sigma1, LidarNoiseConfig{}.sigma1);
  EXPECT_THROW(io::ReadConfig<LidarConfig>(YAML::Load("noise: {sigma: 1}\n"), "lidar.yaml"),
               core::ConfigError);
  EXPECT_THROW(io::ReadConfig<LidarConfig>(YAML::Load("range_max: 0.01\n"), "lidar.yaml"),
               core::ConfigError);
}

TEST(Lidar, ScanMetadataFollowsTheConfig) {
  const Lidar lidar(NoiseFreeLidar(), BoxRoom(-5, -5, 5, 5));
  core::Rng rng(1);
  const LidarReading r = lidar.Scan(core::Pose2(), {}, 12.5, rng);
  ASSERT_EQ(r.scan.size(), 1081u);
  ASSERT_EQ(r.truth.size(), 1081u);
  EXPECT_EQ(r.scan.stamp, 12.5);
  EXPECT_EQ(r.scan.range_min, 0.05);
  EXPECT_EQ(r.scan.range_max, 30.0);
  EXPECT_DOUBLE_EQ(r.scan.angle_min, core::DegToRad(-135.0));
  EXPECT_DOUBLE_EQ(r.scan.angle_increment, core::DegToRad(0.25));
  EXPECT_NEAR(r.scan.Angle(1080), core::DegToRad(135.0), 1e-12);
  EXPECT_NEAR(r.scan.Angle(540), 0.0, 1e-12);
}

TEST(Lidar, RangesMatchABoxRoomAtManyAngles) {
  const double x0 = -4.0, y0 = -3.0, x1 = 6.0, y1 = 5.0;
  const Lidar lidar(NoiseFreeLidar(), BoxRoom(x0, y0, x1, y1));
  core::Rng rng(1);
  for (const core::Pose2& X_WR :
       {core::Pose2(0, 0, 0), core::Pose2(1.0, 0.5, 0.3), core::Pose2(-3.5, 4.2, -2.9)}) {
    const LidarReading r = lidar.Scan(X_WR, {}, 0.0, rng);
    for (std::size_t i = 0; i < r.scan.size(); ++i) {
      const double expected =
          BoxRange(X_WR.translation(), X_WR.theta + r.scan.Angle(i), x0, y0, x1, y1);
      ASSERT_NEAR(r.truth[i].range, expected, 1e-9) << i;
      ASSERT_NEAR(r.scan.ranges[i], expected, 1e-5) << i;  // float readings
      ASSERT_EQ(r.truth[i].source, BeamSource::kStatic);
      ASSERT_EQ(r.truth[i].pedestrian_id, -1);
    }
  }
}

TEST(Lidar, HonoursTheMountPose) {
  const double x0 = -4.0, y0 = -3.0, x1 = 6.0, y1 = 5.0;
  LidarConfig config = NoiseFreeLidar();
  config.mount = core::Pose2(0.3, -0.1, core::kPi / 2.0);
  const Lidar lidar(config, BoxRoom(x0, y0, x1, y1));
  core::Rng rng(1);
  const core::Pose2 X_WR(1.0, 0.5, 0.3);
  const LidarReading r = lidar.Scan(X_WR, {}, 0.0, rng);
  // The sensor position and heading in W, written out by hand.
  const Vec2 p(1.0 + std::cos(0.3) * 0.3 - std::sin(0.3) * -0.1,
               0.5 + std::sin(0.3) * 0.3 + std::cos(0.3) * -0.1);
  const double heading = 0.3 + core::kPi / 2.0;
  for (std::size_t i = 0; i < r.scan.size(); ++i) {
    ASSERT_NEAR(r.truth[i].range, BoxRange(p, heading + r.scan.Angle(i), x0, y0, x1, y1), 1e-9)
        << i;
  }
  // Beam 180 points at -90 deg in L, i.e. along the robot's x axis.
  EXPECT_NEAR(r.truth[180].range, BoxRange(p, 0.3, x0, y0, x1, y1), 1e-9);
}

TEST(Lidar, ReadsInfinityWithoutAReturn) {
  core::Rng rng(1);
  {  // open space
    const Lidar lidar(NoiseFreeLidar(), StaticGeometry{});
    const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
    for (std::size_t i = 0; i < r.scan.size(); ++i) {
      ASSERT_TRUE(r.scan.NoReturn(i));
      ASSERT_EQ(r.truth[i].source, BeamSource::kNothing);
      ASSERT_EQ(r.truth[i].range, kInf);
    }
  }
  {  // a room larger than range_max: only the beams towards the near wall return
    const Lidar lidar(NoiseFreeLidar(), BoxRoom(-40.0, -40.0, 20.0, 40.0));
    const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
    int returns = 0;
    for (std::size_t i = 0; i < r.scan.size(); ++i) {
      const double expected = BoxRange({0, 0}, r.scan.Angle(i), -40.0, -40.0, 20.0, 40.0);
      if (expected > 30.0) {
        ASSERT_TRUE(r.scan.NoReturn(i)) << i;
        ASSERT_EQ(r.truth[i].source, BeamSource::kNothing);
      } else {
        ASSERT_NEAR(r.scan.ranges[i], expected, 1e-5);
        ++returns;
      }
    }
    EXPECT_EQ(returns, 2 * 192 + 1);  // |angle| <= acos(20/30) = 48.19 deg, 0.25 deg apart
  }
}

TEST(Lidar, ReadsNegativeInfinityWhenTooClose) {
  const Lidar lidar(NoiseFreeLidar(), BoxRoom(-0.03, -5.0, 5.0, 5.0));
  core::Rng rng(1);
  // Facing -x: the wall is 3 cm behind the sensor's range_min.
  const LidarReading r = lidar.Scan(core::Pose2(0, 0, core::kPi), {}, 0.0, rng);
  EXPECT_EQ(r.scan.ranges[540], -std::numeric_limits<float>::infinity());
  EXPECT_FALSE(r.scan.Valid(540));
  EXPECT_FALSE(r.scan.NoReturn(540));
  EXPECT_EQ(r.truth[540].source, BeamSource::kStatic);
  EXPECT_NEAR(r.truth[540].range, 0.03, 1e-12);
}

TEST(Lidar, LabelsPedestrianHitsAndLetsThemOccludeWalls) {
  const Lidar lidar(NoiseFreeLidar(), BoxRoom(-10, -10, 10, 10));
  core::Rng rng(1);
  const std::vector<DynamicCircle> people = {
      {{5.0, 0.0}, 0.3, 7},    // in front
      {{15.0, 3.0}, 0.3, 8},   // behind the wall
      {{-5.0, 0.0}, 0.3, 9},   // behind the sensor, outside the 270 deg fan
      {{3.0, 3.0}, 0.25, 4}};  // at 45 deg
  const LidarReading r = lidar.Scan(core::Pose2(), people, 0.0, rng);
  EXPECT_EQ(r.truth[540].source, BeamSource::kPedestrian);
  EXPECT_EQ(r.truth[540].pedestrian_id, 7);
  EXPECT_NEAR(r.truth[540].range, 4.7, 1e-12);
  EXPECT_NEAR(r.scan.ranges[540], 4.7, 1e-6);
  EXPECT_EQ(r.truth[720].pedestrian_id, 4);  // beam 720 at +45 deg
  EXPECT_NEAR(r.truth[720].range, std::sqrt(18.0) - 0.25, 1e-12);
  int seen7 = 0;
  for (std::size_t i = 0; i < r.scan.size(); ++i) {
    const double a = r.scan.Angle(i);
    ASSERT_NE(r.truth[i].pedestrian_id, 8);
    ASSERT_NE(r.truth[i].pedestrian_id, 9);
    if (r.truth[i].pedestrian_id == 7) {
      ++seen7;
      ASSERT_LE(std::abs(a), std::asin(0.3 / 5.0));
    } else if (r.truth[i].pedestrian_id == -1) {
      ASSERT_EQ(r.truth[i].source, BeamSource::kStatic);
      ASSERT_NEAR(r.truth[i].range, BoxRange({0, 0}, a, -10, -10, 10, 10), 1e-9);
    }
  }
  EXPECT_EQ(seen7, 2 * 13 + 1);  // asin(0.06) = 3.44 deg

  // With a full circle of beams, the one behind is seen by the first and last beams.
  LidarConfig full = NoiseFreeLidar();
  full.fov_deg = 360.0;
  full.beams = 1441;
  const Lidar round(full, BoxRoom(-10, -10, 10, 10));
  const LidarReading rr = round.Scan(core::Pose2(), people, 0.0, rng);
  EXPECT_EQ(rr.truth.front().pedestrian_id, 9);
  EXPECT_EQ(rr.truth.back().pedestrian_id, 9);
  EXPECT_NEAR(rr.truth.front().range, 4.7, 1e-12);
}

TEST(Lidar, PedestrianCullingAgreesWithTestingEveryBeam) {
  core::Rng rng(5);
  for (const double fov : {270.0, 360.0, 90.0}) {
    LidarConfig config = NoiseFreeLidar();
    config.fov_deg = fov;
    config.beams = 721;
    const Lidar lidar(config, BoxRoom(-18, -18, 18, 18));
    for (int trial = 0; trial < 20; ++trial) {
      const core::Pose2 X_WR(rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(-3.2, 3.2));
      std::vector<DynamicCircle> people;
      for (int k = 0; k < 30; ++k) {
        const double d = k < 3 ? rng.Uniform(0.35, 0.6) : rng.Uniform(0.4, 15.0);
        const double a = rng.Uniform(-core::kPi, core::kPi);
        people.push_back({X_WR.translation() + d * Vec2(std::cos(a), std::sin(a)),
                          rng.Uniform(0.1, 0.34), 100 + k});
      }
      const LidarReading r = lidar.Scan(X_WR, people, 0.0, rng);
      for (std::size_t i = 0; i < r.scan.size(); ++i) {
        const double a = X_WR.theta + r.scan.Angle(i);
        const Vec2 dir(std::cos(a), std::sin(a));
        double best = BoxRange(X_WR.translation(), a, -18, -18, 18, 18);
        int id = -1;
        for (const DynamicCircle& p : people) {
          const double t = RayCircleHit(X_WR.translation(), dir, {p.center, p.radius});
          if (t < best) {
            best = t;
            id = p.id;
          }
        }
        ASSERT_EQ(r.truth[i].pedestrian_id, id) << "fov " << fov << " beam " << i;
        ASSERT_NEAR(r.truth[i].range, best, 1e-9);
      }
    }
  }
}

TEST(Lidar, SeesTheBoundaryOfAPedestrianAroundTheSensor) {
  const Lidar lidar(NoiseFreeLidar(), BoxRoom(-10, -10, 10, 10));
  core::Rng rng(1);
  const std::vector<DynamicCircle> people = {{{0.1, 0.0}, 0.3, 3}};
  const LidarReading r = lidar.Scan(core::Pose2(), people, 0.0, rng);
  for (std::size_t i = 0; i < r.scan.size(); ++i) {
    ASSERT_EQ(r.truth[i].pedestrian_id, 3);
    ASSERT_GE(r.truth[i].range, 0.2 - 1e-12);
    ASSERT_LE(r.truth[i].range, 0.4 + 1e-12);
  }
}

TEST(Lidar, RangeNoiseHasTheConfiguredMeanAndDeviation) {
  LidarConfig config = NoiseFreeLidar();
  config.noise.sigma0 = 0.01;
  config.noise.sigma1 = 0.001;
  for (const double radius : {2.0, 20.0}) {
    const Lidar lidar(config, CircleRoom(radius));
    const double sigma = 0.01 + 0.001 * radius;
    for (const std::uint64_t seed : kSeeds) {
      core::Rng rng(seed);
      double sum = 0.0, sum2 = 0.0;
      int n = 0;
      for (int k = 0; k < 100; ++k) {
        const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
        for (std::size_t i = 0; i < r.scan.size(); ++i) {
          ASSERT_NEAR(r.truth[i].range, radius, 1e-12);
          const double e = static_cast<double>(r.scan.ranges[i]) - radius;
          sum += e;
          sum2 += e * e;
          ++n;
        }
      }
      const double mean = sum / n;
      const double std = std::sqrt(sum2 / n - mean * mean);
      EXPECT_LT(std::abs(mean), 4.0 * sigma / std::sqrt(n)) << "radius " << radius;
      EXPECT_NEAR(std / sigma, 1.0, 0.02) << "radius " << radius << " seed " << seed;
    }
  }
}

TEST(Lidar, DropoutAndShortReturnRatesMatchTheirProbabilities) {
  LidarConfig config = NoiseFreeLidar();
  config.noise.dropout_probability = 0.1;
  config.noise.short_probability = 0.05;
  const double radius = 10.0;
  const Lidar lidar(config, CircleRoom(radius));
  for (const std::uint64_t seed : kSeeds) {
    core::Rng rng(seed);
    int n = 0, dropouts = 0, shorts = 0;
    double short_sum = 0.0;
    for (int k = 0; k < 100; ++k) {
      const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
      for (std::size_t i = 0; i < r.scan.size(); ++i) {
        ++n;
        ASSERT_NEAR(r.truth[i].range, radius, 1e-12);
        switch (r.truth[i].source) {
          case BeamSource::kDropout:
            ++dropouts;
            ASSERT_TRUE(r.scan.NoReturn(i));
            break;
          case BeamSource::kSpurious:
            ++shorts;
            ASSERT_GE(r.scan.ranges[i], 0.05f);
            ASSERT_LE(r.scan.ranges[i], static_cast<float>(radius));
            short_sum += r.scan.ranges[i];
            break;
          case BeamSource::kStatic:
            ASSERT_EQ(r.scan.ranges[i], static_cast<float>(radius));
            break;
          default:
            FAIL() << "unexpected source";
        }
      }
    }
    // Binomial standard deviations are 0.0009 and 0.0007 for n = 108100.
    EXPECT_NEAR(static_cast<double>(dropouts) / n, 0.1, 0.004) << seed;
    EXPECT_NEAR(static_cast<double>(shorts) / n, 0.05, 0.003) << seed;
    // Uniform in [range_min, true range): mean 5.025, sd 2.87 / sqrt(5400) = 0.04.
    EXPECT_NEAR(short_sum / shorts, (0.05 + radius) / 2.0, 0.16) << seed;
  }
}

TEST(Lidar, SpuriousReturnsAppearInOpenSpaceToo) {
  LidarConfig config = NoiseFreeLidar();
  config.noise.short_probability = 0.2;
  const Lidar lidar(config, StaticGeometry{});
  core::Rng rng(3);
  int shorts = 0, n = 0;
  for (int k = 0; k < 20; ++k) {
    const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
    for (std::size_t i = 0; i < r.scan.size(); ++i, ++n) {
      if (r.truth[i].source == BeamSource::kSpurious) {
        ++shorts;
        ASSERT_TRUE(r.scan.Valid(i));
      } else {
        ASSERT_TRUE(r.scan.NoReturn(i));
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(shorts) / n, 0.2, 0.015);
}

TEST(Lidar, NoisyReadingsNeverLeaveTheValidIntervalWhileFinite) {
  LidarConfig config;  // default noise
  config.noise.sigma0 = 0.02;
  for (const double radius : {0.06, 29.98}) {
    const Lidar lidar(config, CircleRoom(radius));
    core::Rng rng(21);
    int pos_inf = 0, neg_inf = 0;
    for (int k = 0; k < 20; ++k) {
      const LidarReading r = lidar.Scan(core::Pose2(), {}, 0.0, rng);
      for (std::size_t i = 0; i < r.scan.size(); ++i) {
        const float v = r.scan.ranges[i];
        ASSERT_FALSE(std::isnan(v));
        if (std::isfinite(v)) {
          ASSERT_TRUE(r.scan.Valid(i)) << v;
          ASSERT_GT(v, 0.0f);
        } else if (v > 0) {
          ++pos_inf;
        } else {
          ++neg_inf;
        }
      }
    }
    if (radius < 1.0) {
      EXPECT_GT(neg_inf, 100);  // readings pushed below range_min read -inf, never <= 0
    } else {
      EXPECT_GT(pos_inf, 1000);  // pushed beyond range_max: +inf, never a clamped max
    }
  }
}

TEST(Lidar, SameSeedGivesBitIdenticalScans) {
  const Lidar lidar(LidarConfig{}, BoxRoom(-10, -8, 12, 9));
  const std::vector<DynamicCircle> people = {{{3.0, 1.0}, 0.3, 1}, {{-2.0, 4.0}, 0.3, 2}};
  const core::Pose2 X_WR(0.5, -0.5, 0.7);
  core::Rng a(77), b(77), c(78);
  const LidarReading ra = lidar.Scan(X_WR, people, 1.0, a);
  const LidarReading rb = lidar.Scan(X_WR, people, 1.0, b);
  const LidarReading rc = lidar.Scan(X_WR, people, 1.0, c);
  ASSERT_EQ(ra.scan.ranges.size(), rb.scan.ranges.size());
  EXPECT_EQ(std::memcmp(ra.scan.ranges.data(), rb.scan.ranges.data(),
                        ra.scan.ranges.size() * sizeof(float)),
            0);
  for (std::size_t i = 0; i < ra.truth.size(); ++i) {
    ASSERT_EQ(ra.truth[i].source, rb.truth[i].source);
    ASSERT_EQ(ra.truth[i].range, rb.truth[i].range);
  }
  EXPECT_EQ(a.NextU64(), b.NextU64());
  EXPECT_NE(ra.scan.ranges, rc.scan.ranges);
}

}  // namespace
}  // namespace retrace::sim
