#include "curvetet/shell/coarsen.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/shell/curved_middle.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/local_thickness.hpp"
#include "curvetet/shell/operations.hpp"
#include "curvetet/shell/rejection_memo.hpp"
#include "curvetet/shell/shell_editor.hpp"
#include "curvetet/shell/star_invariants.hpp"
#include "curvetet/shell/surface_distance.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <queue>

namespace curvetet::shell {

namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t) { return std::chrono::duration<double>(clock_type::now() - t).count(); }

// Number of queue entries checked together. Fixed (not per thread) so the
// batches, hence the result, do not depend on the thread count.
constexpr int kBatch = 256;

// ---- Queue entries --------------------------------------------------------
struct Entry {
  double priority; // smaller first
  int a, b;        // edge (a, b) or vertex a (b = -1)
  std::uint32_t va, vb;
  bool operator>(const Entry& o) const {
    if (priority != o.priority) return priority > o.priority;
    if (a != o.a) return a > o.a;
    return b > o.b;
  }
};
using Queue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

// ---- Operations as the scheduler sees them -----------------------------
class Operation {
 public:
  virtual ~Operation() = default;
  virtual OpKind kind() const = 0;
  // Entry for (a, b) with the current state, or nullopt if not wanted.
  virtual std::optional<double> priority(const ShellEditor& e, int a, int b) const = 0;
  // Whether commits renew the entries around the new faces in this pass.
  virtual bool renews() const { return true; }
  virtual bool per_vertex() const { return false; }
  // Whether a rejection may be remembered (rejection_memo.hpp): the
  // candidates read nothing outside the faces around a and b.
  virtual bool local() const { return false; }
  // Alternatives in preference order; the first that passes is committed.
  virtual std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int b) const = 0;
};

double middle_length(const ShellEditor& e, int a, int b) {
  return (e.shell().middle[a] - e.shell().middle[b]).norm();
}

class CollapseOp final : public Operation {
 public:
  explicit CollapseOp(SmoothParams p) : p_(p) {}
  OpKind kind() const override { return OpKind::collapse; }
  bool local() const override { return true; }
  std::optional<double> priority(const ShellEditor& e, int a, int b) const override { return middle_length(e, a, b); }
  // Both directions keeping `to`'s pillar first, then both re-aiming it.
  std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int b) const override {
    std::vector<StarCandidate> out;
    for (auto [from, to] : {std::pair{a, b}, std::pair{b, a}})
      if (auto c = collapse_candidate(e, from, to)) out.push_back(std::move(*c));
    const std::size_t plain = out.size();
    out.reserve(2 * plain); // out[i] is read while pushing
    for (std::size_t i = 0; i < plain; ++i)
      if (auto c = collapse_reaimed_candidate(e, out[i], p_)) out.push_back(std::move(*c));
    return out;
  }

 private:
  SmoothParams p_;
};

class FlipOp final : public Operation {
 public:
  OpKind kind() const override { return OpKind::flip; }
  std::optional<double> priority(const ShellEditor& e, int a, int b) const override {
    const int gain = flip_valence_gain(e, a, b);
    if (gain >= 0) return std::nullopt;
    return static_cast<double>(gain);
  }
  std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int b) const override {
    std::vector<StarCandidate> out;
    if (flip_valence_gain(e, a, b) >= 0) return out; // no longer an improvement
    if (auto c = flip_candidate(e, a, b)) out.push_back(std::move(*c));
    return out;
  }
};

class SplitOp final : public Operation {
 public:
  explicit SplitOp(double min_length) : min_length_(min_length) {}
  OpKind kind() const override { return OpKind::split; }
  bool renews() const override { return false; }
  std::optional<double> priority(const ShellEditor& e, int a, int b) const override {
    const double l = middle_length(e, a, b);
    if (!(l > min_length_)) return std::nullopt;
    return -l;
  }
  std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int b) const override {
    std::vector<StarCandidate> out;
    if (auto c = split_candidate(e, a, b)) out.push_back(std::move(*c));
    return out;
  }

 private:
  double min_length_;
};

class SmoothOp final : public Operation {
 public:
  explicit SmoothOp(SmoothParams p) : p_(p) {}
  OpKind kind() const override { return OpKind::smooth; }
  bool local() const override { return true; }
  bool renews() const override { return false; }
  bool per_vertex() const override { return true; }
  std::optional<double> priority(const ShellEditor& e, int a, int) const override {
    if (e.shell().singular[a]) return std::nullopt;
    return static_cast<double>(a);
  }
  std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int) const override {
    return smooth_candidates(e, a, p_);
  }

 private:
  SmoothParams p_;
};

