#include "uavplan/core/text.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

TEST(Text, StrfIsNeverCut) {
  const std::string id(5000, 'x');
  const std::string s = strf("'%s' at %.1f s", id.c_str(), 2.25);
  EXPECT_EQ(s.size(), id.size() + 11);
  EXPECT_EQ(s.substr(s.size() - 10), "' at 2.2 s");
  EXPECT_EQ(strf("%s", ""), "");
  EXPECT_EQ(num_text(2.5), "2.5");
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

TEST(Text, WordListsJoinWithCommasAndTheLastConjunction) {
  EXPECT_EQ(word_list({}), "");
  EXPECT_EQ(word_list({"a"}), "a");
  EXPECT_EQ(word_list({"a", "b"}), "a or b");
  EXPECT_EQ(word_list({"a", "b", "c"}, "and"), "a, b and c");
}

TEST(Text, NearestWordNamesWhatATypoMeant) {
  const std::vector<std::string> keys = {"speed", "separation", "start", "radius", "id"};
  EXPECT_EQ(nearest_word("sped", keys), "speed");
  EXPECT_EQ(nearest_word("seperation", keys), "separation");
  EXPECT_EQ(nearest_word("raduis", keys), "radius");  // a swap is one edit
  EXPECT_EQ(nearest_word("colour", keys), "");        // nothing near
  EXPECT_EQ(nearest_word("ix", keys), "id");
  EXPECT_EQ(nearest_word("xyz", keys), "");
}

}  // namespace
}  // namespace uavplan
