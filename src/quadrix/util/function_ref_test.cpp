// FunctionRef (function_ref.h): calls the callable it refers to, not a copy of it, whatever the
// size of its capture; an empty one is false.
#include "quadrix/util/function_ref.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace quadrix {
namespace {

TEST(FunctionRef, CallsTheCallableItRefersToNotACopy) {
    FunctionRef<int(int)> empty;
    EXPECT_FALSE(empty);

    int calls = 0;
    // A capture of 64 bytes and more (std::function would allocate it on the heap).
    const std::array<double, 8> weights{1, 2, 3, 4, 5, 6, 7, 8};
    auto counted = [&calls, weights](int x) {
        ++calls;
        return x * static_cast<int>(weights[7]);
    };
    FunctionRef<int(int)> ref = counted;
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref(3), 24);
    EXPECT_EQ(ref(-1), -8);
    EXPECT_EQ(calls, 2);

    // A mutable callable's state is the referenced object's: no copy was made.
    int total = 0;
    auto accumulate = [total](int x) mutable { return total += x; };
    FunctionRef<int(int)> acc = accumulate;
    acc(5);
    acc(7);
    EXPECT_EQ(accumulate(0), 12);

    // Arguments passed by reference.
    auto append = [](std::string& s, const std::string& t) { s += t; };
    FunctionRef<void(std::string&, const std::string&)> app = append;
    std::string s = "ab";
    app(s, "cd");
    EXPECT_EQ(s, "abcd");

    // Reassigned (the shader's way: empty, then set where shadows are on), it calls the new one.
    auto plusOne = [](int x) { return x + 1; };
    FunctionRef<int(int)> later;
    EXPECT_FALSE(later);
    later = plusOne;
    EXPECT_EQ(later(1), 2);
    later = counted;
    EXPECT_EQ(later(1), 8);
    EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace quadrix
