// libFuzzer harness for the readers of untrusted files (issue 27). One
// executable per reader, selected by CURVETET_FUZZ_READER at compile time:
// off, obj, stl, ply, msh, features, map. A reader may reject its input only
// with curvetet::Error (a clear message and an exit code); any other
// exception, a crash, or a sanitizer report is a finding.
#include "curvetet/core/error.hpp"
#include "curvetet/io/features_json.hpp"
#include "curvetet/io/map_file.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/read_surface.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

namespace {

using namespace curvetet;

void parse(std::string_view bytes) {
  const std::string name = "fuzz-input";
  using F = io::SurfaceFormat;
  const std::string_view reader = CURVETET_FUZZ_READER;
  if (reader == "off") io::parse_surface(bytes, F::off, name);
  else if (reader == "obj") io::parse_surface(bytes, F::obj, name);
  else if (reader == "stl") io::parse_surface(bytes, F::stl, name);
  else if (reader == "ply") io::parse_surface(bytes, F::ply, name);
  else if (reader == "msh") io::parse_msh(bytes, name);
  else if (reader == "features") io::parse_features(std::string(bytes), io::FeatureSet::all, name);
  else if (reader == "map") io::parse_map(bytes, name);
  else std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    parse(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const curvetet::Error&) {
    // A clean rejection.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reader threw a non-curvetet exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