// Control-point smoothing (curved middle only): the star of a vertex is
// proposed unchanged, so only the fit of its spokes and faces is redone.
class RefitOp final : public Operation {
 public:
  OpKind kind() const override { return OpKind::refit; }
  bool renews() const override { return false; }
  bool per_vertex() const override { return true; }
  std::optional<double> priority(const ShellEditor&, int a, int) const override { return static_cast<double>(a); }
  std::vector<StarCandidate> candidates(const ShellEditor& e, int a, int) const override {
    StarCandidate c;
    c.op = OpKind::refit;
    c.removed = e.faces_of(a);
    std::sort(c.removed.begin(), c.removed.end());
    for (int f : c.removed) c.faces.push_back(e.shell().faces[f]);
    return {std::move(c)};
  }
};

// ---- The scheduler ----------------------------------------------------------

void push_entry(const ShellEditor& e, const Operation& op, Queue& q, int a, int b) {
  if (auto p = op.priority(e, a, b)) q.push({*p, a, b, e.version(a), b >= 0 ? e.version(b) : 0u});
}

void push_vertex_entries(const ShellEditor& e, const Operation& op, Queue& q, int v) {
  if (op.per_vertex()) {
    push_entry(e, op, q, v, -1);
    return;
  }
  for (int w : e.neighbours(v))
    if (v < w) push_entry(e, op, q, v, w);
    else push_entry(e, op, q, w, v);
}

bool stale(const ShellEditor& e, const Entry& en) {
  if (!e.vertex_alive(en.a) || e.version(en.a) != en.va) return true;
  if (en.b >= 0 && (!e.vertex_alive(en.b) || e.version(en.b) != en.vb)) return true;
  return false;
}

// The vertices an operation on (a, b) may read or change: those of the faces
// around a and b. Two entries whose sets are disjoint are independent.
void star_vertices(const ShellEditor& e, const Entry& en, std::vector<int>& out) {
  out.clear();
  for (int v : {en.a, en.b}) {
    if (v < 0) continue;
    for (int f : e.faces_of(v))
      for (int w : e.shell().faces[f]) out.push_back(w);
  }
  // Flip and collapse also read the neighbourhoods of the opposite vertices
  // (valence, adjacency); their faces all contain a star vertex, so locking
  // the star vertices keeps them unchanged by other members of the batch.
}

struct SlotResult {
  std::optional<StarCandidate> accepted;
  int tried = 0;
  std::array<long long, kRejectionCount> rejected{};
  std::uint64_t signature = 0;
  bool remembered = false;      // taken from the memo
  bool local_rejections = true; // every rejection by a star-local invariant
  InvariantSeconds invariant_seconds{};
  double proposal_seconds = 0;
};

