// Image comparison speed: a 512x512 comparison in the slowest case, every pixel failing and the
// position layer searching around each. Every scene x lane is compared against its golden and
// the other lanes, so this is paid many times per run. Then each perceptual metric
// (metric_layers.h) on the same images, whose time is to be read against the layers'.
//
//   build/tests/bench/compare_benchmark
#include <benchmark/benchmark.h>

#include "harness/image/image_compare.h"
#include "harness/image/metric_layers.h"

namespace {

// Two 512x512 gradients whose blue differs everywhere; `hdr` puts one channel above 1 so that
// FLIP runs its exposures.
std::pair<xshade::harness::FloatImage, xshade::harness::FloatImage> differing_pair(bool hdr = false) {
  xshade::harness::FloatImage reference(512, 512), test(512, 512);
  for (uint32_t y = 0; y < 512; ++y)
    for (uint32_t x = 0; x < 512; ++x) {
      const float red = hdr ? 4.0f * float(x) / 511.0f : float(x) / 511.0f;
      reference.set(x, y, {red, float(y) / 511.0f, 0.3f, 1.0f});
      test.set(x, y, {red, float(y) / 511.0f, 0.6f, 1.0f});
    }
  return {std::move(reference), std::move(test)};
}

void Metric512(benchmark::State& state, xshade::harness::Metric metric, bool hdr) {
  const auto [reference, test] = differing_pair(hdr);
  xshade::harness::MetricSettings settings;
  settings.metric = metric;
  for (auto _ : state) benchmark::DoNotOptimize(xshade::harness::run_metric(test, reference, settings));
}

BENCHMARK_CAPTURE(Metric512, flip_ldr, xshade::harness::Metric::Flip, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Metric512, flip_hdr, xshade::harness::Metric::Flip, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Metric512, ssim, xshade::harness::Metric::Ssim, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Metric512, deltae, xshade::harness::Metric::DeltaE, false)->Unit(benchmark::kMillisecond);

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
