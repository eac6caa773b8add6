// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace sadr::orchestrator {

namespace {

std::string os_error(const std::string& what, const std::filesystem::path& path) {
  return what + " '" + path.string() + "': " + std::strerror(errno);
}

/// Unique temporary name in the target's directory (pid + counter), hidden.
std::filesystem::path temporary_for(const std::filesystem::path& path) {
  static std::atomic<unsigned long> counter{0};
  std::string name(".");
  name.append(path.filename().string());
  name.append(".tmp.");
  name.append(std::to_string(static_cast<long>(::getpid())));
  name.push_back('.');
  name.append(std::to_string(counter.fetch_add(1)));
  return path.parent_path() / name;
}

void write_all(int fd, std::string_view bytes, const std::filesystem::path& tmp) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(os_error("cannot write", tmp));
    }
    done += static_cast<std::size_t>(n);
  }
}

void fsync_directory(const std::filesystem::path& dir) {
  const std::filesystem::path d = dir.empty() ? std::filesystem::path(".") : dir;
  const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError(os_error("cannot open directory", d));
  const int rc = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  // Some file systems do not support fsync on directories (EINVAL); the
  // rename is then as durable as they allow.
  if (rc != 0 && errno != EINVAL) throw IoError(os_error("cannot fsync directory", d));
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes,
                       const AtomicWriteFault* fault) {
  const std::filesystem::path tmp = temporary_for(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(os_error("cannot create", tmp));
  if (fault && fault->fail_after_bytes < bytes.size()) {
    // Simulated crash: part of the data reaches the temporary, which stays behind.
    try {
      write_all(fd, bytes.substr(0, fault->fail_after_bytes), tmp);
    } catch (...) {
      ::close(fd);
      throw;
    }
    ::close(fd);
    throw IoError("simulated crash after " + std::to_string(fault->fail_after_bytes) +
                  " bytes while writing '" + path.string() + "'");
  }
  try {
    write_all(fd, bytes, tmp);
    if (::fsync(fd) != 0) throw IoError(os_error("cannot fsync", tmp));
  } catch (...) {
    ::close(fd);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  if (::close(fd) != 0) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw IoError(os_error("cannot close", tmp));
  }
  if (fault && fault->fail_before_rename) {
    throw IoError("simulated crash before renaming onto '" + path.string() + "'");
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string msg = os_error("cannot rename onto", path);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw IoError(msg);
  }
  fsync_directory(path.parent_path());
}

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw IoError("cannot create directory '" + dir.string() + "': " + ec.message());
}

}  // namespace sadr::orchestrator
