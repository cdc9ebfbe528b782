// What one reading of the process's memory costs (rayview/process_memory.h): `rayview render` reads it four
// times a render, the viewer once for each pass it shows.
//   build/release/bench/process_memory_bench
#include <benchmark/benchmark.h>

#include "rayview/process_memory.h"

namespace {

void ProcessMemoryReading(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(rayview::processMemory());
}
BENCHMARK(ProcessMemoryReading);

}  // namespace

BENCHMARK_MAIN();
