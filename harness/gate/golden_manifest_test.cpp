#include "harness/gate/golden_manifest.h"

#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

using ::testing::StartsWith;

GoldenEntry entry(std::string scene, std::string lane, std::string reason) {
  return {std::move(scene),
          std::move(lane),
          std::move(reason),
          "ada",
          "2024-05-01T12:34:56Z",
          "0123456789abcdef0123456789abcdef",
          {},
          {}};
}

TEST(GoldenManifestTest, FormatsEntriesSortedAfterTheHeaderAndReadsThemBack) {
  GoldenManifest manifest;
  manifest.record(entry("toon", "", "first render"));
  manifest.record(entry("dof_off", "vk-hlsl", "a \"quoted\" reason\\with a backslash\nand a second line"));
  manifest.record(entry("dof_off", "", "first render"));
  const std::string text = format_golden_manifest(manifest);

  const std::string header_end = "# Entries are sorted by scene, then lane.\n";
  ASSERT_THAT(text, StartsWith("# Why each golden image is what it is."));
  const std::string entries = text.substr(text.find(header_end) + header_end.size());
  EXPECT_EQ(entries,
            "\n[[golden]]\n"
            "scene = \"dof_off\"\n"
            "reason = \"first render\"\n"
            "blessed_by = \"ada\"\n"
            "date = \"2024-05-01T12:34:56Z\"\n"
            "hash = \"0123456789abcdef0123456789abcdef\"\n"
            "\n[[golden]]\n"
            "scene = \"dof_off\"\n"
            "lane = \"vk-hlsl\"\n"
            "reason = \"a \\\"quoted\\\" reason\\\\with a backslash\\nand a second line\"\n"
            "blessed_by = \"ada\"\n"
            "date = \"2024-05-01T12:34:56Z\"\n"
            "hash = \"0123456789abcdef0123456789abcdef\"\n"
            "\n[[golden]]\n"
            "scene = \"toon\"\n"
            "reason = \"first render\"\n"
            "blessed_by = \"ada\"\n"
            "date = \"2024-05-01T12:34:56Z\"\n"
            "hash = \"0123456789abcdef0123456789abcdef\"\n");

  auto read = parse_golden_manifest(text, "MANIFEST.toml");
  ASSERT_TRUE(read) << read.error().to_string();
  ASSERT_EQ(read->entries.size(), 3u);
  EXPECT_EQ(read->entries[1].reason, "a \"quoted\" reason\\with a backslash\nand a second line");
  EXPECT_EQ(read->entries[1].lane, "vk-hlsl");
  EXPECT_EQ(read->entries[1].where.to_string(), "MANIFEST.toml:23:1");
  EXPECT_EQ(format_golden_manifest(*read), text);
}

TEST(GoldenManifestTest, TheHeaderAloneIsAnEmptyManifest) {
  const std::string text = format_golden_manifest({});
  auto read = parse_golden_manifest(text, "MANIFEST.toml");
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_TRUE(read->entries.empty());
}

TEST(GoldenManifestTest, RecordingTheSameImageAgainReplacesItsEntry) {
  GoldenManifest manifest;
  manifest.record(entry("dof_off", "", "first render"));
  manifest.record(entry("dof_off", "gl", "llvmpipe"));
  manifest.record(entry("dof_off", "", "warmer light"));
  ASSERT_EQ(manifest.entries.size(), 2u);
  EXPECT_EQ(manifest.find("dof_off", "")->reason, "warmer light");
  EXPECT_EQ(manifest.find("dof_off", "gl")->reason, "llvmpipe");
  EXPECT_EQ(manifest.find("dof_off", "vk"), nullptr);
}

// The project's own manifest is valid and keeps the header bless writes, so that the first bless
// changes nothing but its entry.
TEST(GoldenManifestTest, TheProjectManifestReadsAndKeepsTheHeader) {
  const std::filesystem::path path = std::filesystem::path(XSHADE_SOURCE_DIR) / "golden" / "MANIFEST.toml";
  auto read = read_golden_manifest(path);
  ASSERT_TRUE(read) << read.error().to_string();
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_THAT(text.str(), StartsWith(format_golden_manifest({})));
  EXPECT_EQ(format_golden_manifest(*read), text.str());
}

