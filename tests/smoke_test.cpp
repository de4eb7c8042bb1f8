#include <gtest/gtest.h>
#include "quadrix/math/mat4.h"
TEST(Smoke, Identity) { EXPECT_EQ(quadrix::Mat4::Identity()(0, 0), 1.0); }
