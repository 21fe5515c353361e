// Helpers the test programs share: a whole file as a string, the case lists
// (tests/data/cases.txt, tests/fuzz/*/cases.txt: one case per line, "#" starts a
// comment line, fields separated by tabs), and the checker's verdict as a test
// expectation.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "verify/checker.h"

namespace vismap_test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The non-empty, non-comment lines of a case list.
inline std::vector<std::string> case_lines(const std::filesystem::path& list) {
  std::vector<std::string> lines;
  std::ifstream in(list);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  return lines;
}

// A case line's first field (a scene file) and the rest after its tab.
struct Case {
  std::string file, args;
};
inline Case split_case(const std::string& line) {
  const auto tab = line.find('\t');
  return {line.substr(0, tab), tab == std::string::npos ? "" : line.substr(tab + 1)};
}

// A test's name for a case line: the scene file's stem, and the line's number in
// the list (a scene may appear with several views).
inline std::string case_name(const std::string& file, std::size_t index) {
  std::string n = file.substr(0, file.find('.'));
  for (char& ch : n)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n + "_" + std::to_string(index);
}

// The independent checker accepts `json` as the map of `scene`, having sampled it.
inline void expect_checked(const vismap::Scene& scene, const std::string& json, const vismap_check::Options& opt,
                           const std::string& what) {
  const vismap_check::Report r = vismap_check::check_map(scene, json, opt);
  std::string text;
  for (const auto& f : r.failures) text += "  " + f + "\n";
  EXPECT_TRUE(r.ok) << what << ":\n" << text;
  EXPECT_GT(r.samples_checked, 0u) << what;
}

}  // namespace vismap_test
