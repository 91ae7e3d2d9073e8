#include "curvetet/core/atomic_file.hpp"

#include "curvetet/core/error.hpp"

#include <filesystem>
#include <system_error>

namespace curvetet {

AtomicFile::AtomicFile(std::string path, bool binary)
    : path_(std::move(path)), partial_(path_ + ".partial"),
      out_(partial_, binary ? std::ios::binary | std::ios::out | std::ios::trunc : std::ios::out | std::ios::trunc) {
  if (!out_) throw Error(ExitCode::io, "cannot open '" + partial_ + "' for writing");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(partial_, ec);
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw Error(ExitCode::io, "failed while writing '" + partial_ + "'");
  out_.close();
  std::error_code ec;
  std::filesystem::rename(partial_, path_, ec);
  if (ec) throw Error(ExitCode::io, "cannot move '" + partial_ + "' to '" + path_ + "': " + ec.message());
  committed_ = true;
}

} // namespace curvetet
