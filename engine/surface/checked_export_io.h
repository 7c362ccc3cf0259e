// The file access assimp's exporters write through: every write, flush and close is checked,
// and the first failure is kept with its system error. assimp's
// own file access ignores short writes, so a full disk left a truncated file that the exporter
// reported as written.
#pragma once

#include <assimp/IOSystem.hpp>

#include <string>

namespace galsculpt {

class CheckedExportIO : public Assimp::IOSystem {
 public:
  bool Exists(const char* file) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override;
  void Close(Assimp::IOStream* stream) override;

  // The first failure ("NAME: reason", the file's name without its folder), empty when every
  // write and close succeeded.
  const std::string& failure() const { return failure_; }

 private:
  friend class CheckedExportStream;
  void fail(const std::string& file, int error);
  std::string failure_;
};

}  // namespace galsculpt
