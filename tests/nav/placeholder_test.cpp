#include <gtest/gtest.h>
TEST(NavPlaceholder, Builds) { SUCCEED(); }
