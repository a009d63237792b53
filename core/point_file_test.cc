#include "core/point_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hexcal {
namespace {

using ::testing::HasSubstr;

TEST(PointFile, CsvWithAndWithoutSigma) {
  StatusOr<PointSets> sets = ParsePointFile(
      "pose,point,x,y,z,sigma\nview_0000.png,R1,1,2,3,0.01\nview_0000.png,R2,4,5,6,0.02\nview_0001.png,R1,7,8,9,0.01\n",
      "p.csv", 0.05);
  ASSERT_TRUE(sets.ok()) << sets.status().message();
  ASSERT_EQ(sets->size(), 2u);
  EXPECT_EQ((*sets)[0].pose, "view_0000.png");
  ASSERT_EQ((*sets)[0].points.size(), 2u);
  EXPECT_EQ((*sets)[0].points[1].position, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ((*sets)[0].points[1].sigma, 0.02);
  sets = ParsePointFile("z,y,x,point,pose\n3,2,1,R1,a\n", "p.csv", 0.05);  // any order, default σ
  ASSERT_TRUE(sets.ok()) << sets.status().message();
  EXPECT_EQ((*sets)[0].points[0].position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ((*sets)[0].points[0].sigma, 0.05);
}

TEST(PointFile, SpatialAnalyzerLayout) {
  const std::string text =
      "// SA export\n\nA::Tracker, Pose01, R1, 1.5, 2, 3\nA::Tracker\tPose01\tR2\t4 5 6 0.01\n"
      "A::Tracker Pose02 R1 7 8 9\n";
  StatusOr<PointSets> sets = ParsePointFile(text, "sa.txt", 0.03);
  ASSERT_TRUE(sets.ok()) << sets.status().message();
  ASSERT_EQ(sets->size(), 2u);
  EXPECT_EQ((*sets)[0].pose, "Pose01");
  EXPECT_EQ((*sets)[0].points[0].position, Eigen::Vector3d(1.5, 2, 3));
  EXPECT_EQ((*sets)[0].points[0].sigma, 0.03);
  EXPECT_EQ((*sets)[0].points[1].sigma, 0.01);
  EXPECT_EQ((*sets)[1].points[0].name, "R1");
}

std::string ErrorOf(const std::string& text) {
  StatusOr<PointSets> sets = ParsePointFile(text, "f", 0.02);
  return sets.ok() ? "" : sets.status().message();
}

TEST(PointFile, BadFilesNameTheLine) {
  EXPECT_THAT(ErrorOf("pose,point,x,y\na,R1,1,2\n"), HasSubstr("z"));
  EXPECT_THAT(ErrorOf("pose,point,x,y,z\na,R1,1,2,nan\n"), HasSubstr("f"));
  EXPECT_THAT(ErrorOf("pose,point,x,y,z\na,R1,1,2,3\na,R1,1,2,3\n"),
              HasSubstr("f:3: point 'R1' of pose 'a' is given twice"));
  EXPECT_THAT(ErrorOf("pose,point,x,y,z,sigma\na,R1,1,2,3,0\n"), HasSubstr("f:2: sigma must be positive"));
  EXPECT_THAT(ErrorOf("C G R1 1 2\n"), HasSubstr("f:1: expected collection, group, target, x, y, z"));
  EXPECT_THAT(ErrorOf("C G R1 1 2 0x10\n"), HasSubstr("f:1: field 6 is not a number"));
  EXPECT_THAT(ErrorOf("// nothing\n"), HasSubstr("f: no points"));
}

TEST(PointFile, Reflectors) {
  StatusOr<std::vector<NamedPoint>> reflectors = ParseReflectorFile("point,x,y,z\nR1,1,2,3\nR2,4,5,6\n", "r.csv");
  ASSERT_TRUE(reflectors.ok()) << reflectors.status().message();
  ASSERT_EQ(reflectors->size(), 2u);
  EXPECT_EQ((*reflectors)[1].position, Eigen::Vector3d(4, 5, 6));
  reflectors = ParseReflectorFile("point,x,y,z\nR1,1,2,3\nR1,4,5,6\n", "r.csv");
  ASSERT_FALSE(reflectors.ok());
  EXPECT_THAT(reflectors.status().message(), HasSubstr("r.csv:3: reflector 'R1' is given twice"));
}

}  // namespace
}  // namespace hexcal
