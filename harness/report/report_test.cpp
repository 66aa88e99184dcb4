#include "harness/report/report.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness/image/image_io.h"
#include "harness/report/junit_report.h"
#include "harness/report/report_html.h"
#include "harness/report/results_json.h"
#include "harness/report/viewer_data.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const std::string kHostileScene = "toon <script>alert(1)</script> & co";

DriverInfo gl_driver() {
  return {"OpenGL 4.5 core (OSMesa)", "llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6",
          "Mesa 22.3.6", "15.0.6"};
}

// A failing comparison's metrics: 312 pixels beyond the tolerance, the worst 64 steps at (4, 7).
ImageMetrics failing_metrics() {
  ImageMetrics metrics{0.25, 4, 7, 0.01, 0.02, 33.5, 312, 0.076};
  metrics.max_steps = 64;
  metrics.worst_x = 4;
  metrics.worst_y = 7;
  metrics.first_failing = std::pair<uint32_t, uint32_t>{1, 2};
  return metrics;
}

LaneResult passing_lane(const std::string& scene, const std::string& lane) {
  LaneResult result;
  result.lane = lane;
  result.layers = {{"finite", Verdict::Pass, "no NaN, Inf or negative values"},
                   {"exact", Verdict::Pass, "identical bits"}};
  result.against_golden = ImageMetrics{0.0, 0, 0, 0.0, 0.0, std::numeric_limits<double>::infinity(), 0, 0.0};
  result.image = scene + "/" + lane + ".png";
  result.golden = scene + "/golden.png";
  result.diff = scene + "/" + lane + ".diff.png";
  result.timings = {{"main", 12.5}, {"tonemap", 1.25}};
  result.seconds = 0.75;
  result.driver = gl_driver();
  return result;
}

