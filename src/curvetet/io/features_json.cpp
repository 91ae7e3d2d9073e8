#include "curvetet/io/features_json.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>

namespace curvetet::io {

namespace {

[[noreturn]] void bad(const std::string& name, const std::string& what) {
  throw Error(InputDefect::bad_features, name + ": " + what);
}
[[noreturn]] void malformed(const std::string& name, const std::string& what) { bad(name, "malformed feature file: " + what); }

// An id: a JSON integer an int holds (a float such as 2e62 would be an
// undefined conversion; range checks against the mesh come later).
int id_entry(const nlohmann::json& v, const std::string& name, const char* key) {
  if (!v.is_number_integer()) malformed(name, std::string("\"") + key + "\" entries must be integers");
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())
                             : v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
                                   v.get<std::int64_t>() > std::numeric_limits<int>::max())
    malformed(name, std::string("\"") + key + "\" entry out of range");
  return static_cast<int>(v.get<std::int64_t>());
}

const nlohmann::json& array_entry(const nlohmann::json& v, const std::string& name, const char* key) {
  if (!v.is_array()) malformed(name, std::string("\"") + key + "\" must be an array");
  return v;
}

} // namespace

features::FeatureInput parse_features(const std::string& text, FeatureSet set, const std::string& name) {
  features::FeatureInput f;
  try {
    auto j = nlohmann::json::parse(text);
    if (!j.is_object()) bad(name, "feature file must hold a JSON object");
    const char* edges_key = set == FeatureSet::sharp ? "sharp_edges" : "edges";
    const char* corners_key = set == FeatureSet::sharp ? "sharp_corners" : "corners";
    if (set == FeatureSet::sharp && !j.contains(edges_key)) bad(name, "--feature-set sharp needs a \"sharp_edges\" entry");
    if (j.contains(edges_key))
      for (const auto& e : array_entry(j.at(edges_key), name, edges_key)) {
        if (!e.is_array() || e.size() != 2) malformed(name, std::string("\"") + edges_key + "\" entries must be pairs");
        f.edges.push_back({id_entry(e[0], name, edges_key), id_entry(e[1], name, edges_key)});
      }
    if (j.contains(corners_key))
      for (const auto& c : array_entry(j.at(corners_key), name, corners_key)) f.corners.push_back(id_entry(c, name, corners_key));
    if (j.contains("points")) {
      const auto& p = j.at("points");
      if (!p.is_object()) malformed(name, "\"points\" must be an object");
      if (p.contains("faces"))
        for (const auto& t : array_entry(p.at("faces"), name, "faces")) f.points.faces.push_back(id_entry(t, name, "faces"));
      if (p.contains("barycentric")) f.points.barycentric = p.at("barycentric").get<std::vector<std::array<double, 3>>>();
    }
  } catch (const nlohmann::json::exception& e) {
    malformed(name, e.what());
  }
  return f;
}

features::FeatureInput read_features(const std::string& path, FeatureSet set) {
  std::string text;
  try {
    text = read_file_bytes(path);
  } catch (const Error&) {
    throw Error(InputDefect::bad_features, "cannot open feature file '" + path + "'");
  }
  return parse_features(text, set, path);
}

} // namespace curvetet::io
