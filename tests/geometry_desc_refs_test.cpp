// Tests of geometry/desc_refs.h: a list converts to references to its own
// elements, in order, and a builder reading references sees the elements
// themselves (no copies), so a store keeps their input indices.
#include "geometry/desc_refs.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "geometry/kinds/sphere.h"

namespace quiver {
namespace {

TEST(DescRefs, AListConvertsToReferencesToItsOwnElementsInOrder) {
  const std::vector<int> list{4, 5, 6};
  const DescRefs<int> refs = list;
  ASSERT_EQ(refs.size(), 3u);
  for (std::size_t i = 0; i < list.size(); ++i) EXPECT_EQ(&refs[i], &list[i]) << i;
  EXPECT_EQ(DescRefs<int>().size(), 0u);
}

TEST(DescRefs, PushedReferencesKeepTheirOrderAndABuilderIndexesThem) {
  const std::array<SphereDesc, 3> spheres{SphereDesc{{0.f, 0.f, 0.f}, 1.f}, SphereDesc{{5.f, 0.f, 0.f}, 2.f},
                                          SphereDesc{{9.f, 0.f, 0.f}, 3.f}};
  DescRefs<SphereDesc> backwards;
  for (std::size_t i = spheres.size(); i-- > 0;) backwards.push_back(spheres[i]);
  EXPECT_EQ(&backwards[0], &spheres[2]);
  BuildReport report;
  const SphereSoA store = build_spheres(backwards, report);
  ASSERT_EQ(store.count, 3u);
  // Positions in the list handed over, not in the array behind it.
  EXPECT_EQ(store.source, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(store.cx[0], 9.f);
  EXPECT_EQ(store.cx[2], 0.f);
}

}  // namespace
}  // namespace quiver
