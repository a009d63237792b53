// Test helper for the camera-file tests (camera_file_test, camera_writers_test):
// two cameras equal in model, size, intrinsics and every coefficient, exactly.
//
//   ExpectSameCamera(*ParseCameraFile(text, "back.yaml"), camera);
#pragma once

#include <gtest/gtest.h>

#include "vision/camera.h"

namespace hexcal {

inline void ExpectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  for (size_t i = 0; i < a.distortion.size(); ++i) EXPECT_EQ(a.distortion[i], b.distortion[i]) << i;
}

}  // namespace hexcal
