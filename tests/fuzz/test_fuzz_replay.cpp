// The short fuzz run of the default tests: every corpus input of every target
// (tests/fuzz/corpus), then deterministic mutations of them (byte flips and insertions, cut and
// duplicated lines, numbers replaced by extreme ones, splices of two inputs), fed to the parsers
// (fuzz_targets.hpp). Reference: a parser accepts an input or refuses it with core::InputError;
// no other exception, and no input takes longer than 2 s (a hang). The long run is libFuzzer's
// under label `fuzz` (tests/CMakeLists.txt, AFEMP_FUZZ).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/fuzz_targets.hpp"

namespace afemp::fuzz {
namespace {

std::vector<std::string> corpus(Target t) {
  std::vector<std::string> out;
  const std::filesystem::path dir =
      std::filesystem::path(AFEMP_SOURCE_DIR) / "tests/fuzz/corpus" / name(t);
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    out.push_back(s.str());
  }
  return out;
}

// xorshift64*: the same mutations on every machine.
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 2685821657736338717ull;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
};

std::string mutate(const std::vector<std::string>& seeds, Random& r) {
  std::string s = seeds[r.below(seeds.size())];
  static const char* numbers[] = {
      "0",          "-1", "1e308", "-1e308", "nan",       "inf", "1e-308", "99999999999999999999",
      "2147483648", "-0", "0x10",  "1e12",   "4294967296"};
  static const char* bytes = "\n\t ,=[]{}\"'#*$.-+eE0123456789xyz";
  const int edits = 1 + static_cast<int>(r.below(4));
  for (int k = 0; k < edits; ++k) {
    const std::size_t at = r.below(s.size() + 1);
    switch (r.below(7)) {
      case 0:  // flip a byte
        if (!s.empty()) s[r.below(s.size())] ^= static_cast<char>(1u << r.below(8));
        break;
      case 1:  // insert a byte that means something to the formats
        s.insert(at, 1, bytes[r.below(std::char_traits<char>::length(bytes))]);
        break;
      case 2:  // cut a range
        s.erase(at, r.below(64));
        break;
      case 3: {  // duplicate a line
        const std::size_t b = s.rfind('\n', at == 0 ? 0 : at - 1), e = s.find('\n', at);
        const std::size_t from = b == std::string::npos ? 0 : b + 1;
        s.insert(from, s.substr(from, (e == std::string::npos ? s.size() : e + 1) - from));
        break;
      }
      case 4: {  // a number replaced by an extreme one
        std::size_t p = s.find_first_of("0123456789", at);
        if (p == std::string::npos) break;
        std::size_t e = s.find_first_not_of("0123456789.eE+-d", p);
        s.replace(p, (e == std::string::npos ? s.size() : e) - p, numbers[r.below(13)]);
        break;
      }
      case 5: {  // splice in part of another input
        const std::string& o = seeds[r.below(seeds.size())];
        const std::size_t from = r.below(o.size() + 1);
        s.insert(at, o.substr(from, r.below(256)));
        break;
      }
      case 6:  // truncate
        s.resize(at);
        break;
    }
  }
  if (s.size() > 65536) s.resize(65536);
  return s;
}

// Reference: each input is accepted or refused with InputError (feed returns), in under 2 s.
TEST(Fuzz, EveryParserAcceptsOrRefusesCorpusAndMutatedInputs) {
  constexpr int kMutations = 20000;  // per target
  long runs = 0;
  for (Target t : targets) {
    const std::vector<std::string> seeds = corpus(t);
    ASSERT_FALSE(seeds.empty()) << name(t);
    Random r{0x9e3779b97f4a7c15ull ^ static_cast<std::uint64_t>(t)};
    double slowest = 0.0;
    for (int k = -static_cast<int>(seeds.size()); k < kMutations; ++k) {
      const std::string input =
          k < 0 ? seeds[static_cast<std::size_t>(k + static_cast<int>(seeds.size()))]
                : mutate(seeds, r);
      const auto start = std::chrono::steady_clock::now();
      try {
        feed(t, input);
      } catch (const std::exception& e) {
        ADD_FAILURE() << name(t) << " input " << k << " threw " << e.what() << "\n--- input ---\n"
                      << input.substr(0, 2000);
        return;
      }
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      slowest = std::max(slowest, s);
      EXPECT_LT(s, 2.0) << name(t) << " input " << k << "\n--- input ---\n"
                        << input.substr(0, 2000);
      ++runs;
    }
    std::printf("fuzz %s: %zu corpus inputs and %d mutations, slowest %.3f s\n", name(t),
                seeds.size(), kMutations, slowest);
  }
  EXPECT_GT(runs, 120000);
}

}  // namespace
}  // namespace afemp::fuzz
