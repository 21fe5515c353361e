// Runs a program as a child process for the command-line tests: arguments
// without a shell, standard input from a file (or nothing), standard output
// and error captured, resource limits set in the child, and what the child
// spent (CPU time, peak memory) measured with wait4/getrusage.
#pragma once
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"   // slurp

#if defined(__SANITIZE_ADDRESS__)
#define VISMAP_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VISMAP_TEST_ASAN 1
#endif
#endif

namespace vismap_test {

// Under AddressSanitizer a process reserves terabytes of address space and uses
// more memory: no RLIMIT_AS there, and looser memory bounds.
#ifdef VISMAP_TEST_ASAN
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif

struct Limits {
  std::uint64_t address_space = 0;   // RLIMIT_AS in bytes (0: none; never under ASan)
  std::uint64_t cpu_seconds = 0;     // RLIMIT_CPU (0: none)
  double kill_after_seconds = 0;     // wall-clock: SIGKILL after this (0: never)
};

struct Result {
  bool exited = false;       // false: killed by a signal
  int status = -1;           // exit status, or the signal number
  std::string out, err;
  double cpu_seconds = 0;    // user + system
  std::uint64_t max_rss = 0; // bytes
  long minor_faults = 0;     // page faults served without I/O (fresh memory, mostly)
};

// Starts `argv` and returns its pid; stdin from `in` ("" = /dev/null), stdout
// and stderr to the given files.
inline pid_t start(const std::vector<std::string>& argv, const std::string& in, const std::string& out_file,
                   const std::string& err_file, const Limits& lim = {}) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  const int i = ::open(in.empty() ? "/dev/null" : in.c_str(), O_RDONLY);
  const int o = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int e = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (i < 0 || o < 0 || e < 0) ::_exit(126);
  ::dup2(i, 0);
  ::dup2(o, 1);
  ::dup2(e, 2);
  if (lim.address_space != 0 && !kAsan) {
    rlimit r{lim.address_space, lim.address_space};
    ::setrlimit(RLIMIT_AS, &r);
  }
  if (lim.cpu_seconds != 0) {
    rlimit r{lim.cpu_seconds, lim.cpu_seconds + 1};
    ::setrlimit(RLIMIT_CPU, &r);
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  ::execv(args[0], args.data());
  ::_exit(127);
}

// Waits for `pid`, measuring it.
inline Result finish(pid_t pid, const std::string& out_file, const std::string& err_file, const Limits& lim = {}) {
  Result r;
  int status = 0;
  rusage ru{};
  if (lim.kill_after_seconds > 0) {
    const int steps = static_cast<int>(lim.kill_after_seconds * 100);
    bool done = false;
    for (int k = 0; k < steps && !done; ++k) {
      done = ::wait4(pid, &status, WNOHANG, &ru) == pid;
      if (!done) ::usleep(10'000);
    }
    if (!done) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &ru);
    }
  } else {
    ::wait4(pid, &status, 0, &ru);
  }
  r.exited = WIFEXITED(status);
  r.status = r.exited ? WEXITSTATUS(status) : WTERMSIG(status);
  r.cpu_seconds = ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  r.max_rss = static_cast<std::uint64_t>(ru.ru_maxrss) * 1024;
  r.minor_faults = ru.ru_minflt;
  r.out = slurp(out_file);
  r.err = slurp(err_file);
  return r;
}

// Runs `argv` to the end; its output goes through files in `scratch`.
inline Result run(const std::vector<std::string>& argv, const std::filesystem::path& scratch,
                  const std::string& in = "", const Limits& lim = {}) {
  const std::string o = (scratch / "child.stdout").string(), e = (scratch / "child.stderr").string();
  return finish(start(argv, in, o, e, lim), o, e, lim);
}

// A fresh empty folder under the temporary directory, removed at the end.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = std::filesystem::temp_directory_path() / ("vismap_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path_ / name, std::ios::binary) << bytes;
    return file(name);
  }
  // Names in the folder, sorted (the scratch files of run() excluded).
  std::vector<std::string> names() const {
    std::vector<std::string> v;
    for (const auto& e : std::filesystem::directory_iterator(path_)) {
      const std::string n = e.path().filename().string();
      if (n != "child.stdout" && n != "child.stderr") v.push_back(n);
    }
    std::sort(v.begin(), v.end());
    return v;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace vismap_test
