#include "harness/gate/run_results.h"

namespace xshade::harness {

int exit_code(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass:
    case Verdict::Skipped: return 0;
    case Verdict::Fail: return 1;
    case Verdict::Error: return 2;
    case Verdict::Crash: return 3;
  }
  return 3;
}

// Skipped < Pass < Fail < Error < Crash: the exit code's order, with nothing run below a pass.
Verdict worst(Verdict a, Verdict b) {
  auto rank = [](Verdict v) {
    switch (v) {
      case Verdict::Skipped: return 0;
      case Verdict::Pass: return 1;
      case Verdict::Fail: return 2;
      case Verdict::Error: return 3;
      case Verdict::Crash: return 4;
    }
    return 4;
  };
  return rank(a) >= rank(b) ? a : b;
}

}  // namespace xshade::harness
