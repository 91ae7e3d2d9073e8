#pragma once
// Output files are written to "<path>.partial" and renamed into place only
// once complete, so a failed run leaves no partial output file (every
// writer: surfaces, MSH, VTU, maps, tables, report.json).
#include <fstream>
#include <string>

namespace curvetet {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path, bool binary = false);
  ~AtomicFile(); // removes the partial file unless commit() ran
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  // Flushes, checks for errors and renames into place; throws Error(io).
  void commit();

 private:
  std::string path_, partial_;
  std::ofstream out_;
  bool committed_ = false;
};

} // namespace curvetet
