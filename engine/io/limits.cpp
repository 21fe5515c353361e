// Memory limits: the estimate of what a scene needs, the default limit (from
// physical memory, cgroups and RLIMIT_AS), and sizes as text.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "engine/scene.h"

namespace vismap {
namespace {

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

// a*b + c, saturating at kMax (header counts can be anything).
std::uint64_t mul_add(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  if (b != 0 && a > (kMax - c) / b) return kMax;
  return a * b + c;
}

// The first number in a file such as /sys/fs/cgroup/memory.max; kMax if none.
std::uint64_t read_limit_file(const char* path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max") return kMax;
  std::uint64_t v = 0;
  for (char ch : word) {
    if (ch < '0' || ch > '9') return kMax;
    v = mul_add(v, 10, static_cast<std::uint64_t>(ch - '0'));
  }
  return v == 0 ? kMax : v;
}

}  // namespace

std::uint64_t estimate_memory(std::uint64_t file_bytes, std::uint64_t vertices, std::uint64_t faces,
                              std::uint64_t corners) {
  std::uint64_t need = mul_add(1, file_bytes, MemoryModel::kBase);
  need = mul_add(vertices, MemoryModel::kPerVertex, need);
  need = mul_add(faces, MemoryModel::kPerFace, need);
  need = mul_add(corners, MemoryModel::kPerCorner, need);
  return need;
}

std::uint64_t default_max_memory() {
  std::uint64_t limit = kMax;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) limit = mul_add(static_cast<std::uint64_t>(pages), static_cast<std::uint64_t>(page), 0);
  limit = std::min(limit, read_limit_file("/sys/fs/cgroup/memory.max"));                    // cgroup v2
  limit = std::min(limit, read_limit_file("/sys/fs/cgroup/memory/memory.limit_in_bytes"));  // cgroup v1
  rlimit as{};
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    limit = std::min<std::uint64_t>(limit, as.rlim_cur);
  return limit == kMax ? 0 : limit;
}

bool parse_memory_size(std::string_view text, std::uint64_t& bytes) {
  std::size_t i = 0;
  double value = 0, scale = 1;
  bool digits = false, point = false;
  for (; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch >= '0' && ch <= '9') {
      digits = true;
      if (point) scale /= 10;
      value = value * 10 + (ch - '0');
    } else if (ch == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!digits) return false;
  value *= scale;
  std::string_view unit = text.substr(i);
  double mult = 1;
  if (!unit.empty()) {
    switch (unit[0]) {
      case 'k': case 'K': mult = 1024.0; break;
      case 'm': case 'M': mult = 1024.0 * 1024; break;
      case 'g': case 'G': mult = 1024.0 * 1024 * 1024; break;
      case 't': case 'T': mult = 1024.0 * 1024 * 1024 * 1024; break;
      case 'b': case 'B': mult = 1; unit = unit.substr(1); break;
      default: return false;
    }
    if (mult != 1) {
      unit = unit.substr(1);
      if (unit == "iB" || unit == "ib" || unit == "B" || unit == "b") unit = {};
    }
    if (!unit.empty()) return false;
  }
  const double b = std::floor(value * mult);
  if (!(b >= 1) || b >= 1.8e19) return false;
  bytes = static_cast<std::uint64_t>(b);
  return true;
}

std::string format_bytes(std::uint64_t bytes) {
  static const char* const kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  double v = static_cast<double>(bytes) / 1024;
  int u = 0;
  while (v >= 1024 && u < 5) {
    v /= 1024;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, kUnits[u]);
  return buf;
}

}  // namespace vismap
