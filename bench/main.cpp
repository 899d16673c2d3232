// One main for every Google Benchmark file in bench/.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
