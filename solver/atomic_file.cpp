#include "atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw OutputError("cannot write " + path.string() + ": directory " + dir.string() +
                      " does not exist");
  }
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on chained operator+ here.
  std::string tmpName = ".";
  tmpName.append(path.filename().string()).append(".tmp").append(std::to_string(getpid()));
  const fs::path tmp = dir / tmpName;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw OutputError("cannot write " + path.string() + ": " + std::strerror(errno));
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      fs::remove(tmp, ec);
      throw;
    }
    out.flush();
    if (!out) {
      const std::string reason = std::strerror(errno);
      out.close();
      fs::remove(tmp, ec);
      throw OutputError("cannot write " + path.string() + ": " + reason);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw OutputError("cannot write " + path.string() + ": " + ec.message());
  }
}

std::string readWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace galsculpt
