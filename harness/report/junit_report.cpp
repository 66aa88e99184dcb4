#include "harness/report/junit_report.h"

#include <iterator>
#include <vector>

#include <fmt/format.h>

#include "base/markup.h"
#include "harness/report/report_text.h"

namespace xshade::harness {
namespace {

struct TestCase {
  std::string name;
  Verdict verdict = Verdict::Pass;
  double seconds = 0.0;
  std::string message;  // one line, for the attribute
  std::string text;     // everything a reviewer needs, for the element
};

std::string layers_text(const LaneResult& lane) {
  std::string text;
  for (const LayerResult& layer : lane.layers)
    text += fmt::format("{} {}: {}\n", layer.layer, verdict_name(layer.verdict), layer.detail);
  if (!lane.message.empty()) text += lane.message + "\n";
  return text;
}

std::vector<TestCase> test_cases(const SceneResult& scene) {
  std::vector<TestCase> cases;
  Verdict carried = Verdict::Skipped;
  for (const LaneResult& lane : scene.lanes) {
    cases.push_back(
        {lane.lane, lane.verdict, lane.seconds, std::string(first_line(first_failure(lane))), layers_text(lane)});
    carried = worst(carried, lane.verdict);
  }
  for (const CrossLaneResult& pair : scene.cross_lane) {
    const std::string metrics = describe_metrics(pair.metrics);
    cases.push_back({pair_name(pair), pair.verdict, 0.0, metrics, metrics + "\n"});
    carried = worst(carried, pair.verdict);
  }
  if (cases.empty() || urgency(scene.verdict) > urgency(carried)) {
    cases.push_back({"scene", scene.verdict, 0.0, std::string(first_line(scene.message)),
                     scene.message.empty() ? std::string() : scene.message + "\n"});
  }
  return cases;
}

struct Totals {
  size_t tests = 0, failures = 0, errors = 0, skipped = 0;
  double seconds = 0.0;

  void add(const TestCase& test) {
    ++tests;
    failures += test.verdict == Verdict::Fail;
    errors += test.verdict == Verdict::Error || test.verdict == Verdict::Crash;
    skipped += test.verdict == Verdict::Skipped;
    seconds += test.seconds;
  }
  std::string attributes() const {
    return fmt::format(R"(tests="{}" failures="{}" errors="{}" skipped="{}" time="{:.3f}")", tests, failures, errors,
                       skipped, seconds);
  }
};

void write_case(std::string& out, const std::string& scene, const TestCase& test) {
  auto to = std::back_inserter(out);
  fmt::format_to(to, R"(    <testcase classname="{}" name="{}" time="{:.3f}")", escape_attribute(scene),
                 escape_attribute(test.name), test.seconds);
  switch (test.verdict) {
    case Verdict::Pass: out += "/>\n"; return;
    case Verdict::Skipped:
      fmt::format_to(to, ">\n      <skipped message=\"{}\"/>\n    </testcase>\n", escape_attribute(test.message));
      return;
    case Verdict::Fail:
      fmt::format_to(to, ">\n      <failure message=\"{}\" type=\"fail\">{}</failure>\n    </testcase>\n",
                     escape_attribute(test.message), escape_text(test.text));
      return;
    case Verdict::Error:
    case Verdict::Crash:
      fmt::format_to(to, ">\n      <error message=\"{}\" type=\"{}\">{}</error>\n    </testcase>\n",
                     escape_attribute(test.message), verdict_name(test.verdict), escape_text(test.text));
      return;
  }
}

}  // namespace

std::string junit_xml(const RunResults& results) {
  std::string suites;
  Totals run;
  for (const SceneResult& scene : results.scenes) {
    const std::vector<TestCase> cases = test_cases(scene);
    Totals suite;
    for (const TestCase& test : cases) suite.add(test);
    for (const TestCase& test : cases) run.add(test);
    fmt::format_to(std::back_inserter(suites), "  <testsuite name=\"{}\" {} timestamp=\"{}\">\n",
                   escape_attribute(scene.scene), suite.attributes(), escape_attribute(results.started));
    for (const TestCase& test : cases) write_case(suites, scene.scene, test);
    suites += "  </testsuite>\n";
  }
  // The run's own duration, not the sum of its lanes': it includes loading and compiling.
  run.seconds = results.seconds;
  return fmt::format("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"xshade\" {}>\n{}</testsuites>\n",
                     run.attributes(), suites);
}

}  // namespace xshade::harness
