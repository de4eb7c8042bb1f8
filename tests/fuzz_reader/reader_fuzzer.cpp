// libFuzzer target for the language reader (issue 7 "Robust reader"). Built by the standalone
// CMake project in this folder with clang (see README.md and run.sh):
//
//   tests/fuzz_reader/run.sh 60        # build, then fuzz for 60 s from the corpus
//
// Inputs are read as one scene text named "fuzz.uq" in the working directory (run.sh runs it in
// a scratch directory holding two small files that `read` statements may reach, one of them a
// read cycle). Half of the inputs get an interactive-command handler. A violated property of
// reader_fuzz_check.h aborts, so libFuzzer saves the input; a crash or a hang is saved too.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "reader_fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Longer inputs only slow the search; the reader's behaviour on long inputs is covered by
    // the pathological cases of the ordinary suite.
    if (size > 1 << 16) return 0;
    std::string text(reinterpret_cast<const char*>(data), size);
    // Endless devices and kernel files are refused only after 256 MiB (regressions/
    // read_dev_zero.uq); the fuzzer gains nothing from reading them and would slow to a crawl.
    for (const char* dir : {"/dev", "/proc", "/sys"})
        if (text.find(dir) != std::string::npos) return 0;
    // `read -` reads standard input, which run.sh connects to /dev/null.
    bool withHandler = size > 0 && (data[0] & 1) != 0;
    std::string problem = quadrix::fuzz::CheckReaderInput(text, "fuzz.uq", withHandler);
    if (!problem.empty()) {
        std::fprintf(stderr, "reader property violated: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
