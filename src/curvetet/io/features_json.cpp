#include "curvetet/io/features_json.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/io/text_cursor.hpp"

#include <nlohmann/json.hpp>

namespace curvetet::io {

features::FeatureInput parse_features(const std::string& text, FeatureSet set, const std::string& name) {
  features::FeatureInput f;
  try {
    auto j = nlohmann::json::parse(text);
    if (!j.is_object()) throw Error(InputDefect::bad_features, name + ": feature file must hold a JSON object");
    const char* edges_key = set == FeatureSet::sharp ? "sharp_edges" : "edges";
    const char* corners_key = set == FeatureSet::sharp ? "sharp_corners" : "corners";
    if (set == FeatureSet::sharp && !j.contains(edges_key))
      throw Error(InputDefect::bad_features, name + ": --feature-set sharp needs a \"sharp_edges\" entry");
    if (j.contains(edges_key)) f.edges = j.at(edges_key).get<std::vector<std::array<int, 2>>>();
    if (j.contains(corners_key)) f.corners = j.at(corners_key).get<std::vector<int>>();
    if (j.contains("points")) {
      const auto& p = j.at("points");
      if (p.contains("faces")) f.points.faces = p.at("faces").get<std::vector<int>>();
      if (p.contains("barycentric")) f.points.barycentric = p.at("barycentric").get<std::vector<std::array<double, 3>>>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(InputDefect::bad_features, name + ": malformed feature file: " + e.what());
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
