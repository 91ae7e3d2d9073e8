#pragma once
// The shell invariants as a list an operation runs on the prisms it touched
// (STYLE.md 2): each entry is a named local check; the list stops at the
// first failure and says which invariant failed (the rejection reason).
// Used by the thickening rounds; the coarsening operations (part 2) run the
// same list on their candidate stars, adding the distance invariant.
#include "curvetet/shell/invariants.hpp"

#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace curvetet::shell {

// What a local check may use besides the shell: the input-face -> prisms
// index (section containment) and the cap spatial hash (kept up to date by
// the caller: update() the touched prisms before checking).
struct InvariantContext {
  const std::vector<std::vector<int>>* trackers = nullptr;
  CapIndex* caps = nullptr; // null: the box-sweep local check is used
};

struct LocalInvariant {
  InvariantKind kind;
  // Failing prisms among / touched by `prisms` (for cap pairs: both prisms).
  std::function<std::vector<int>(const Shell&, std::span<const int> prisms, const InvariantContext&)> failing;
};

class InvariantSet {
 public:
  // Invariants 1-3 in order of cost: positivity, section, caps.
  static InvariantSet shell_invariants();
  void add(LocalInvariant invariant) { list_.push_back(std::move(invariant)); }

  // First failing invariant on these prisms, or nullopt when all hold.
  std::optional<InvariantKind> first_failure(const Shell& s, std::span<const int> prisms,
                                             const InvariantContext& ctx) const;
  // All prisms implicated by any invariant (sorted, unique): used by batch
  // edits (thickening) that undo exactly the failing part.
  std::vector<int> implicated(const Shell& s, std::span<const int> prisms, const InvariantContext& ctx) const;

 private:
  std::vector<LocalInvariant> list_;
};

} // namespace curvetet::shell