// The manifest is TOML too: a key deep enough to overflow toml++'s stack is refused before it
// reads it, at the key.
TEST(GoldenManifestTest, AKeyNestedTooDeepIsRefusedBeforeTheTomlParserRecurses) {
  std::string key = "a";
  for (int i = 1; i < 100000; ++i) key += ".a";
  auto read = parse_golden_manifest("[[golden]]\nscene = \"a\"\n" + key + " = 1\n", "MANIFEST.toml");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().to_string(),
            "MANIFEST.toml:3:1: a dotted key or table header of 100000 parts; xshade reads "
            "at most 100 (a longer one could overflow the TOML parser's stack)");
}

TEST(GoldenManifestTest, AManifestOfMoreEntriesThanAnyProjectIsRefusedAtTheFirstOnePastTheLimit) {
  std::string text;
  for (size_t i = 0; i <= kMaxManifestEntries; ++i)
    text += fmt::format("[[golden]]\nscene = \"s{}\"\nreason = \"r\"\n", i);
  auto read = parse_golden_manifest(text, "MANIFEST.toml");
  ASSERT_FALSE(read);
  EXPECT_EQ(
      read.error().to_string(),
      fmt::format("MANIFEST.toml:{}:1: more than {} [[golden]] entries: this is not a golden manifest xshade wrote",
                  3 * kMaxManifestEntries + 1, kMaxManifestEntries));
}

struct BadManifest {
  std::string text;
  std::string error;
};

class GoldenManifestErrorTest : public ::testing::TestWithParam<BadManifest> {};

TEST_P(GoldenManifestErrorTest, NamesTheProblemAndWhereItIs) {
  auto read = parse_golden_manifest(GetParam().text, "MANIFEST.toml");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().to_string(), GetParam().error);
}

INSTANTIATE_TEST_SUITE_P(
    Manifests, GoldenManifestErrorTest,
    ::testing::Values(
        BadManifest{"[[golden]]\nscene = \"a\"\nreason = \"why\"\ncolour = \"red\"\n",
                    "MANIFEST.toml:4:10: unknown key 'colour' in a [[golden]] entry (known: scene, lane, reason, "
                    "blessed_by, date, hash, float_hash)"},
        BadManifest{"[[golden]]\nscene = \"a\"\nreason = 3\n", "MANIFEST.toml:3:10: 'reason' must be a string"},
        BadManifest{"[[golden]]\nscene = \"a\"\nlane = \"dx12\"\nreason = \"why\"\n",
                    "MANIFEST.toml:3:8: unknown lane 'dx12' (lanes: gl, vk, vk-hlsl)"},
        BadManifest{"[[golden]]\nreason = \"why\"\n", "MANIFEST.toml:1:1: a [[golden]] entry needs a scene"},
        BadManifest{"[[golden]]\nscene = \"a\"\nlane = \"vk\"\nreason = \" \"\n",
                    "MANIFEST.toml:1:1: the golden of vk/a has no reason"},
        BadManifest{"[[golden]]\nscene = \"a\"\nreason = \"x\"\n\n[[golden]]\nscene = \"a\"\nreason = \"y\"\n",
                    "MANIFEST.toml:5:1: a second entry for the golden of a (the first is at MANIFEST.toml:1:1)"},
        // Found when the entries are sorted, and still named in the order of the file.
        BadManifest{"[[golden]]\nscene = \"b\"\nreason = \"x\"\n\n[[golden]]\nscene = \"a\"\nreason = \"y\"\n\n"
                    "[[golden]]\nscene = \"b\"\nlane = \"vk\"\nreason = \"z\"\n\n[[golden]]\nscene = \"b\"\nreason = "
                    "\"w\"\n",
                    "MANIFEST.toml:14:1: a second entry for the golden of b (the first is at MANIFEST.toml:1:1)"},
        BadManifest{"goldens = 1\n",
                    "MANIFEST.toml:1:11: unknown key 'goldens' (the manifest holds only [[golden]] "
                    "entries)"},
        BadManifest{"golden = 1\n", "MANIFEST.toml:1:10: 'golden' must be an array of tables: [[golden]]"}));

}  // namespace
}  // namespace xshade::harness
