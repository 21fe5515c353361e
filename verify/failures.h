// Collects failure messages: keeps the first few of each category (the text
// before the first ':'), so that one flood does not hide other kinds; counts all.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vismap_check {

class Failures {
 public:
  static constexpr std::size_t kPerCategory = 5;
  static constexpr std::size_t kKept = 25;
  void add(std::string msg) {
    ++count_;
    std::string cat = msg.substr(0, msg.find(':'));
    if (kept_.size() < kKept && per_category_[cat]++ < kPerCategory) kept_.push_back(std::move(msg));
  }
  std::size_t count() const { return count_; }
  // The kept messages, plus one line saying how many were left out.
  std::vector<std::string> messages() const {
    std::vector<std::string> out = kept_;
    if (count_ > kept_.size())
      out.push_back("... and " + std::to_string(count_ - kept_.size()) + " more failures");
    return out;
  }

 private:
  std::vector<std::string> kept_;
  std::map<std::string, std::size_t> per_category_;
  std::size_t count_ = 0;
};

}  // namespace vismap_check