// A passing scene (with a skipped lane), a failing scene whose name is hostile markup, and a
// scene that failed before any lane ran.
RunResults sample_results() {
  RunResults results;
  results.started = "2024-05-01T10:20:30Z";
  results.seconds = 4.5;
  results.command = "xshade run --report out <all>";

  SceneResult sphere;
  sphere.scene = "lit_sphere";
  sphere.description = "A lit sphere on grey";
  sphere.lanes = {passing_lane("lit_sphere", "gl"), passing_lane("lit_sphere", "vk")};
  LaneResult skipped;
  skipped.lane = "vk-hlsl";
  skipped.verdict = Verdict::Skipped;
  skipped.message = "lane not selected";
  sphere.lanes.push_back(skipped);
  sphere.cross_lane = {{"gl", "vk", Verdict::Pass, {}, "lit_sphere/gl_vs_vk.diff.png"}};
  sphere.plan = "pass main -> target colour 64x64\n  draw sphere with lit.hlsl";

  SceneResult toon;
  toon.scene = kHostileScene;
  toon.description = "Description with <b>tags</b> & ampersands";
  toon.verdict = Verdict::Fail;
  LaneResult toon_gl = passing_lane("toon", "gl");
  LaneResult toon_vk = passing_lane("toon", "vk");
  toon_vk.verdict = Verdict::Fail;
  toon_vk.layers = {{"finite", Verdict::Fail, "3 NaN at (4, 7) first"},
                    {"per_pixel", Verdict::Fail, "312 pixels beyond 2/255 (budget 0.1%)"}};
  toon_vk.against_golden = failing_metrics();
  toon_vk.non_finite = {3, 0, 0, std::make_pair(4u, 7u)};
  toon_vk.non_finite_mask = "toon/vk.nonfinite.png";
  LaneResult toon_hlsl = passing_lane("toon", "vk-hlsl");
  toon_hlsl.verdict = Verdict::Fail;
  toon_hlsl.golden.clear();
  toon_hlsl.diff.clear();
  toon_hlsl.against_golden.reset();
  toon_hlsl.layers = {{"golden", Verdict::Fail, "no golden for this scene"}};
  toon_hlsl.message = "run: xshade bless toon --lane vk-hlsl";
  toon.lanes = {toon_gl, toon_vk, toon_hlsl};
  toon.cross_lane = {{"gl", "vk", Verdict::Fail, failing_metrics(), "toon/gl_vs_vk.diff.png"}};
  toon.plan = "pass main <with> & without";
  toon.warnings = {"toon.shader:5:13: warning: unknown pragma '<frob>'"};

  SceneResult broken;
  broken.scene = "broken_shader";
  broken.verdict = Verdict::Error;
  broken.message = "materials/broken.hlsl:3:5: error: unknown identifier 'colr'\n  return colr;\n         ^";

  results.scenes = {sphere, toon, broken};
  return results;
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// The value of attribute `name` in the first element `element` of an XML text.
std::string attribute(const std::string& xml, const std::string& element, const std::string& name) {
  std::smatch match;
  const std::regex tag("<" + element + "\\b[^>]*\\b" + name + "=\"([^\"]*)\"");
  return std::regex_search(xml, match, tag) ? match[1].str() : "<missing>";
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("xshade_report_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    results_ = sample_results();
    auto written = write_reports(results_, dir_);
    ASSERT_TRUE(written) << written.error().to_string();
    pages_ = scene_page_names(results_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  RunResults results_;
  std::vector<std::string> pages_;
};

TEST_F(ReportTest, WritesEveryFileAndNoTemporaryOnes) {
  EXPECT_TRUE(fs::is_regular_file(dir_ / "index.html"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "junit.xml"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "results.json"));
  ASSERT_EQ(pages_.size(), 3u);
  for (const std::string& page : pages_) EXPECT_TRUE(fs::is_regular_file(dir_ / page)) << page;
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(ReportTest, PageNamesAreSafeFileNames) {
  EXPECT_EQ(pages_[0], "lit_sphere.html");
  EXPECT_EQ(pages_[1], "toon__script_alert_1___script____co.html");
  EXPECT_EQ(pages_[2], "broken_shader.html");

  RunResults clashing;
  for (const char* name : {"index", "a b", "a_b", "A_B", ""}) {
    SceneResult scene;
    scene.scene = name;
    clashing.scenes.push_back(scene);
  }
  EXPECT_EQ(scene_page_names(clashing),
            (std::vector<std::string>{"index-2.html", "a_b.html", "a_b-2.html", "A_B-3.html", "scene.html"}));
}

TEST_F(ReportTest, IndexLinksEveryScenePageAndListsFailuresFirst) {
  const std::string index = read_text(dir_ / "index.html");
  for (const std::string& page : pages_) EXPECT_NE(index.find("href=\"" + page), std::string::npos) << page;
  const size_t failing = index.find("href=\"" + pages_[1] + "\"");
  const size_t errored = index.find("href=\"" + pages_[2] + "\"");
  const size_t passing = index.find("href=\"" + pages_[0] + "\"");
  EXPECT_LT(errored, failing);  // the more urgent verdict first
  EXPECT_LT(failing, passing);
  EXPECT_NE(index.find("<title>xshade: ERROR</title>"), std::string::npos);
  EXPECT_NE(index.find("Did not pass (2)"), std::string::npos);
  EXPECT_NE(index.find(results_.command.substr(0, 20)), std::string::npos);
}

TEST_F(ReportTest, IndexSaysWhatDecidesEachScenesComparison) {
  RunResults results = sample_results();
  results.scenes[0].compare.metric = MetricSettings{Metric::Flip, 0.002, 1.0, 0.0, 0.0};
  results.scenes[1].compare.channel_tolerance = 3;
  results.scenes[1].compare.position_radius = 1;
  const std::string index = index_html(results);
  EXPECT_NE(index.find("compared by FLIP mean ≤ 0.002"), std::string::npos) << index;
  EXPECT_NE(index.find("compared by per pixel ±3 sRGB steps, within 1 px"), std::string::npos) << index;
  EXPECT_NE(index.find("compared by per pixel ±1 sRGB step<"), std::string::npos) << index;
}

TEST_F(ReportTest, AMergedReportListsItsRunsFoldedBelowTheScenes) {
  RunResults results = sample_results();
  for (int i = 1; i <= 31; ++i)
    results.merged_from.push_back({"test-" + std::to_string(i), "2024-05-01T10:20:30Z", 1.0, "xshade run scene"});
  const std::string index = index_html(results);
  EXPECT_NE(index.find("merged from</dt><dd>31 runs"), std::string::npos);
  const size_t table = index.find("<table class=\"index\"");
  const size_t runs = index.find("<details id=\"runs\"");
  ASSERT_NE(table, std::string::npos);
  ASSERT_NE(runs, std::string::npos);
  EXPECT_LT(table, runs);  // the results first
  EXPECT_LT(runs, index.find("test-1:"));
  EXPECT_EQ(index.find("<details id=\"runs\" open"), std::string::npos);  // folded
}

TEST_F(ReportTest, IndexShowsTheFailingLaneWithItsFirstFailingLayer) {
  const std::string index = read_text(dir_ / "index.html");
  const std::string vk_cell = "<td class=\"cell v-fail\"><a href=\"" + pages_[1] + "#lane-vk\">";
  const size_t cell = index.find(vk_cell);
  ASSERT_NE(cell, std::string::npos) << index;
  const std::string rest = index.substr(cell, index.find("</td>", cell) - cell);
  EXPECT_NE(rest.find("FAIL"), std::string::npos);
  EXPECT_NE(rest.find("finite: 3 NaN at (4, 7) first"), std::string::npos) << rest;
  // The errored scene says why in its row, and the failing cross-lane pair shows its numbers.
  EXPECT_NE(index.find("materials/broken.hlsl:3:5: error: unknown identifier &#39;colr&#39;"), std::string::npos);
  EXPECT_NE(index.find("worst 64 sRGB steps at (4, 7), 312 failing pixels (7.6%)"), std::string::npos);
}

TEST_F(ReportTest, SceneTextIsEscapedEverywhere) {
  for (const std::string& file : {std::string("index.html"), pages_[1], std::string("junit.xml")}) {
    const std::string text = read_text(dir_ / file);
    EXPECT_EQ(text.find("<script>alert"), std::string::npos) << file;
    EXPECT_NE(text.find("toon &lt;script&gt;alert(1)&lt;/script&gt; &amp; co"), std::string::npos) << file;
  }
  const std::string page = read_text(dir_ / pages_[1]);
  // In the viewer's data, as JSON whose '<' cannot end its <script> element.
  EXPECT_NE(page.find(R"("scene":"toon \u003cscript>alert(1)\u003c/script> & co")"), std::string::npos);
  EXPECT_NE(page.find("Description with &lt;b&gt;tags&lt;/b&gt; &amp; ampersands"), std::string::npos);
  EXPECT_NE(page.find("<pre>pass main &lt;with&gt; &amp; without</pre>"), std::string::npos);
}

TEST_F(ReportTest, ScenePageShowsImagesMetricsTimingsAndDriver) {
  const std::string page = read_text(dir_ / pages_[0]);
  // The viewer gets each lane's images; without float images (none in this folder) the two lanes
  // cannot be proven identical and are shown apart.
  EXPECT_NE(page.find("<div id=\"xshade-viewer\"></div>"), std::string::npos);
  EXPECT_NE(page.find(R"("lanes":["gl"],"metric":null,"output":{"pixels":null,"png":"lit_sphere/gl.png"})"),
            std::string::npos);
  EXPECT_NE(page.find(R"("golden":{"pixels":null,"png":"lit_sphere/golden.png"})"), std::string::npos);
  EXPECT_NE(page.find(R"("heat_map":"lit_sphere/vk.diff.png")"), std::string::npos);
  EXPECT_NE(page.find("<a href=\"lit_sphere/gl.png\">image (PNG)</a>"), std::string::npos);
  EXPECT_NE(page.find("src=\"lit_sphere/gl_vs_vk.diff.png\""), std::string::npos);
  EXPECT_NE(page.find("image-rendering: pixelated"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"num\">12.50</td>"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"num\">0.750 s</td>"), std::string::npos);
  EXPECT_NE(page.find("llvmpipe (LLVM 15.0.6, 256 bits)"), std::string::npos);
  EXPECT_NE(page.find("<th>llvm_version</th><td>15.0.6</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>PSNR</th><td>identical</td>"), std::string::npos);
  EXPECT_NE(page.find("<pre>pass main -&gt; target colour 64x64\n  draw sphere with lit.hlsl</pre>"),
            std::string::npos);
  // No NaN in this scene: no mask.
  EXPECT_EQ(page.find("NaN / Inf / negative"), std::string::npos);
  // Nothing fetched from elsewhere: the viewer is the report's own, and no float data is here to
  // load beside the page.
  EXPECT_EQ(occurrences(page, "<script src"), 1u);
  EXPECT_NE(page.find("<link rel=\"stylesheet\" href=\"viewer.css\">\n<script src=\"viewer.js\"></script>"),
            std::string::npos);
  EXPECT_EQ(read_text(dir_ / "viewer.js"), viewer_script());
  EXPECT_EQ(read_text(dir_ / "viewer.css"), viewer_style());
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
}

TEST_F(ReportTest, FailingScenePageShowsTheMaskMetricsAndTheMissingGolden) {
  const std::string page = read_text(dir_ / pages_[1]);
  EXPECT_NE(page.find("src=\"toon/vk.nonfinite.png\""), std::string::npos);
  EXPECT_NE(page.find("<th>domain</th><td>8-bit sRGB steps, as the per-pixel layer compares</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>worst</th><td>64 steps at (4, 7)</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>first failing</th><td>(1, 2)</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>failing pixels</th><td>312 (7.6%)</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>PSNR</th><td>33.50 dB</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>first at</th><td>(4, 7)</td>"), std::string::npos);
  EXPECT_NE(page.find("<pre class=\"message\">run: xshade bless toon --lane vk-hlsl</pre>"), std::string::npos);
  // The first layer that failed is the one a reviewer reads first, not the last.
  EXPECT_EQ(page.find("<p class=\"why\">per_pixel"), std::string::npos);
  EXPECT_NE(page.find("<p class=\"why\">finite: 3 NaN at (4, 7) first</p>"), std::string::npos);
  // The front end's warnings about the scene's sources, escaped.
  EXPECT_NE(page.find("<h2>Warnings</h2>\n<pre class=\"warnings\">toon.shader:5:13: warning: unknown pragma "
                      "&#39;&lt;frob&gt;&#39;\n</pre>"),
            std::string::npos);
  EXPECT_EQ(read_text(dir_ / pages_[0]).find("<h2>Warnings</h2>"), std::string::npos) << "none in the sphere's sources";
}

TEST_F(ReportTest, ErroredScenePageShowsTheMessage) {
  const std::string page = read_text(dir_ / pages_[2]);
  EXPECT_NE(page.find("<pre class=\"message\">materials/broken.hlsl:3:5: error: unknown identifier &#39;colr&#39;\n"
                      "  return colr;\n         ^</pre>"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"badge v-error\">ERROR</span>"), std::string::npos);
}

TEST_F(ReportTest, JUnitCountsMatchTheResults) {
  const std::string xml = read_text(dir_ / "junit.xml");
  // lit_sphere: gl, vk, vk-hlsl (skipped), gl vs vk; toon: gl, vk (fail), vk-hlsl (fail),
  // gl vs vk (fail); broken_shader: one "scene" case (error).
  EXPECT_EQ(attribute(xml, "testsuites", "tests"), "9");
  EXPECT_EQ(attribute(xml, "testsuites", "failures"), "3");
  EXPECT_EQ(attribute(xml, "testsuites", "errors"), "1");
  EXPECT_EQ(attribute(xml, "testsuites", "skipped"), "1");
  EXPECT_EQ(attribute(xml, "testsuites", "time"), "4.500");
  EXPECT_EQ(occurrences(xml, "<testsuite "), 3u);
  EXPECT_EQ(occurrences(xml, "<testcase "), 9u);
  EXPECT_EQ(occurrences(xml, "<failure "), 3u);
  EXPECT_EQ(occurrences(xml, "<error "), 1u);
  EXPECT_EQ(occurrences(xml, "<skipped "), 1u);
  EXPECT_NE(xml.find("<testcase classname=\"lit_sphere\" name=\"gl vs vk\""), std::string::npos);
  EXPECT_NE(
      xml.find("<testsuite name=\"lit_sphere\" tests=\"4\" failures=\"0\" errors=\"0\" skipped=\"1\" time=\"1.500\""),
      std::string::npos);
  EXPECT_NE(xml.find("<failure message=\"finite: 3 NaN at (4, 7) first\" type=\"fail\">"), std::string::npos);
  EXPECT_NE(xml.find("<testcase classname=\"broken_shader\" name=\"scene\" time=\"0.000\">\n      <error "
                     "message=\"materials/broken.hlsl:3:5: error: unknown identifier &#39;colr&#39;\" type=\"error\">"),
            std::string::npos);
}

// Parses a file with Python's XML parser, when there is a python3 to run; -1 when there is not.
int parse_with_python(const fs::path& file) {
  if (std::system("command -v python3 >/dev/null 2>&1") != 0) return -1;
  const std::string command =
      "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' '" + file.string() + "'";
  return std::system(command.c_str());
}

TEST_F(ReportTest, JUnitIsWellFormedXmlEvenForHostileText) {
  RunResults hostile = sample_results();
  hostile.scenes[1].lanes[1].layers[0].detail = std::string("bad \x01 bytes \xFF and ]]> <x a=\"b\">\n second line");
  hostile.scenes[2].message = std::string("\x1b[31mred\x1b[0m & \"quoted\"");
  const fs::path file = dir_ / "hostile.xml";
  std::ofstream(file) << junit_xml(hostile);
  const int parsed = parse_with_python(file);
  if (parsed == -1) GTEST_SKIP() << "no python3 to parse the XML with";
  EXPECT_EQ(parsed, 0) << read_text(file);
  EXPECT_EQ(parse_with_python(dir_ / "junit.xml"), 0);
}

TEST_F(ReportTest, ResultsJsonParsesBackWithTheSameVerdicts) {
  const auto json = nlohmann::json::parse(read_text(dir_ / "results.json"));
  EXPECT_EQ(json["format"], "xshade-results-1");
  EXPECT_EQ(json["verdict"], "error");
  EXPECT_EQ(json["exit_code"], 2);
  EXPECT_EQ(json["command"], results_.command);
  EXPECT_EQ(json["scene_counts"]["fail"], 1);
  EXPECT_EQ(json["check_counts"]["total"], 8);
  ASSERT_EQ(json["scenes"].size(), results_.scenes.size());
  for (size_t i = 0; i < results_.scenes.size(); ++i) {
    const SceneResult& scene = results_.scenes[i];
    const auto& scene_json = json["scenes"][i];
    EXPECT_EQ(scene_json["scene"], scene.scene);
    EXPECT_EQ(scene_json["verdict"], std::string(verdict_name(scene.verdict)));
    EXPECT_EQ(scene_json["message"], scene.message);
    ASSERT_EQ(scene_json["lanes"].size(), scene.lanes.size());
    for (size_t l = 0; l < scene.lanes.size(); ++l) {
      EXPECT_EQ(scene_json["lanes"][l]["lane"], scene.lanes[l].lane);
      EXPECT_EQ(scene_json["lanes"][l]["verdict"], std::string(verdict_name(scene.lanes[l].verdict)));
    }
  }
  const auto& vk = json["scenes"][1]["lanes"][1];
  EXPECT_EQ(vk["first_failure"], "finite: 3 NaN at (4, 7) first");
  EXPECT_EQ(vk["layers"][1]["layer"], "per_pixel");
  EXPECT_EQ(vk["against_golden"]["steps"]["failing_pixels"], 312);
  EXPECT_EQ(vk["against_golden"]["steps"]["worst"], 64);
  EXPECT_DOUBLE_EQ(vk["against_golden"]["steps"]["psnr"].get<double>(), 33.5);
  EXPECT_EQ(vk["non_finite"]["nan"], 3);
  EXPECT_EQ(vk["non_finite"]["first"]["y"], 7);
  EXPECT_EQ(vk["non_finite_mask"], "toon/vk.nonfinite.png");
  EXPECT_EQ(vk["driver"]["llvm_version"], "15.0.6");
  EXPECT_EQ(vk["timings"][0]["pass"], "main");
  // Identical images: an infinite PSNR, which JSON cannot hold.
  EXPECT_TRUE(json["scenes"][0]["lanes"][0]["against_golden"]["steps"]["psnr"].is_null());
  EXPECT_TRUE(json["scenes"][0]["lanes"][2]["against_golden"].is_null());
  EXPECT_EQ(json["scenes"][1]["cross_lane"][0]["verdict"], "fail");
}

TEST_F(ReportTest, ResultsJsonRepairsTextThatIsNotUtf8) {
  RunResults broken = sample_results();
  broken.scenes[2].message = std::string("bad \xFF byte");
  const auto json = nlohmann::json::parse(results_json(broken));
  EXPECT_EQ(json["scenes"][2]["message"], "bad \uFFFD byte");
}

// What report merge reads: every field comes back, and written again it is the same document.
TEST_F(ReportTest, ResultsJsonReadsBackWhole) {
  RunResults results = sample_results();
  results.scenes[1].compare.channel_tolerance = 3;
  results.scenes[1].compare.reason = "a soft edge";
  results.scenes[0].cross_lane[0].identical = true;
  results.scenes[0].compare.metric = MetricSettings{Metric::DeltaE, 0.25, 2.0, 0.01, 0.0};
  results.merged_from = {{"shard-1", "2024-05-01T10:20:30Z", 2.5, "xshade run --shard 1/2"}};
  const std::string written = results_json(results);
  auto read = results_from_json(written, "r/results.json");
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(results_json(*read), written);
  EXPECT_EQ(read->scenes[1].compare.channel_tolerance, 3u);
  ASSERT_TRUE(read->scenes[0].compare.metric);
  EXPECT_EQ(read->scenes[0].compare.metric->metric, Metric::DeltaE);
  EXPECT_EQ(read->scenes[0].compare.metric->incorrect_fraction, 0.01);
  EXPECT_FALSE(read->scenes[1].compare.metric);
  EXPECT_TRUE(read->scenes[0].cross_lane[0].identical);
  EXPECT_EQ(read->merged_from.at(0).command, "xshade run --shard 1/2");
  EXPECT_EQ(read->scenes[1].warnings, results.scenes[1].warnings);
}

TEST_F(ReportTest, ResultsJsonOfAnotherKindIsRefusedNamingTheFile) {
  for (const std::string& text : {std::string("not json"), std::string(R"({"format": "other"})"),
                                  std::string(R"({"format": "xshade-results-1", "started": "x"})")}) {
    auto read = results_from_json(text, "shard/results.json");
    ASSERT_FALSE(read) << text;
    EXPECT_EQ(read.error().kind, ErrorKind::UserInput);
    EXPECT_EQ(read.error().message.rfind("shard/results.json: not a results.json xshade wrote (", 0), 0u)
        << read.error().message;
  }
}

TEST(WriteReports, FailsAsAValueWhenTheFolderCannotBeMade) {
  const fs::path file = fs::temp_directory_path() / "xshade_report_test_not_a_folder";
  std::ofstream(file) << "a file where the folder would be";
  auto written = write_reports(sample_results(), file / "report");
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find("cannot create the report folder"), std::string::npos);
  EXPECT_EQ(written.error().kind, ErrorKind::Backend);  // the machine's, not the report's: exit 3
  fs::remove(file);
}

TEST(WriteReports, ReplacesAnEarlierReport) {
  const fs::path dir = fs::temp_directory_path() / "xshade_report_test_replace";
  fs::remove_all(dir);
  RunResults results = sample_results();
  ASSERT_TRUE(write_reports(results, dir));
  results.scenes.resize(1);
  ASSERT_TRUE(write_reports(results, dir));
  EXPECT_EQ(attribute(read_text(dir / "junit.xml"), "testsuites", "tests"), "4");
  fs::remove_all(dir);
}

// A merged report can name one image from thousands of scenes: its float values are written
// once, in a script of their own that every page showing the image loads.
TEST(WriteReports, WritesTheFloatValuesOfAnImageOnceHoweverManyPagesShowIt) {
  const fs::path dir = fs::temp_directory_path() / "xshade_report_test_shared_image";
  fs::remove_all(dir);
  FloatImage image(2, 1);
  image.rgba = {0.25f, 0.5f, 2.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  fs::create_directories(dir / "shared");
  ASSERT_TRUE(write_exr(image, dir / "shared" / "gl.exr"));
  RunResults results;
  for (const char* name : {"first", "second"}) {
    SceneResult scene;
    scene.scene = name;
    scene.verdict = Verdict::Pass;
    LaneResult lane;
    lane.lane = "gl";
    lane.verdict = Verdict::Pass;
    lane.image = "shared/gl.png";
    lane.image_exr = "shared/gl.exr";
    scene.lanes.push_back(lane);
    results.scenes.push_back(scene);
  }
  auto written = write_reports(results, dir);
  ASSERT_TRUE(written) << written.error().to_string();
  const std::string script = read_text(dir / "pixels" / "shared" / "gl.exr.js");
  EXPECT_EQ(occurrences(script, "(window.XSHADE_PIXELS = window.XSHADE_PIXELS || {})[\"shared/gl.exr\"] = "), 1u)
      << script.substr(0, 200);
  EXPECT_EQ(occurrences(script, "\n"), 1u);
  for (const char* page : {"first.html", "second.html"}) {
    const std::string text = read_text(dir / page);
    EXPECT_EQ(occurrences(text, "<script src=\"pixels/shared/gl.exr.js\"></script>"), 1u) << page;
    EXPECT_NE(text.find(R"("output":{"pixels":"shared/gl.exr","png":"shared/gl.png"})"), std::string::npos) << page;
  }
  size_t scripts = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "pixels")) scripts += entry.is_regular_file();
  EXPECT_EQ(scripts, 1u);
  // Encoded for the first page that shows it, and only named by the next.
  std::set<std::string> scripted;
  const ViewerPage first = viewer_page(results.scenes[0], dir, {}, &scripted);
  const ViewerPage second = viewer_page(results.scenes[1], dir, {}, &scripted);
  ASSERT_EQ(first.pixels.size(), 1u);
  ASSERT_EQ(second.pixels.size(), 1u);
  EXPECT_EQ(first.pixels[0].script, script);
  EXPECT_EQ(second.pixels[0].image, "shared/gl.exr");
  EXPECT_EQ(second.pixels[0].script, "");
  fs::remove_all(dir);
}

// xshade watch writes again only the scenes a save reached: the others' pages and pixel scripts
// stay as they are, listed as the report's (so never removed as stale), and the index is new.
TEST(WriteReports, ScenesWrittenAlreadyAreLeftAsTheyAre) {
  const fs::path dir = fs::temp_directory_path() / "xshade_report_test_written_already";
  fs::remove_all(dir);
  FloatImage image(2, 1);
  image.rgba = {0.25f, 0.5f, 0.75f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  RunResults results;
  for (const char* name : {"kept", "changed"}) {
    fs::create_directories(dir / name);
    ASSERT_TRUE(write_exr(image, dir / name / "gl.exr"));
    SceneResult scene;
    scene.scene = name;
    scene.verdict = Verdict::Pass;
    LaneResult lane;
    lane.lane = "gl";
    lane.verdict = Verdict::Pass;
    lane.image = std::string(name) + "/gl.png";
    lane.image_exr = std::string(name) + "/gl.exr";
    scene.lanes.push_back(lane);
    results.scenes.push_back(scene);
  }
  std::vector<ViewerPage> viewers;
  for (const SceneResult& scene : results.scenes) viewers.push_back(viewer_page(scene, dir));
  ASSERT_TRUE(write_reports(results, dir, &viewers));
  for (const char* file : {"kept.html", "changed.html", "pixels/kept/gl.exr.js", "pixels/changed/gl.exr.js"})
    std::ofstream(dir / file) << "as before";
  results.scenes[1].verdict = Verdict::Fail;
  const std::vector<bool> written_already = {true, false};
  ASSERT_TRUE(write_reports(results, dir, &viewers, &written_already));
  EXPECT_EQ(read_text(dir / "kept.html"), "as before");
  EXPECT_EQ(read_text(dir / "pixels/kept/gl.exr.js"), "as before");
  EXPECT_NE(read_text(dir / "changed.html"), "as before");
  EXPECT_NE(read_text(dir / "pixels/changed/gl.exr.js"), "as before");
  EXPECT_NE(read_text(dir / ".xshade-report-files").find("pixels/kept/gl.exr.js"), std::string::npos);
  EXPECT_NE(read_text(dir / "index.html").find("v-fail"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace xshade::harness
