// Image comparison speed: a 512x512 comparison in the slowest case, every pixel failing and the
// position layer searching around each. Every scene x lane is compared against its golden and
// the other lanes, so this is paid many times per run.
//
//   build/tests/bench/compare_benchmark
#include <benchmark/benchmark.h>

#include "harness/image/image_compare.h"

namespace {

void CompareWorstCase512(benchmark::State& state) {
  xshade::harness::FloatImage reference(512, 512), test(512, 512);
  for (uint32_t y = 0; y < 512; ++y)
    for (uint32_t x = 0; x < 512; ++x) {
      reference.set(x, y, {float(x) / 511.0f, float(y) / 511.0f, 0.3f, 1.0f});
      test.set(x, y, {float(x) / 511.0f, float(y) / 511.0f, 0.6f, 1.0f});
    }
  xshade::harness::CompareSettings settings;
  settings.channel_tolerance = 1;
  settings.position_radius = 1;
  for (auto _ : state) benchmark::DoNotOptimize(xshade::harness::compare_images(test, reference, settings));
}

BENCHMARK(CompareWorstCase512)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