// `memo` (null: none) remembers and replays rejections of local operations.
PassStats run_pass(ShellEditor& e, const Operation& op, const StarContext& ctx, const InvariantList& invariants,
                   int round, RejectionMemo* memo) {
  if (!op.local()) memo = nullptr;
  const auto start = clock_type::now();
  PassStats st;
  st.op = op.kind();
  st.round = round;
  st.faces_before = e.alive_faces();
  Queue q;
  for (int v = 0; v < e.shell().num_vertices(); ++v)
    if (e.vertex_alive(v)) {
      if (op.per_vertex()) push_entry(e, op, q, v, -1);
      else
        for (int w : e.neighbours(v))
          if (v < w) push_entry(e, op, q, v, w);
    }
  std::vector<char> locked(e.shell().num_vertices(), 0);
  std::vector<int> star, locked_list;
  int batch_id = 0;
  while (!q.empty()) {
    // 1. An independent batch in priority order.
    std::vector<Entry> batch, deferred;
    locked.resize(e.shell().num_vertices(), 0);
    while (!q.empty() && static_cast<int>(batch.size()) < kBatch) {
      const Entry en = q.top();
      q.pop();
      if (stale(e, en)) continue;
      star_vertices(e, en, star);
      if (std::any_of(star.begin(), star.end(), [&](int v) { return locked[v]; })) {
        deferred.push_back(en);
        continue;
      }
      for (int v : star) {
        if (!locked[v]) locked_list.push_back(v);
        locked[v] = 1;
      }
      batch.push_back(en);
    }
    for (int v : locked_list) locked[v] = 0;
    locked_list.clear();
    for (const auto& en : deferred) q.push(en);
    if (batch.empty()) break;
    ++st.batches;
    // 2. Check in parallel (the shell is read-only here).
    std::vector<SlotResult> results(batch.size());
    const auto check_start = clock_type::now();
    tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) {
      auto& r = results[i];
      if (memo) {
        r.signature = star_signature(e, batch[i].a, batch[i].b, ctx.thickness);
        if (const RejectionRecord* before = memo->find(r.signature)) {
          r.tried = before->tried;
          r.rejected = before->rejected;
          r.remembered = true;
          return;
        }
      }
      const auto proposal_start = clock_type::now();
      auto cands = op.candidates(e, batch[i].a, batch[i].b);
      r.proposal_seconds = since(proposal_start);
      if (cands.empty()) {
        r.tried = 1;
        ++r.rejected[static_cast<int>(Rejection::topology)];
        return;
      }
      for (auto& c : cands) {
        ++r.tried;
        const auto why = check_candidate(invariants, ctx, c, &r.invariant_seconds);
        if (!why) {
          r.accepted = std::move(c);
          return;
        }
        ++r.rejected[static_cast<int>(*why)];
        r.local_rejections = r.local_rejections && rejection_is_local(*why);
      }
    });
    st.check_seconds += since(check_start);
    // 3. Commit in batch order.
    for (std::size_t i = 0; i < batch.size(); ++i) {
      auto& r = results[i];
      st.tried += r.tried;
      for (int k = 0; k < kRejectionCount; ++k) {
        st.rejected[k] += r.rejected[k];
        st.invariant_seconds[k] += r.invariant_seconds[k];
      }
      st.proposal_seconds += r.proposal_seconds;
      st.remembered += r.remembered ? 1 : 0;
      if (!r.accepted) {
        if (memo && !r.remembered && r.local_rejections) memo->remember(r.signature, {r.tried, r.rejected});
        continue;
      }
      if (!caps_free_of_batch(ctx, *r.accepted, batch_id) || e.reshapes_batch_face(*r.accepted, batch_id)) {
        ++st.rejected[static_cast<int>(Rejection::batch_conflict)];
        continue;
      }
      const auto ids = e.commit(*r.accepted, batch_id);
      ++st.accepted;
      if (op.renews()) {
        std::vector<int> verts;
        for (int f : ids)
          for (int v : e.shell().faces[f]) verts.push_back(v);
        std::sort(verts.begin(), verts.end());
        verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
        for (int v : verts) push_vertex_entries(e, op, q, v);
      }
    }
    ++batch_id;
  }
  e.compact();
  st.faces_after = e.alive_faces();
  st.seconds = since(start);
  return st;
}

double mean_edge_length(const Shell& s) {
  double total = 0;
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) total += (s.middle[f[k]] - s.middle[f[(k + 1) % 3]]).norm();
  return s.faces.empty() ? 0 : total / (3.0 * s.faces.size());
}

void debug_check(const Shell& s, double epsilon, const std::string& stage) {
  require_valid_shell(s, stage);
  if (const int f = first_uncertified_prism(s); f >= 0)
    throw Error(ExitCode::internal, fmt::format("curved middle of prism {} not certified after {}", f, stage));
  if (const double d = middle_distance_bound(s, epsilon); !(d <= epsilon))
    throw Error(ExitCode::internal,
                fmt::format("middle surface farther than epsilon from the input after {}: bound {} (epsilon {})", stage, d, epsilon));
  const auto m = check_map(s);
  if (!(m.max_distance < epsilon) || m.points_outside > 0 || !m.bijective()) {
    throw Error(ExitCode::internal,
                fmt::format("shell map violated after {}: max distance {} (epsilon {}), {} points outside their "
                            "prism, {} prisms not tiled exactly (worst {}, area error {}), {} with a negative piece",
                            stage, m.max_distance, epsilon, m.points_outside, m.prisms_not_tiled, m.worst_prism,
                            m.max_area_error, m.prisms_folded));
  }
}

} // namespace

