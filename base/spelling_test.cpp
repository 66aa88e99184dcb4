#include "base/spelling.h"

#include <gtest/gtest.h>

namespace xshade {
namespace {

TEST(EditDistance, CountsOneEditPerTypoAndIgnoresCase) {
  EXPECT_EQ(edit_distance("_Colr", "_Color"), 1u);   // a letter missing
  EXPECT_EQ(edit_distance("_Cloor", "_Color"), 1u);  // two letters swapped
  EXPECT_EQ(edit_distance("_COLOR", "_Color"), 0u);  // case only
  EXPECT_EQ(edit_distance("_RampTexture", "_RampTex"), 4u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
}

TEST(Nearest, SuggestsOnlyWhatIsCloseEnoughForTheWordsLength) {
  EXPECT_EQ(nearest("_Colr", {"_Color", "_MainTex"}), "_Color");
  EXPECT_EQ(nearest("_RampTexture", {"_MainTex", "_RampTex"}), "_RampTex");
  // Two edits in a five-letter word is another word, not a typo.
  EXPECT_EQ(nearest("_Clr", {"_Color"}), std::nullopt);
  EXPECT_EQ(nearest("_BlurAmount", {"_Distance", "_LensCoeff"}), std::nullopt);
  EXPECT_EQ(nearest("valk", std::vector<std::string>{"eval", "run", "bless"}), std::nullopt);
  EXPECT_EQ(nearest("blss", std::vector<std::string>{"eval", "run", "bless"}), "bless");
}

}  // namespace
}  // namespace xshade
