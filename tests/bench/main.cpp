// One main for all benchmark files (each file only registers its benchmarks).
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