CoarsenStats coarsen_shell(Shell& s, const CoarsenOptions& o, const MiddleFit* fit) {
  const auto start = clock_type::now();
  const LinearMiddle linear;
  if (!fit) fit = &linear;
  CoarsenStats flat_phase;
  const bool two_phases = o.flat_first && fit->degree() > 1 && s.middle_nodes.empty();
  if (two_phases) flat_phase = coarsen_shell(s, o, &linear);
  const double diag = mesh::bbox_diagonal(s.input.vertices);
  CoarsenStats out;
  out.epsilon = o.epsilon_abs > 0 ? o.epsilon_abs : o.epsilon * diag;
  out.faces_before = two_phases ? flat_phase.faces_before : s.num_prisms();
  out.vertices_before = two_phases ? flat_phase.vertices_before : s.num_vertices();
  out.passes = flat_phase.passes;
  if (fit->degree() > 1 && (s.middle_degree != fit->degree() || s.middle_nodes.size() != s.faces.size())) {
    set_flat_middle(s, fit->degree());
    // Where the flat shell's slab map already folds, the curving could not
    // start: place slab tets over straight middle parts straight (they are
    // then the prisms' own tets, positive by invariant 1).
    s.straight_slab_parts = false;
    if (const int f = first_uncertified_prism(s); f >= 0) {
      s.straight_slab_parts = true;
      logger().info("coarsen: the slab map of prism {} folds on the flat middle; slab tets over straight middle parts "
                    "are placed straight",
                    f);
    }
  }
  if (fit->degree() == 1 && !s.middle_nodes.empty())
    throw Error(ExitCode::internal, "coarsen_shell: a curved shell needs a curved middle fit");
  ShellEditor editor(s);
  // The thickness under each vertex, refreshed every round (vertices move
  // a little, splits add some); rays skip the input within 2 epsilon of the
  // middle surface.
  std::unique_ptr<ThicknessProbe> probe;
  std::vector<double> thickness;
  if (std::isfinite(o.thickness_ratio)) probe = std::make_unique<ThicknessProbe>(s.input);
  StarContext ctx{editor, *fit, out.epsilon, o.quality_bound, o.slab_quality_bound, o.curved_quality_bound};
  if (probe) {
    ctx.thickness = &thickness;
    ctx.thickness_ratio = o.thickness_ratio;
  }
  const auto invariants = default_star_invariants();
  const SmoothParams pillar_params{o.target_pillar * diag, o.singular_dot};
  const CollapseOp collapse(pillar_params);
  const FlipOp flip;
  const SmoothOp smooth(pillar_params);
  const RefitOp refit;
  // Feature straightening reads input faces beyond the star: no memo then.
  std::optional<RejectionMemo> collapse_memo, smooth_memo;
  if (o.remember_rejections && s.features.empty()) {
    collapse_memo.emplace();
    smooth_memo.emplace();
  }
  if (o.debug_invariants) debug_check(s, out.epsilon, "coarsen start");
  for (int round = 0; round < o.max_rounds; ++round) {
    out.rounds = round + 1;
    std::vector<const Operation*> ops = {&collapse, &flip, &smooth};
    if (fit->degree() > 1) ops.push_back(&refit);
    std::unique_ptr<SplitOp> split;
    if (o.split_factor > 0) {
      split = std::make_unique<SplitOp>(o.split_factor * mean_edge_length(s));
      ops.push_back(split.get());
    }
    if (probe) thickness = probe->at_vertices(s, 2 * out.epsilon);
    const int before = s.num_prisms();
    // The last round: collapses stalled (none accepted, or they removed less
    // than min_round_gain of the faces). It skips the split, which would
    // only leave faces behind; splits help a coarsening that still moves.
    bool last = round + 1 == o.max_rounds;
    for (const Operation* op : ops) {
      if (op->kind() == OpKind::split && last) continue;
      auto& memo = op->kind() == OpKind::collapse ? collapse_memo : smooth_memo;
      auto st = run_pass(editor, *op, ctx, invariants, round, memo ? &*memo : nullptr);
      if (op->kind() == OpKind::collapse)
        last = last || st.accepted == 0 || before - s.num_prisms() < o.min_round_gain * before;
      logger().info("coarsen round {} {}: {} -> {} faces, {}/{} accepted, {:.2f} s ({} rejected as before)", round,
                    to_string(st.op), st.faces_before, st.faces_after, st.accepted, st.tried, st.seconds, st.remembered);
      out.passes.push_back(st);
      if (o.debug_invariants) debug_check(s, out.epsilon, fmt::format("coarsen round {} {}", round, to_string(st.op)));
    }
    if (last) break;
  }
  out.faces_after = s.num_prisms();
  out.vertices_after = s.num_vertices();
  out.max_distance = check_map(s, false).max_distance;
  out.max_surface_distance = middle_distance_bound(s, out.epsilon);
  out.seconds = since(start);
  return out;
}

nlohmann::json rejections_json(const std::vector<PassStats>& passes) {
  nlohmann::json out = nlohmann::json::object();
  for (int k = 0; k < kRejectionCount; ++k) {
    long long n = 0;
    for (const auto& p : passes) n += p.rejected[k];
    out[std::string(to_string(static_cast<Rejection>(k)))] = n;
  }
  return out;
}

nlohmann::json rejections_json(const PassStats& pass) { return rejections_json(std::vector<PassStats>{pass}); }

nlohmann::json check_seconds_json(const std::vector<PassStats>& passes) {
  nlohmann::json out = nlohmann::json::object();
  double proposals = 0;
  for (const auto& p : passes) proposals += p.proposal_seconds;
  out["proposals"] = proposals;
  for (int k = 0; k < kRejectionCount; ++k) {
    double t = 0;
    for (const auto& p : passes) t += p.invariant_seconds[k];
    if (t > 0) out[std::string(to_string(static_cast<Rejection>(k)))] = t;
  }
  return out;
}

} // namespace curvetet::shell
