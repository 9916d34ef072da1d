// The simulator's terrain: the catalogue's soils by name, patches and hills along the path, and
// the rover's synthetic profiles scaled to the stated roughness.
#include "sim/terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace slipgraph {
namespace sim {
namespace {

TEST(Terrain, TheCatalogueByName) {
  for (const char* name :
       {"grass", "mulch", "gravel", "mud", "asphalt", "soft_dirt", "loose_rock"}) {
    EXPECT_EQ(FindTerrain(name).name, name);
  }
  EXPECT_THROW(FindTerrain("lava"), std::invalid_argument);
}

TEST(Terrain, PatchesAndHillsAlongThePath) {
  Course c;
  c.patches = {{0.0, FindTerrain("grass")}, {10.0, FindTerrain("mud")}};
  c.hills = {{20.0, 10.0, 0.1, -0.04}};
  EXPECT_EQ(c.PatchAt(5.0).terrain.name, "grass");
  EXPECT_EQ(c.PatchAt(10.0).terrain.name, "mud");
  EXPECT_EQ(c.PatchAt(1e6).terrain.name, "mud");
  EXPECT_NEAR(c.DistanceIntoPatch(13.5), 3.5, 1e-12);
  // A raised cosine: zero at both ends, the peak halfway.
  EXPECT_DOUBLE_EQ(c.GradeRad(19.0), 0.0);
  EXPECT_NEAR(c.GradeRad(20.0), 0.0, 1e-12);
  EXPECT_NEAR(c.GradeRad(25.0), 0.1, 1e-12);
  EXPECT_NEAR(c.CrossSlopeRad(25.0), -0.04, 1e-12);
  EXPECT_NEAR(c.GradeRad(30.0), 0.0, 1e-12);
  EXPECT_GT(c.GradeRad(22.0), 0.0);
  EXPECT_LT(c.GradeRad(22.0), 0.1);
}

TEST(Terrain, ProfileHasTheStatedRoughnessAndDependsOnTheSeed) {
  const double length = 20.0;
  const TerrainProfile p = MakeTerrainProfile(0.01, length, 3);
  ASSERT_EQ(p.wavelength_m.size(), 20u);
  EXPECT_NEAR(p.wavelength_m.front(), 0.013, 0.002);
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double y = p.Elevation(length * i / n);
    sum += y;
    sum2 += y * y;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.001);
  const TerrainProfile same = MakeTerrainProfile(0.01, length, 3);
  const TerrainProfile other = MakeTerrainProfile(0.01, length, 4);
  EXPECT_EQ(p.Elevation(7.3), same.Elevation(7.3));
  EXPECT_NE(p.Elevation(7.3), other.Elevation(7.3));
  // A contact patch averages the short wavelengths away: smoother than the raw elevation.
  double raw_step = 0.0, wheel_step = 0.0;
  for (int i = 1; i < 2000; ++i) {
    const double x = 0.005 * i;
    raw_step += std::abs(p.Elevation(x) - p.Elevation(x - 0.005));
    wheel_step += std::abs(p.WheelElevation(x, 0.1) - p.WheelElevation(x - 0.005, 0.1));
  }
  EXPECT_LT(wheel_step, raw_step);
}

}  // namespace
}  // namespace sim
}  // namespace slipgraph
