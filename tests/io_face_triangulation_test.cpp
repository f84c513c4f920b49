// A mesh face's corner triples (io/face_triangulation.h): convex faces,
// collinear corners included, are fanned from the first corner in the
// file's order; concave ones are ear-clipped into triangles that keep the
// face's winding and cover it.
#include <array>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "io/face_triangulation.h"

namespace quiver {
namespace {

using Triples = std::vector<std::array<std::size_t, 3>>;

TEST(FaceTriangulation, ConvexFacesAndCollinearCornersAreFannedAsWritten) {
  Triples triples;
  const std::vector<Vec3<float>> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  triangulate_face(square, triples);
  EXPECT_EQ(triples, (Triples{{0, 1, 2}, {0, 2, 3}}));
  // A corner on the edge between its neighbours turns by 0: still convex, still a fan.
  const std::vector<Vec3<float>> with_collinear{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
  triangulate_face(with_collinear, triples);
  EXPECT_EQ(triples, (Triples{{0, 1, 2}, {0, 2, 3}}));
  const std::vector<Vec3<float>> triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangulate_face(triangle, triples);
  EXPECT_EQ(triples, (Triples{{0, 1, 2}}));
}

TEST(FaceTriangulation, AConcaveFaceIsClippedIntoEarsThatKeepItsWinding) {
  // An L (concave at corner 3), counter-clockwise about +z.
  const std::vector<Vec3<float>> l_shape{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  Triples triples;
  triangulate_face(l_shape, triples);
  ASSERT_EQ(triples.size(), 4u);
  double area = 0.0;
  for (const auto& t : triples) {
    const Vec3<float> a = l_shape[t[0]], b = l_shape[t[1]], c = l_shape[t[2]];
    const float z = cross(b - a, c - a).z;
    EXPECT_GT(z, 0.f);
    area += 0.5 * z;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);
}

// The same L, a dart (an arrowhead quad) and a band notched at its end
// (whose turns, each taken from the corner two back, all look convex),
// written from every corner, so that the reflex corner comes at each place
// in the list: every triangle keeps the face's winding and together they
// cover it.
TEST(FaceTriangulation, AReflexCornerAnywhereInTheListIsFound) {
  const std::vector<std::vector<Vec3<float>>> faces{
      {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}},  // the L, area 3
      {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5f, 1, 0}},                     // the dart, area 1.5
      {{4, 2, 0}, {0, 2, 0}, {0, 1, 0}, {4, 0, 0}, {3, 1, 0}}};            // a notched band, area 5
  const double areas[] = {3.0, 1.5, 5.0};
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::size_t n = faces[f].size();
    for (std::size_t start = 0; start < n; ++start) {
      std::vector<Vec3<float>> face;
      for (std::size_t k = 0; k < n; ++k) face.push_back(faces[f][(start + k) % n]);
      Triples triples;
      triangulate_face(face, triples);
      EXPECT_EQ(triples.size(), n - 2);
      double area = 0.0;
      for (const auto& t : triples) {
        const float z = cross(face[t[1]] - face[t[0]], face[t[2]] - face[t[0]]).z;
        EXPECT_GT(z, 0.f) << "face " << f << " from corner " << start;
        area += 0.5 * z;
      }
      EXPECT_DOUBLE_EQ(area, areas[f]) << "face " << f << " from corner " << start;
    }
  }
}

}  // namespace
}  // namespace quiver
