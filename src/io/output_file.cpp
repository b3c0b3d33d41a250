// nephele — output files: checks, atomic replacement, and temporary files removed on signals.
#include "nephele/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <optional>

#include "nephele/error.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& s) {
  std::string out = "'";
  out += shorten_path_for_message(s);
  return out += "'";
}

// The directory a file would be created in ("." for a bare file name).
fs::path directory_of(const fs::path& path) {
  const fs::path dir = path.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// The file a write to `path` replaces: the target of a link (which stays a link), else `path`.
fs::path write_target(const std::string& path) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path target = fs::canonical(path, ec);
    if (!ec) return target;
  }
  return path;
}

// The file at `path` (through links) as device and inode; nullopt where there is none.
std::optional<std::pair<dev_t, ino_t>> file_identity(const std::string& path) {
  struct stat st = {};
  if (path.empty() || path == kStandardOutput || ::stat(path.c_str(), &st) != 0) return std::nullopt;
  return std::pair{st.st_dev, st.st_ino};
}

// --- temporary files, known to the signal handler ---------------------------------------

// Paths of the temporary files being written, for remove_temporary_files() to read from a
// signal handler: fixed storage; a slot is claimed, its path written, then published.
enum SlotState : int { kFree, kClaimed, kPublished };
struct TempSlot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX] = {};
};
static_assert(std::atomic<int>::is_always_lock_free);
constexpr int kTempSlots = 16;
TempSlot g_temp_slots[kTempSlots];

[[noreturn]] void throw_io_error(const std::string& path, const std::string& what, int err) {
  throw RuntimeError("cannot write " + quoted(path) + ": " + what + ": " + std::strerror(err));
}

// A new temporary file in a folder (".nephele-<pid>-<n>.tmp": short, whatever the target's
// name), open for writing, mode 0666 before the umask as for any file created. It is listed
// for the signal handler before it is created, and removed unless released (after a
// successful rename).
class TempFile {
 public:
  TempFile(const fs::path& dir, const std::string& target) {
    static std::atomic<unsigned> counter{0};
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
      path_ = (dir / (".nephele-" + std::to_string(::getpid()) + "-" +
                      std::to_string(counter++) + ".tmp"))
                  .string();
      list();
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd_ >= 0) break;
      const int err = errno;
      unlist();
      if (err != EEXIST)
        throw_io_error(target, "cannot create a file in " + quoted(dir.string()), err);
    }
    if (fd_ < 0) throw_io_error(target, "cannot create a file in " + quoted(dir.string()), EEXIST);
  }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!path_.empty()) ::unlink(path_.c_str());
    unlist();
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  int fd() const { return fd_; }
  const std::string& path() const { return path_; }
  // Closes the file, reporting the error close() may be the first to see.
  int close() {
    const int result = ::close(fd_);
    fd_ = -1;
    return result;
  }
  void release() {
    unlist();
    path_.clear();
  }

 private:
  void list() {
    for (int i = 0; i < kTempSlots && path_.size() < PATH_MAX; ++i) {
      int expected = kFree;
      if (!g_temp_slots[i].state.compare_exchange_strong(expected, kClaimed)) continue;
      std::memcpy(g_temp_slots[i].path, path_.c_str(), path_.size() + 1);
      g_temp_slots[i].state.store(kPublished, std::memory_order_release);
      slot_ = i;
      return;
    }
  }
  void unlist() {
    if (slot_ >= 0) g_temp_slots[slot_].state.store(kFree, std::memory_order_release);
    slot_ = -1;
  }
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;
};

void write_all(int fd, std::string_view bytes, const std::string& path) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_io_error(path, "write failed", errno);
    if (n == 0) throw_io_error(path, "write failed", ENOSPC);
    done += size_t(n);
  }
}

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  remove_temporary_files();
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

