// Output files are written whole or not at all: each to a temporary name in
// its own folder (".NAME.tmp-XXXXXX"), flushed to disk, and renamed over the
// target only when every output of the run is complete. A failure, or SIGINT,
// SIGTERM, SIGHUP or SIGQUIT during the run, leaves the old files as they were
// and no temporary behind. "-" means standard output.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vismap {

// Makes SIGINT, SIGTERM, SIGHUP and SIGQUIT remove the temporaries in flight
// before the process dies of the signal as it would have. Call once, early.
void install_output_cleanup_handlers();

// Writes every (path, contents): all temporaries first, then all renames, so
// that one that cannot be written leaves every target untouched. Throws
// std::runtime_error naming the file when one cannot be written.
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files);

// One file.
void write_file_atomically(const std::string& path, const std::string& contents);

// An output whose bytes are produced in pieces: render(write) calls write on
// each piece in order (a GB of JSON need not be held whole). A piece is taken
// by value: one handed over with std::move is never copied (tens of MB of JSON
// go to the file as they are). write may be called from any thread, one call at
// a time (write_json's threads hand over their pieces themselves).
struct StreamedOutput {
  std::string path;
  std::function<void(const std::function<void(std::string)>& write)> render;
};
// As write_files_atomically: every temporary written whole first, then all renamed;
// standard output ("-") gets its bytes last, once every file is in place.
void write_outputs_atomically(const std::vector<StreamedOutput>& outputs);

// A temporary being written, for tests and callers that stream: created next
// to `path`, removed on destruction unless commit() renamed it over `path`.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);   // throws std::runtime_error
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(const std::string& bytes);           // throws std::runtime_error
  void finish();                                  // flush to disk and close; throws
  void commit();                                  // finish() if needed, then rename; throws
  const std::string& temp_path() const { return tmp_; }

 private:
  void discard() noexcept;
  std::string path_, tmp_;
  int fd_ = -1;
  int slot_ = -1;
  static constexpr std::size_t kFlushStep = std::size_t{8} << 20;
  std::size_t written_ = 0, flushing_ = 0;   // bytes written; of those, sent to the disk
  bool committed_ = false;
};

}  // namespace vismap
