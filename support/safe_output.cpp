#include "safe_output.hpp"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace safe_output {

namespace {

// A stream buffer over a file descriptor that keeps the first error: std::ofstream and stdio lose
// errno, and an ofstream's close is never checked by its destructor.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }
  void fail(int error) {
    if (!error_) error_ = error;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  // Writes the buffer out; after a failure the rest is dropped (the output is lost either way).
  bool drain() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && !error_) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      } else if (n == 0) {
        fail(EIO);
      } else {
        p += n;
        left -= static_cast<std::size_t>(n);
      }
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return !error_;
  }
  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

std::string reason(int error) { return std::strerror(error); }

bool is_regular_or_missing(const std::string& path, struct stat& st, bool& exists) {
  exists = ::stat(path.c_str(), &st) == 0;
  return !exists || S_ISREG(st.st_mode);
}

// The file a rename must replace: a symbolic link's target, so that the link stays a link.
std::string resolved(const std::string& path, bool exists) {
  if (!exists) return path;
  char buffer[PATH_MAX];
  return ::realpath(path.c_str(), buffer) ? std::string(buffer) : path;
}

// Creates the temporary file beside `target`; returns its descriptor (or -1 with errno set).
int create_temporary(const std::string& target, std::string& temporary, const struct stat* existing) {
  static unsigned counter = 0;
  const std::filesystem::path p(target);
  const std::string dir = p.has_parent_path() ? p.parent_path().string() + "/" : std::string();
  // Short enough for NAME_MAX when the target's own name is near it.
  const std::string name = p.filename().string().substr(0, 200);
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = dir + "." + name + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      if (existing) (void)::fchmod(fd, existing->st_mode & 07777);  // a replaced file keeps its permissions
      return fd;
    }
    if (errno != EEXIST) return -1;
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

struct OutputFile::Impl {
  int fd = -1;
  bool direct = false;   // a device or pipe: written in place
  bool existed = false;  // a regular file is replaced (else created)
  bool done = false;
  std::string target;     // what the rename replaces
  std::string temporary;  // empty when direct
  FdBuffer buffer;
  std::ostream out;
  explicit Impl(int descriptor) : fd(descriptor), buffer(descriptor), out(&buffer) {}
};

std::string refusal(const std::string& path) {
  struct stat st {};
  bool exists = false;
  if (!is_regular_or_missing(path, st, exists)) {
    if (S_ISDIR(st.st_mode)) return "is a directory";
    return ::access(path.c_str(), W_OK) == 0 ? std::string() : "cannot be written (" + reason(errno) + ")";
  }
  // A rename bypasses the file's own permissions: a read-only file is refused as it was before.
  if (exists && ::access(path.c_str(), W_OK) != 0) return "cannot be written (" + reason(errno) + ")";
  std::string temporary;
  const int fd = create_temporary(resolved(path, exists), temporary, nullptr);
  if (fd < 0) {
    const std::string why = reason(errno);
    const std::filesystem::path p(path);
    return "cannot create a file in " + (p.has_parent_path() ? p.parent_path().string() : std::string(".")) + " (" +
           why + ")";
  }
  ::close(fd);
  ::unlink(temporary.c_str());
  return {};
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  struct stat st {};
  bool exists = false;
  if (!is_regular_or_missing(path_, st, exists)) {
    if (S_ISDIR(st.st_mode)) throw WriteError(path_ + ": cannot be written (it is a directory)");
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw WriteError(path_ + ": cannot be opened for writing (" + reason(errno) + ")");
    impl_ = std::make_unique<Impl>(fd);
    impl_->direct = true;
    impl_->target = path_;
    return;
  }
  const std::string target = resolved(path_, exists);
  std::string temporary;
  const int fd = create_temporary(target, temporary, exists ? &st : nullptr);
  if (fd < 0) throw WriteError(path_ + ": cannot be written (" + reason(errno) + ")");
  impl_ = std::make_unique<Impl>(fd);
  impl_->existed = exists;
  impl_->target = target;
  impl_->temporary = temporary;
}

OutputFile::~OutputFile() { discard(); }

std::ostream& OutputFile::stream() { return impl_->out; }

void OutputFile::discard() noexcept {
  if (!impl_ || impl_->done) return;
  impl_->done = true;
  if (impl_->fd >= 0) ::close(impl_->fd);
  impl_->fd = -1;
  if (!impl_->temporary.empty()) ::unlink(impl_->temporary.c_str());
}

void OutputFile::commit() {
  Impl& f = *impl_;
  if (f.done) return;
  f.out.flush();
  if (f.buffer.pubsync() != 0 && !f.buffer.error()) f.buffer.fail(EIO);
  // The data on disk before the rename, or a crash could leave an empty file under the name.
  if (!f.direct && !f.buffer.error() && ::fsync(f.fd) != 0) f.buffer.fail(errno);
  if (::close(f.fd) != 0) f.buffer.fail(errno);
  f.fd = -1;
  int error = f.buffer.error();
  if (!error && !f.direct && ::rename(f.temporary.c_str(), f.target.c_str()) != 0) error = errno;
  if (!error) {
    f.done = true;
    return;
  }
  discard();
  throw WriteError(path_ + ": writing failed (" + reason(error) + "); " +
                   (f.direct ? std::string("the output is incomplete")
                             : f.existed ? std::string("the existing file is unchanged") : std::string("no file was created")));
}

void write_file(const std::string& path, std::string_view bytes) {
  OutputFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

namespace {
std::vector<std::unique_ptr<OutputFile>>& pending() {
  static std::vector<std::unique_ptr<OutputFile>> files;
  return files;
}
}  // namespace

OutputFile& open_pending(const std::string& path) {
  pending().push_back(std::make_unique<OutputFile>(path));
  return *pending().back();
}

void commit_pending() {
  try {
    for (auto& file : pending()) file->commit();
  } catch (...) {
    discard_pending();
    throw;
  }
  pending().clear();
}

void discard_pending() noexcept { pending().clear(); }

struct StandardOutput::Impl {
  FdBuffer buffer{STDOUT_FILENO};
  std::streambuf* previous = nullptr;
  bool finished = false;
};

StandardOutput::StandardOutput() : impl_(std::make_unique<Impl>()) {
  std::cout.flush();
  impl_->previous = std::cout.rdbuf(&impl_->buffer);
  // As stdio does for a terminal: lines appear as they are written, in order with standard error.
  if (::isatty(STDOUT_FILENO)) std::cout << std::unitbuf;
}

StandardOutput::~StandardOutput() {
  finish();
  std::cout.rdbuf(impl_->previous);
}

std::string StandardOutput::finish() {
  if (impl_->finished) return {};
  impl_->finished = true;
  std::cout.flush();
  if (impl_->buffer.pubsync() != 0 && !impl_->buffer.error()) impl_->buffer.fail(EIO);
  if (std::fflush(stdout) != 0) impl_->buffer.fail(errno);
  if (!impl_->buffer.error()) return {};
  return "standard output: writing failed (" + reason(impl_->buffer.error()) + "); the output is incomplete";
}

}  // namespace safe_output
