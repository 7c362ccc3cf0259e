#include "engine/surface/checked_export_io.h"

#include <unistd.h>
#include <assimp/IOStream.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace galsculpt {

class CheckedExportStream : public Assimp::IOStream {
 public:
  CheckedExportStream(CheckedExportIO& io, std::string file, std::FILE* f)
      : io_(io), file_(std::move(file)), f_(f) {}
  ~CheckedExportStream() override { finish(); }

  size_t Read(void* buffer, size_t size, size_t count) override {
    return std::fread(buffer, size, count, f_);
  }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    const size_t written = std::fwrite(buffer, size, count, f_);
    if (written != count) io_.fail(file_, errno);
    return written;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const int whence = origin == aiOrigin_SET   ? SEEK_SET
                       : origin == aiOrigin_CUR ? SEEK_CUR
                                                : SEEK_END;
    return std::fseek(f_, static_cast<long>(offset), whence) == 0 ? aiReturn_SUCCESS
                                                                  : aiReturn_FAILURE;
  }
  size_t Tell() const override { return static_cast<size_t>(std::ftell(f_)); }
  size_t FileSize() const override {
    const long at = std::ftell(f_);
    std::fseek(f_, 0, SEEK_END);
    const long size = std::ftell(f_);
    std::fseek(f_, at, SEEK_SET);
    return static_cast<size_t>(size);
  }
  void Flush() override {
    if (std::fflush(f_) != 0) io_.fail(file_, errno);
  }

  // Flushed and closed, each step checked.
  void finish() {
    if (!f_) return;
    if (std::fflush(f_) != 0) io_.fail(file_, errno);
    if (std::fclose(f_) != 0) io_.fail(file_, errno);
    f_ = nullptr;
  }

 private:
  CheckedExportIO& io_;
  std::string file_;
  std::FILE* f_;
};

bool CheckedExportIO::Exists(const char* file) const {
  return access(file, F_OK) == 0;
}

Assimp::IOStream* CheckedExportIO::Open(const char* file, const char* mode) {
  std::FILE* f = std::fopen(file, mode);
  if (!f) {
    fail(file, errno);
    return nullptr;
  }
  return new CheckedExportStream(*this, file, f);
}

void CheckedExportIO::Close(Assimp::IOStream* stream) {
  delete stream;  // finish() checks the last writes
}

void CheckedExportIO::fail(const std::string& file, int error) {
  // The file's own name: it is written in a temporary folder and renamed into place.
  if (failure_.empty())
    failure_ = std::filesystem::path(file).filename().string() + ": " +
               std::strerror(error != 0 ? error : EIO);
}

}  // namespace galsculpt
