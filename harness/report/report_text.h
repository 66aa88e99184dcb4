// What every report format (HTML, JUnit XML, JSON) says the same way about a result, so that a
// reviewer reads the same words for the same failure wherever they look.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/gate/run_results.h"
#include "harness/scene/lane.h"

namespace xshade::harness {

struct VerdictCounts {
  size_t pass = 0;
  size_t fail = 0;
  size_t error = 0;
  size_t crash = 0;
  size_t skipped = 0;

  void add(Verdict verdict);
  size_t total() const { return pass + fail + error + crash + skipped; }
};

VerdictCounts count_scenes(const RunResults& results);
// Every lane and every cross-lane pair of every scene.
VerdictCounts count_checks(const RunResults& results);

// Fail, Error or Crash: what a reviewer has to look at.
bool is_problem(Verdict verdict);
// Crash, Error, Fail, Pass, Skipped: the order reports list scenes in, most urgent first.
int urgency(Verdict verdict);
// The worst verdict of the run: its scenes' worst, Pass for a run of no scenes.
Verdict run_verdict(const RunResults& results);

// Why a lane did not pass: "layer: detail" of the first layer that did not pass, else the lane's
// message; empty for a lane that passed.
std::string first_failure(const LaneResult& lane);
// "gl vs vk"
std::string pair_name(const CrossLaneResult& pair);  // "38.52 dB", or "identical" when the PSNR is infinite.
std::string describe_psnr(double psnr);
// "850 ms", "12.3 s" or "2 min 5.0 s".
std::string describe_duration(double seconds);

std::string_view first_line(std::string_view text);

// The head of a generated Markdown document (docs/stability.md, docs/accuracy.md): its title,
// the command that made it and the date, and each lane's driver.
std::string generated_markdown_head(std::string_view title, std::string_view command_line,
                                    const std::vector<std::pair<Lane, DriverInfo>>& drivers);

}  // namespace xshade::harness
