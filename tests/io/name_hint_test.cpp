// Tests for name hints: edit distance, the nearest known name, and the hint text.
#include "wirerig/io/name_hint.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(EditDistance("duration", "duration"), 0u);
  EXPECT_EQ(EditDistance("duraton", "duration"), 1u);    // deletion
  EXPECT_EQ(EditDistance("durration", "duration"), 1u);  // insertion
  EXPECT_EQ(EditDistance("colour", "color"), 1u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
}

TEST(NearestName, SuggestsOnlyLikelyMisspellings) {
  const std::vector<std::string> known = {"name", "duration", "loop", "parts"};
  EXPECT_EQ(NearestName("duraton", known), "duration");
  EXPECT_EQ(NearestName("lop", known), "loop");
  EXPECT_EQ(NearestName("colour", known), "");  // nothing close
  EXPECT_EQ(NearestName("x", known), "");
  EXPECT_EQ(NearestName("anything", {}), "");
}

TEST(NameHint, SuggestsAndLists) {
  const std::vector<std::string> clips = {"wave", "pose"};
  EXPECT_EQ(NameHint("wav", clips, "clips"), "; did you mean \"wave\"? (clips: wave, pose)");
  EXPECT_EQ(NameHint("dance", clips, "clips"), " (clips: wave, pose)");
  EXPECT_EQ(NameHint("dance", {}, "clips"), " (there are no clips)");
}

TEST(NameHint, ListsAtMostTwentyNames) {
  std::vector<std::string> parts;
  for (int i = 0; i < 25; ++i) parts.push_back(std::string(1, 'p').append(std::to_string(i)));
  const std::string hint = NameHint("zzzz", parts, "parts");
  EXPECT_NE(hint.find("p19, and 5 more)"), std::string::npos) << hint;
  EXPECT_EQ(hint.find("p20"), std::string::npos) << hint;
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