void check_output_file(const std::string& path, const std::string& parameter, bool allow_stdout) {
  if (allow_stdout && path == kStandardOutput) return;
  const std::string prefix = parameter + " " + quoted(path) + ": ";
  if (path.empty()) throw InputError(parameter + " '': must name a file");
  if (path.size() >= PATH_MAX)
    throw InputError(prefix + "the path is " + std::to_string(path.size()) +
                     " characters long; the system allows " + std::to_string(PATH_MAX - 1));
  std::error_code ec;
  const fs::path target = write_target(path);
  const fs::file_status status = fs::status(target, ec);
  if (fs::is_directory(status)) throw InputError(prefix + "is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw InputError(prefix + "is not a regular file (a device, a pipe or a socket): only " +
                     (allow_stdout ? "regular files, or - for standard output," : "regular files") +
                     " are written");
  const fs::path dir = directory_of(target);
  if (!fs::exists(dir, ec))
    throw InputError(prefix + "directory " + quoted(dir.string()) + " does not exist");
  if (!fs::is_directory(dir, ec)) throw InputError(prefix + quoted(dir.string()) + " is not a directory");
  const long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  const size_t name_length = target.filename().string().size();
  if (name_length > size_t(name_max > 0 ? name_max : NAME_MAX))
    throw InputError(prefix + "the file name is " + std::to_string(name_length) +
                     " characters long; the file system allows " +
                     std::to_string(name_max > 0 ? name_max : NAME_MAX));
  // Creating the temporary file and renaming it needs write and search permission. A file
  // created and removed at once proves it where permissions alone do not (root ignores them;
  // /proc, /sys and read-only mounts refuse new files whatever they say).
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(prefix + "directory " + quoted(dir.string()) + " is not writable");
  try {
    TempFile probe(dir, path);
  } catch (const RuntimeError& e) {
    const std::string why(e.what());
    throw InputError(prefix + "directory " + quoted(dir.string()) + " does not accept new files (" +
                     why.substr(why.rfind(": ") + 2) + "; a writable directory is required)");
  }
}

void check_distinct_outputs(const NamedPaths& outputs) {
  std::vector<fs::path> seen;
  for (size_t o = 0; o < outputs.size(); ++o) {
    const auto& [parameter, path] = outputs[o];
    if (path == kStandardOutput) {
      seen.emplace_back();
      continue;
    }
    std::error_code ec;
    fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) resolved = fs::absolute(path, ec).lexically_normal();
    const auto identity = file_identity(path);
    for (size_t i = 0; i < seen.size(); ++i)
      if (!seen[i].empty() &&
          (seen[i] == resolved || (identity && identity == file_identity(outputs[i].second))))
        throw InputError(parameter + " " + quoted(path) + ": is the same file as " +
                         outputs[i].first + " (each output needs a file of its own)");
    seen.push_back(resolved);
  }
}

void check_outputs_not_inputs(const NamedPaths& outputs, const NamedPaths& inputs) {
  std::vector<std::pair<std::string, std::pair<dev_t, ino_t>>> read;
  for (const auto& [parameter, path] : inputs)
    if (const auto identity = file_identity(path)) read.emplace_back(parameter, *identity);
  for (const auto& [parameter, path] : outputs) {
    const auto identity = file_identity(path);
    if (!identity) continue;
    for (const auto& [input, input_identity] : read)
      if (input_identity == *identity)
        throw InputError(parameter + " " + quoted(path) + ": is the same file as the input " +
                         input + " (an output may not replace a file the work reads)");
  }
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  const fs::path target = write_target(path);
  TempFile temp(directory_of(target), path);
  write_all(temp.fd(), bytes, path);
  if (temp.close() != 0) throw_io_error(path, "write failed", errno);
  if (::rename(temp.path().c_str(), target.c_str()) != 0)
    throw_io_error(path, "cannot replace the file", errno);
  temp.release();
}

void install_temporary_file_cleanup() {
  struct sigaction action = {};
  action.sa_handler = remove_temporaries_and_reraise;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
}

void remove_temporary_files() noexcept {
  for (TempSlot& slot : g_temp_slots)
    if (slot.state.load(std::memory_order_acquire) == kPublished) ::unlink(slot.path);
}

}  // namespace nephele
