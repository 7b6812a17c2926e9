#include <gtest/gtest.h>
TEST(IoPlaceholder, Builds) { SUCCEED(); }
