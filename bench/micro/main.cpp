// One main for every Google Benchmark file in bench/micro/.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
