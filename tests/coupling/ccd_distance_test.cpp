// The CCD's private distances against closed forms, degenerate inputs included.
#include <gtest/gtest.h>

#include <stiffsoft/coupling/ccd/distance.hpp>

namespace stiffsoft::ccd::detail {
namespace {

using V = Vec3<double>;

TEST(CcdDistance, PointTriangleInEachRegion) {
  const V t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(0.2, 0.2, 3), t0, t1, t2), 9);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(-1, -1, 0), t0, t1, t2), 2);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(0.5, -2, 1), t0, t1, t2), 5);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(1, 1, 0), t0, t1, t2), 0.5);
}

TEST(CcdDistance, DegenerateTriangleIsASegment) {
  const V t0(0, 0, 0), t1(1, 0, 0), t2(2, 0, 0);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(1.5, 2, 0), t0, t1, t2), 4);
  EXPECT_DOUBLE_EQ(point_triangle_distance_squared<double>(V(1, 1, 0), t0, t0, t0), 2);
}

TEST(CcdDistance, SegmentSegmentCrossingParallelAndDegenerate) {
  EXPECT_DOUBLE_EQ(segment_segment_distance_squared<double>(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 2),
                                                            V(0, 1, 2)),
                   4);
  // Closest points of the lines outside both segments: endpoint distance.
  EXPECT_DOUBLE_EQ(segment_segment_distance_squared<double>(V(0, 0, 0), V(1, 0, 0), V(2, 1, 0),
                                                            V(2, 2, 0)),
                   2);
  // Parallel, overlapping and not.
  EXPECT_DOUBLE_EQ(segment_segment_distance_squared<double>(V(0, 0, 0), V(2, 0, 0), V(1, 3, 0),
                                                            V(3, 3, 0)),
                   9);
  EXPECT_DOUBLE_EQ(segment_segment_distance_squared<double>(V(0, 0, 0), V(1, 0, 0), V(3, 0, 0),
                                                            V(4, 0, 0)),
                   4);
  // A point-like segment.
  EXPECT_DOUBLE_EQ(segment_segment_distance_squared<double>(V(0, 0, 0), V(0, 0, 0), V(-1, 1, 0),
                                                            V(1, 1, 0)),
                   1);
}

}  // namespace
}  // namespace stiffsoft::ccd::detail
