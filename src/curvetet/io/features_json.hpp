#pragma once
// Feature file (JSON, 0-based indices, every part optional, unknown keys
// ignored):
//   {"edges": [[i,j],...], "corners": [k,...],
//    "points": {"faces": [f,...], "barycentric": [[a,b,c],...]},
//    "sharp_edges": [...], "sharp_corners": [...]}
// FeatureSet::sharp reads "sharp_edges"/"sharp_corners" (the subset on
// non-tangent CAD curves) instead of "edges"/"corners".
// Throws Error(InputDefect::bad_features) on malformed JSON or wrong types;
// validation against the mesh is features::validate_and_normalize.
#include "curvetet/features/feature_input.hpp"

#include <string>

namespace curvetet::io {

enum class FeatureSet { all, sharp };

features::FeatureInput read_features(const std::string& path, FeatureSet set = FeatureSet::all);
features::FeatureInput parse_features(const std::string& text, FeatureSet set, const std::string& name);

} // namespace curvetet::io
