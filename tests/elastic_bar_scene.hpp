// The V1 elastic bar (Ma 2005, §2.3.1; examples/elastic_bar/mpm.toml without its output keys)
// as scene text, for tests that write it to a file (header only; not a test file itself).
#pragma once

#include <string>

namespace afemp::test {

inline constexpr const char* elastic_bar_scene = R"(
[run]
end_time = 0.02
[grid]
cell = 1.0
min = [0, 0, 0]
max = [4, 4, 16]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "wall" }
[materials.copper]
density = 8.9e-3
E = 1.0e5
nu = 0.3
[[bodies]]
name = "bar"
material = "copper"
shape = { cylinder = { base = [0, 0, 0.5], axis = [0, 0, 1], radius = 2.0, length = 10.0 } }
velocity = [0, 0, -300]
)";

// A study file's head for that bar, on 1 thread: the [study] table with `title`, and a
// "rebound" metric (the bar's mean z velocity against Ma 2005's 300 m/s, tolerance 0.1);
// the caller appends its [[runs]] (with `scene = "bar.toml"`).
inline std::string elastic_bar_study(const std::string& title) {
  return "\n[study]\ntitle = \"" + title +
         "\"\nthreads = 1\n\n"
         "[[metrics]]\nkind = \"velocity\"\nname = \"rebound\"\nbody = \"bar\"\n"
         "component = \"z\"\nreference = 300\ntolerance = 0.1\n";
}

}  // namespace afemp::test
