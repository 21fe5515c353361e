#include "arrangements/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace vismap {
namespace {

// Temporaries in flight, where a signal handler can see them: fixed slots of
// plain chars (no allocation in the handler, only unlink). Threads writing
// side by side (vismap --views) each claim a slot first, then fill it, then
// show it to the handler (used).
constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<bool> claimed{false}, used{false};
  char path[kPathMax];
};
Slot g_slots[kSlots];

const int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

extern "C" void on_fatal_signal(int sig) {
  const int saved = errno;
  for (Slot& s : g_slots) {
    if (s.used.load(std::memory_order_acquire)) ::unlink(s.path);
  }
  errno = saved;
  // Die of the same signal, as the default action would have.
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// Blocks the cleanup signals for a scope: a temporary is created and registered
// (or unregistered and renamed) as one step.
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    ::sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockSignals() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

int register_temp(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    Slot& s = g_slots[i];
    bool free = false;
    if (s.claimed.compare_exchange_strong(free, true, std::memory_order_acquire)) {
      std::memcpy(s.path, path.c_str(), path.size() + 1);
      s.used.store(true, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temp(int slot) {
  if (slot < 0) return;
  g_slots[slot].used.store(false, std::memory_order_release);
  g_slots[slot].claimed.store(false, std::memory_order_release);
}

mode_t creation_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

[[noreturn]] void cannot_write(const std::string& path, int err) {
  throw std::runtime_error(path + ": cannot write: " + std::strerror(err));
}

}  // namespace

void install_output_cleanup_handlers() {
  struct sigaction sa{};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : kSignals) sigaddset(&sa.sa_mask, s);
  sa.sa_flags = 0;
  for (int s : kSignals) {
    struct sigaction old{};
    // Keep a signal ignored if it was (e.g. SIGHUP under nohup).
    if (::sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(s, &sa, nullptr);
  }
}

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw std::runtime_error(path + ": cannot write: is a directory");
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::string tmpl = (dir / ("." + p.filename().string() + ".tmp-XXXXXX")).string();
  {
    BlockSignals block;
    fd_ = ::mkstemp(tmpl.data());
    if (fd_ < 0) cannot_write(path, errno);
    tmp_ = tmpl;
    slot_ = register_temp(tmp_);
  }
  if (slot_ < 0) {
    discard();
    throw std::runtime_error(path + ": cannot write: too many outputs at once, or the path is too long");
  }
  // mkstemp makes 0600; give the file what a plain open would have.
  ::fchmod(fd_, creation_mode());
}

AtomicFile::~AtomicFile() {
  if (!committed_) discard();
}

void AtomicFile::discard() noexcept {
  BlockSignals block;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
  unregister_temp(slot_);
  slot_ = -1;
  tmp_.clear();
}

void AtomicFile::write(const std::string& bytes) {
  if (fd_ < 0) throw std::logic_error("AtomicFile::write after finish");
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      cannot_write(path_, errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  written_ += bytes.size();
#ifdef __linux__
  // Starts the disk write of what has piled up, without waiting for it: the
  // flush at the end (fsync) then waits for the last pieces only.
  if (written_ - flushing_ >= kFlushStep) {
    ::sync_file_range(fd_, static_cast<off_t>(flushing_), static_cast<off_t>(written_ - flushing_), SYNC_FILE_RANGE_WRITE);
    flushing_ = written_;
  }
#endif
}

void AtomicFile::finish() {
  if (fd_ < 0) return;
  const bool synced = ::fsync(fd_) == 0 || errno == EINVAL || errno == EROFS;
  const int err = errno;
  const bool closed = ::close(fd_) == 0;
  fd_ = -1;
  if (!synced) cannot_write(path_, err);
  if (!closed) cannot_write(path_, errno);
}

void AtomicFile::commit() {
  finish();
  BlockSignals block;
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) cannot_write(path_, errno);
  committed_ = true;
  unregister_temp(slot_);
  slot_ = -1;
}

void write_outputs_atomically(const std::vector<StreamedOutput>& outputs) {
  std::vector<std::unique_ptr<AtomicFile>> pending;
  std::vector<std::string> to_stdout;
  for (const StreamedOutput& o : outputs) {
    if (o.path == "-") {
      std::string& all = to_stdout.emplace_back();
      o.render([&](std::string piece) { all += piece; });
      continue;
    }
    pending.push_back(std::make_unique<AtomicFile>(o.path));
    AtomicFile& f = *pending.back();
    o.render([&](std::string piece) { f.write(piece); });
    f.finish();
  }
  {
    // All renamed or none: a signal between two renames would leave a new file
    // beside an old one. (Blocked, it is taken when the last rename is done.)
    BlockSignals block;
    for (auto& f : pending) f->commit();
  }
  for (const std::string& contents : to_stdout) {
    if (std::fwrite(contents.data(), 1, contents.size(), stdout) != contents.size() || std::fflush(stdout) != 0)
      throw std::runtime_error(std::string("-: cannot write to standard output: ") + std::strerror(errno));
  }
}

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<StreamedOutput> outputs;
  for (const auto& [path, contents] : files)
    outputs.push_back({path, [&contents = contents](const auto& write) { write(contents); }});
  write_outputs_atomically(outputs);
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  write_files_atomically({{path, contents}});
}

}  // namespace vismap
