// gpilot-bench's main: Google Benchmark's, plus --version as every gpilot binary has it.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>

#include "service_cli.hpp"

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--version") == 0) {
      std::printf("gpilot-bench %s\n", gpilot::gpilot_version());
      return 0;
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
