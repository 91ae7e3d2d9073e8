#include "curvetet/volume/bsp_insert.hpp"

#include "curvetet/volume/bsp_filters.hpp"
#include "curvetet/volume/homogeneous.hpp"
#include "curvetet/volume/mesh_keys.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/mesh/edge_topology.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

namespace curvetet::volume::exact {
namespace {


// Plane {x : n.(x - a) = 0}; a is a double point, n exact; n points to the
// positive side.
struct Plane {
  bool through_triangle = false; // the plane of tri[0..2] (n = (t1-t0)x(t2-t0))
  Vec3 tri[3];
  int ids[3] = {-1, -1, -1};     // their vertex ids (known to be on the plane)
  Vec3 a;
  mpq_class n[3];
  HPlane h;     // the same plane in integers, for the exact side tests
  Vec3 nd;      // n rounded toward zero
  double nd_l1; // |nd|_1
};

Plane make_plane(const Vec3& a, const mpq_class n[3]) {
  Plane p;
  p.a = a;
  for (int i = 0; i < 3; ++i) {
    p.n[i] = n[i];
    p.nd[i] = n[i].get_d();
  }
  p.nd_l1 = p.nd.cwiseAbs().sum();
  p.h = to_hplane(to_q(a), n);
  return p;
}

void cross(const mpq_class u[3], const mpq_class v[3], mpq_class out[3]) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

// A rational point with its double approximation (coordinates within 4u
// relative of the exact ones) for the floating filters.
struct Point {
  HPoint h;
  Vec3 d;
};
Point make_point(HPoint h) {
  const Vec3 d = approximate(h);
  return {std::move(h), d};
}

// A surface triangle as seen by the cut filter: its plane, and the planes
// through its edges perpendicular to it, normals pointing away from it.
struct TriangleShape {
  const Plane* plane = nullptr;
  Plane edge[3];
  Point corner[3];
};

// Exact side of a point (double filter first, bsp_filters.hpp).
int side_of(const Plane& p, const Point& x) {
  if (const int s = side_filter(p.nd, p.nd_l1, p.a, x.d)) return s;
  return sgn(value(p.h, x.h));
}

// sign(((q - p) x (x - p)) . n), n the normal of plane pl.
int orient_in_plane(const Point& p, const Point& q, const Point& x, const Plane& pl) {
  if (&x == &p || &x == &q) return 0;
  if (const int s = orient_in_plane_filter(p.d, q.d, x.d, pl.nd, pl.nd_l1)) return s;
  return exact::orient_in_plane(p.h, q.h, x.h, pl.h.n);
}

// Whether p, q, x lie on one line: (q - p) x (x - p) == 0, on the double
// approximations where they decide it, else on the homogeneous integers.
bool collinear(const Point& p, const Point& q, const Point& x) {
  if (not_collinear_filter(p.d, q.d, x.d)) return false;
  mpz_class hu[3], hw[3];
  for (int i = 0; i < 3; ++i) {
    hu[i] = q.h.x[i] * p.h.w - p.h.x[i] * q.h.w;
    hw[i] = x.h.x[i] * p.h.w - p.h.x[i] * x.h.w;
  }
  return hu[1] * hw[2] == hu[2] * hw[1] && hu[2] * hw[0] == hu[0] * hw[2] && hu[0] * hw[1] == hu[1] * hw[0];
}

struct Face {
  std::vector<int> loop; // cyclic, convex, unoriented
  int cell[2] = {-1, -1};
  int tri = -1;          // surface triangle containing the face, or -1
  // Supporting plane: the cutting plane that made it, or (when null) the
  // plane of the background points origin[0..2].
  const Plane* plane = nullptr;
  std::array<int, 3> origin{-1, -1, -1};
};

class Complex {
 public:
  Vertices v;
  std::vector<Face> faces;
  std::vector<std::vector<int>> cells; // face ids of each cell
  std::vector<std::vector<int>> tet_cells;
  // face_id[t][k]: the face made for background tet t opposite its corner k
  // (before any cut).
  std::vector<std::array<int, 4>> face_id;
  std::size_t num_cuts = 0;

  explicit Complex(const BackgroundMesh& bg) {
    for (const auto& p : bg.points) add_point(p);
    const int nt = static_cast<int>(bg.tets.size());
    std::vector<std::array<int, 4>> computed;
    if (bg.neighbours.empty()) computed = face_neighbours(bg.tets);
    const auto& neighbours = bg.neighbours.empty() ? computed : bg.neighbours;
    cells.resize(nt);
    tet_cells.resize(nt);
    // A face is made by the first of its two tets; the second finds it
    // through the neighbour relation (no hashing of 4 x #tets triples).
    face_id.assign(nt, {-1, -1, -1, -1});
    for (int t = 0; t < nt; ++t) {
      const auto& q = bg.tets[t];
      tet_cells[t] = {t};
      for (int k = 0; k < 4; ++k) {
        const int n = neighbours[t][k];
        int f = -1;
        if (n >= 0 && n < t)
          for (int j = 0; j < 4; ++j)
            if (neighbours[n][j] == t) f = face_id[n][j];
        if (f < 0) {
          const int a = q[(k + 1) % 4], b = q[(k + 2) % 4], c = q[(k + 3) % 4];
          f = static_cast<int>(faces.size());
          faces.push_back(Face{{a, b, c}, {t, -1}, -1, nullptr, {a, b, c}});
        } else {
          faces[f].cell[1] = t;
        }
        face_id[t][k] = f;
        cells[t].push_back(f);
      }
    }
    // Edge -> faces, built in bulk (sorted pairs) rather than by growing
    // one vector per edge in the map.
    std::vector<std::pair<std::uint64_t, int>> pairs;
    pairs.reserve(3 * faces.size());
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
      const auto& l = faces[f].loop;
      for (int k = 0; k < 3; ++k) pairs.emplace_back(edge_key(l[k], l[(k + 1) % 3]), f);
    }
    std::sort(pairs.begin(), pairs.end());
    edge_faces_.reserve(pairs.size() / 4);
    for (std::size_t i = 0; i < pairs.size();) {
      std::size_t j = i;
      while (j < pairs.size() && pairs[j].first == pairs[i].first) ++j;
      auto& list = edge_faces_[pairs[i].first];
      list.reserve(j - i);
      for (; i < j; ++i) list.push_back(pairs[i].second);
    }
  }

  // v's vertices in homogeneous form, same order (the centres added when
  // the cells are tetrahedralized at the end are not mirrored).
  std::vector<Point> points;

  int add_point(const Vec3& p) {
    v.add(p);
    points.push_back({to_h(to_q(p)), p});
    return v.size() - 1;
  }
  int add_point(HPoint p) {
    normalize(p);
    v.add(to_q(p));
    points.push_back({std::move(p), v.d.back()});
    return v.size() - 1;
  }
  // Where edge ab (a and b strictly on opposite sides of p) meets p.
  Point edge_crossing(int a, int b, const Plane& p) const {
    return make_point(crossing(points[a].h, points[b].h, value(p.h, points[a].h), value(p.h, points[b].h)));
  }

  // Exact side of vertex i (double filter first).
  int side(const Plane& p, int i) const {
    if (i == p.ids[0] || i == p.ids[1] || i == p.ids[2]) return 0;
    if (p.through_triangle && v.exact[i]) return geometry::orient3d(p.tri[0], p.tri[1], p.tri[2], v.d[i]);
    return side_of(p, points[i]);
  }

  // Vertices of cell c (each once).
  std::vector<int> cell_vertices(int c) {
    ++stamp_;
    std::vector<int> out;
    for (int f : cells[c])
      for (int i : faces[f].loop) {
        touch(i);
        if (mark_[i] != stamp_) {
          mark_[i] = stamp_;
          out.push_back(i);
        }
      }
    return out;
  }

  // Splits face f (not its cells) by plane p when p crosses it; the cells
  // keep both pieces (coplanar faces). Returns the new face or -1.
  int split_face_by(int f, const Plane& p) {
    bool pos = false, neg = false;
    for (int i : faces[f].loop) {
      touch(i);
      const int s = side(p, i);
      sgn_[i] = static_cast<signed char>(s);
      pos |= s > 0;
      neg |= s < 0;
    }
    if (!pos || !neg) return -1;
    const std::vector<int> l = faces[f].loop;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const int a = l[k], b = l[(k + 1) % l.size()];
      if (sgn_[a] * sgn_[b] >= 0) continue;
      const int wi = add_point(edge_crossing(a, b, p).h);
      touch(wi);
      sgn_[wi] = 0;
      split_edge(a, b, wi);
    }
    return std::get<0>(split_face(f));
  }

  // Cuts cell c by plane p (the new cell goes to tet_cells[tet]); returns
  // whether it was split.
  bool cut(int c, const Plane& p, int tet, const TriangleShape* tri = nullptr) {
    std::vector<int> verts = cell_vertices(c);
    bool pos = false, neg = false;
    for (int i : verts) {
      const int s = side(p, i);
      sgn_[i] = static_cast<signed char>(s);
      pos |= s > 0;
      neg |= s < 0;
    }
    if (!pos || !neg) return false;
    // Cheap separation first: the cell beyond one of the triangle's edges.
    if (tri)
      for (const auto& e : tri->edge) {
        bool all_out = true;
        for (int i : verts)
          if (side(e, i) < 0) {
            all_out = false;
            break;
          }
        if (all_out) return false;
      }
    // 1. The crossing edges and where they meet the plane.
    std::vector<std::uint64_t> crossing;
    for (int f : cells[c]) {
      const auto& l = faces[f].loop;
      for (std::size_t k = 0; k < l.size(); ++k) {
        const int a = l[k], b = l[(k + 1) % l.size()];
        if (sgn_[a] * sgn_[b] < 0) crossing.push_back(edge_key(a, b));
      }
    }
    std::sort(crossing.begin(), crossing.end());
    crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
    std::vector<Point> wq;
    wq.reserve(crossing.size());
    for (auto key : crossing)
      wq.push_back(edge_crossing(static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu), p));
    // 2. Skip the cut when the triangle misses the cell's interior: then it
    // misses the relative interior of the section S, and some edge line of S
    // or of the triangle separates them in the plane (2D separating axes).
    if (tri && separated(c, crossing, wq, *tri)) return false;
    ++num_cuts;
    // 3. Split the crossing edges everywhere they appear.
    for (std::size_t e = 0; e < crossing.size(); ++e) {
      const int a = static_cast<int>(crossing[e] >> 32), b = static_cast<int>(crossing[e] & 0xffffffffu);
      const int wi = add_point(std::move(wq[e].h));
      touch(wi);
      sgn_[wi] = 0;
      split_edge(a, b, wi);
    }
    // 2. Split the faces crossing the plane; collect the section's edges.
    std::vector<int> plus, minus;
    std::vector<std::uint64_t> section;
    const std::vector<int> cell_faces = cells[c];
    for (int f : cell_faces) {
      bool fp = false, fn = false;
      for (int i : faces[f].loop) {
        fp |= sgn_[i] > 0;
        fn |= sgn_[i] < 0;
      }
      if (fp && fn) {
        auto [g, a, b, f_is_plus] = split_face(f);
        (f_is_plus ? plus : minus).push_back(f);
        (f_is_plus ? minus : plus).push_back(g);
        section.push_back(edge_key(a, b));
      } else if (fp || fn) {
        (fp ? plus : minus).push_back(f);
        const auto& l = faces[f].loop;
        for (std::size_t k = 0; k < l.size(); ++k) {
          const int a = l[k], b = l[(k + 1) % l.size()];
          if (sgn_[a] == 0 && sgn_[b] == 0) section.push_back(edge_key(a, b));
        }
      } else {
        throw Error(ExitCode::internal, "volume: BSP cut met a face lying in the cutting plane");
      }
    }
    std::sort(section.begin(), section.end());
    section.erase(std::unique(section.begin(), section.end()), section.end());
    // 3. Chain the section edges into the new face's loop.
    std::unordered_map<int, std::array<int, 2>> nb;
    for (auto key : section) {
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
        auto [it, fresh] = nb.try_emplace(x, std::array<int, 2>{y, -1});
        if (!fresh) it->second[1] = y;
      }
    }
    std::vector<int> loop;
    {
      int prev = -1, cur = static_cast<int>(section[0] >> 32);
      const int start = cur;
      do {
        loop.push_back(cur);
        const auto& n = nb.at(cur);
        const int next = n[0] != prev ? n[0] : n[1];
        if (next < 0) {
          std::string msg = "volume: BSP section is not a closed polygon:";
          for (auto key : section) msg += " " + std::to_string(key >> 32) + "-" + std::to_string(key & 0xffffffffu);
          for (int f : cell_faces) {
            msg += "\n face " + std::to_string(f) + ":";
            for (int i : faces[f].loop) msg += " " + std::to_string(i) + "(" + std::to_string(int(sgn_[i])) + ")";
          }
          throw Error(ExitCode::internal, msg);
        }
        prev = cur;
        cur = next;
      } while (cur != start && loop.size() <= section.size());
      if (loop.size() != section.size() || loop.size() < 3)
        throw Error(ExitCode::internal, "volume: BSP section is not a simple polygon");
    }
    // 4. Two cells: c keeps the positive side, cm gets the negative one.
    const int cm = static_cast<int>(cells.size());
    const int nf = static_cast<int>(faces.size());
    for (int f : minus)
      for (int& x : faces[f].cell)
        if (x == c) x = cm;
    faces.push_back(Face{std::move(loop), {c, cm}, -1, &p, {-1, -1, -1}});
    add_edges(nf);
    plus.push_back(nf);
    minus.push_back(nf);
    cells[c] = std::move(plus);
    cells.push_back(std::move(minus));
    tet_cells[tet].push_back(cm);
#ifdef CURVETET_BSP_DEBUG
    for (int cc : {c, cm, nf}) (void)cc;
    for (int cc = 0; cc < (int)cells.size(); ++cc) {
      auto l = cells[cc];
      std::sort(l.begin(), l.end());
      if (std::adjacent_find(l.begin(), l.end()) != l.end()) throw Error(ExitCode::internal, "dup face in cell " + std::to_string(cc) + " after cutting " + std::to_string(c));
      for (int f : l) if (faces[f].cell[0] != cc && faces[f].cell[1] != cc) throw Error(ExitCode::internal, "face/cell mismatch");
    }
#endif
    return true;
  }

 private:
  std::vector<signed char> sgn_;
  std::vector<unsigned> mark_;
  unsigned stamp_ = 0;
  std::unordered_map<std::uint64_t, std::vector<int>> edge_faces_;

  bool separated(int c, const std::vector<std::uint64_t>& crossing, const std::vector<Point>& wq,
                 const TriangleShape& tri) {
    // Section points: cell vertices on the plane, and the crossing points.
    std::vector<const Point*> pts;
    for (int f : cells[c])
      for (int i : faces[f].loop)
        if (sgn_[i] == 0) pts.push_back(&points[i]);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    for (const auto& w : wq) pts.push_back(&w);
    for (const auto& e : tri.edge) {
      bool all_out = true;
      for (const Point* q : pts)
        if (side_of(e, *q) < 0) {
          all_out = false;
          break;
        }
      if (all_out) return true;
    }
    // Edges of S: per face of the cell, its two section points.
    auto wpoint = [&](int a, int b) -> const Point* {
      const auto it = std::lower_bound(crossing.begin(), crossing.end(), edge_key(a, b));
      return &wq[it - crossing.begin()];
    };
    for (int f : cells[c]) {
      const auto& l = faces[f].loop;
      const Point* ends[2];
      int m = 0;
      for (std::size_t k = 0; k < l.size() && m <= 2; ++k) {
        const int a = l[k], b = l[(k + 1) % l.size()];
        if (sgn_[a] == 0) {
          if (m < 2) ends[m] = &points[a];
          ++m;
        }
        if (sgn_[a] * sgn_[b] < 0) {
          if (m < 2) ends[m] = wpoint(a, b);
          ++m;
        }
      }
      if (m != 2) continue;
      int ref = 0;
      for (const Point* q : pts) {
        ref = orient_in_plane(*ends[0], *ends[1], *q, *tri.plane);
        if (ref != 0) break;
      }
      if (ref == 0) continue;
      bool all_out = true;
      for (const auto& corner : tri.corner)
        if (orient_in_plane(*ends[0], *ends[1], corner, *tri.plane) * ref > 0) {
          all_out = false;
          break;
        }
      if (all_out) return true;
    }
    return false;
  }

  void touch(int i) {
    if (static_cast<int>(mark_.size()) <= i) {
      mark_.resize(2 * i + 16, 0);
      sgn_.resize(2 * i + 16, 0);
    }
  }
  void add_edges(int f) {
    const auto& l = faces[f].loop;
    for (std::size_t k = 0; k < l.size(); ++k) edge_faces_[edge_key(l[k], l[(k + 1) % l.size()])].push_back(f);
  }
  // Inserts w between a and b in every face having edge ab.
  void split_edge(int a, int b, int w) {
    auto node = edge_faces_.extract(edge_key(a, b));
    if (node.empty()) throw Error(ExitCode::internal, "volume: BSP edge without faces");
    std::vector<int> fs = std::move(node.mapped());
    for (int f : fs) {
      auto& l = faces[f].loop;
      const std::size_t n = l.size();
      for (std::size_t k = 0; k < n; ++k) {
        const int x = l[k], y = l[(k + 1) % n];
        if ((x == a && y == b) || (x == b && y == a)) {
          l.insert(l.begin() + static_cast<std::ptrdiff_t>(k + 1), w);
          break;
        }
      }
    }
    edge_faces_[edge_key(a, w)] = fs;
    edge_faces_[edge_key(w, b)] = std::move(fs);
  }
  // Splits face f (vertices on both sides, two on the plane) into f and a new
  // face g; both keep f's cells. Returns g, the chord ends, and whether f
  // kept the positive side.
  std::tuple<int, int, int, bool> split_face(int f) {
    std::vector<int> l = faces[f].loop;
    const std::size_t n = l.size();
    std::size_t z0 = n, z1 = n;
    for (std::size_t k = 0; k < n; ++k)
      if (sgn_[l[k]] == 0) (z0 == n ? z0 : z1) = k;
    if (z1 == n) throw Error(ExitCode::internal, "volume: BSP face split without two plane points");
    std::vector<int> first(l.begin() + z0, l.begin() + z1 + 1);
    std::vector<int> second(l.begin() + z1, l.end());
    second.insert(second.end(), l.begin(), l.begin() + z0 + 1);
    const bool first_plus = sgn_[first[1]] > 0;
    const int a = l[z0], b = l[z1];
    const int g = static_cast<int>(faces.size());
    // A piece of a face lying in a surface triangle lies in it too.
    faces.push_back(Face{second, {faces[f].cell[0], faces[f].cell[1]}, faces[f].tri, faces[f].plane, faces[f].origin});
    faces[f].loop = std::move(first);
    // Edges of g (except the chord) now belong to g instead of f.
    for (std::size_t k = 0; k + 1 < second.size(); ++k) {
      auto& list = edge_faces_[edge_key(second[k], second[k + 1])];
      std::replace(list.begin(), list.end(), f, g);
    }
    edge_faces_[edge_key(a, b)] = {f, g};
    for (int x : faces[f].cell)
      if (x >= 0 && x != -1) {
        // every cell having f also has g (the cut cell's lists are rebuilt by the caller)
        cells[x].push_back(g);
      }
    return {g, a, b, first_plus};
  }
};

} // namespace

InsertedSurface insert_surface(const BackgroundMesh& bg, const std::vector<mesh::Tri>& triangles, int keep_winding) {
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&](const char* what) {
    const auto now = std::chrono::steady_clock::now();
    logger().debug("volume: BSP {} in {:.3f} s", what, std::chrono::duration<double>(now - clock).count());
    clock = now;
  };
  Complex cx(bg);
  lap("complex");
  const int nt = static_cast<int>(triangles.size());
  const auto& P = bg.points;

  // A triangle that is a face of the background crosses no tet: its face is
  // labelled now (and its pieces, if other cuts split it, inherit the label)
  // and only the other triangles are cut in and looked for below.
  std::vector<int> cut_ids;
  if (P.size() < static_cast<std::size_t>(kMaxFaceKeyId)) { // see face_key
    const auto face_of = triangle_faces(bg, triangles, &cut_ids);
    for (std::size_t T = 0; T < bg.tets.size(); ++T)
      for (int k = 0; k < 4; ++k)
        if (face_of[T][k] >= 0) cx.faces[cx.face_id[T][k]].tri = face_of[T][k];
  } else {
    for (int t = 0; t < nt; ++t) cut_ids.push_back(t);
  }
  std::vector<char> is_cut(nt, 0);
  for (int t : cut_ids) is_cut[t] = 1;
  // Planes of the triangles (normal = outward face normal), made when first
  // needed (the cut triangles', and the winding numbers' on the way), and,
  // for edges of a cut triangle whose two triangles are coplanar, a plane
  // through the edge.
  std::vector<Plane> tri_plane(nt); // addresses stay: faces point to them
  std::vector<char> plane_made(nt, 0);
  auto plane = [&](int t) -> const Plane& {
    if (plane_made[t]) return tri_plane[t];
    plane_made[t] = 1;
    const auto& f = triangles[t];
    mpq_class u[3], w[3], n[3];
    for (int i = 0; i < 3; ++i) {
      u[i] = mpq_class(P[f[1]][i]) - P[f[0]][i];
      w[i] = mpq_class(P[f[2]][i]) - P[f[0]][i];
    }
    cross(u, w, n);
    tri_plane[t] = make_plane(P[f[0]], n);
    tri_plane[t].through_triangle = true;
    for (int k = 0; k < 3; ++k) {
      tri_plane[t].tri[k] = P[f[k]];
      tri_plane[t].ids[k] = f[k];
    }
    return tri_plane[t];
  };
  struct EdgePlane {
    Plane plane;
    int a, b; // the shared edge
  };
  std::vector<std::vector<EdgePlane>> edge_planes(nt);
  {
    auto topo = mesh::build_edge_topology(triangles);
    for (int e = 0; e < topo.num_edges(); ++e) {
      if (topo.num_faces_of(e) != 2) throw Error(ExitCode::internal, "volume: offset surface is not closed manifold");
      const int f0 = topo.faces_of(e)[0], f1 = topo.faces_of(e)[1];
      if (!is_cut[f0] && !is_cut[f1]) continue;
      const int a = topo.edges[e][0], b = topo.edges[e][1];
      int c1 = -1;
      for (int k : triangles[f1])
        if (k != a && k != b) c1 = k;
      const auto& t0 = triangles[f0];
      if (geometry::orient3d(P[t0[0]], P[t0[1]], P[t0[2]], P[c1]) != 0) continue;
      // coplanar neighbours: cut along the edge by the plane containing it
      // and the common normal.
      mpq_class u[3], m[3];
      for (int i = 0; i < 3; ++i) u[i] = mpq_class(P[b][i]) - P[a][i];
      cross(u, plane(f0).n, m);
      Plane ep = make_plane(P[a], m);
      edge_planes[f0].push_back({ep, a, b});
      edge_planes[f1].push_back({ep, a, b});
    }
  }
  lap("triangle planes");
  // Cut every tet's cells by the planes of the triangles meeting them. A cell
  // whose (slightly grown) box misses the triangle's box cannot meet the
  // triangle and is skipped; cutting more cells than needed is harmless.
  auto tet_tris = [&] {
    std::vector<mesh::Tri> to_cut;
    for (int t : cut_ids) to_cut.push_back(triangles[t]);
    auto lists = triangles_meeting_tets(bg, to_cut, /*interior=*/true);
    for (auto& l : lists)
      for (int& j : l) j = cut_ids[j];
    return lists;
  }();
  const int ntet = static_cast<int>(bg.tets.size());
  std::vector<Eigen::AlignedBox3d> tri_box(nt);
  for (int t : cut_ids) {
    for (int k : triangles[t]) tri_box[t].extend(P[k]); // exact corners: no pad
  }
  lap("triangle/tet incidence");
  std::vector<TriangleShape> shapes(cut_ids.size());
  std::vector<int> shape_of(nt, -1);
  for (std::size_t i = 0; i < cut_ids.size(); ++i) {
    const int t = cut_ids[i];
    shape_of[t] = static_cast<int>(i);
    const auto& f = triangles[t];
    TriangleShape& sh = shapes[i];
    sh.plane = &plane(t);
    for (int k = 0; k < 3; ++k) {
      sh.corner[k] = {to_h(to_q(P[f[k]])), P[f[k]]};
      const Vec3& x = P[f[k]];
      const Vec3& y = P[f[(k + 1) % 3]];
      mpq_class u[3], m[3];
      for (int j = 0; j < 3; ++j) u[j] = mpq_class(y[j]) - x[j];
      cross(u, sh.plane->n, m); // (y - x) x n points away from the triangle
      sh.edge[k] = make_plane(x, m);
      sh.edge[k].ids[0] = f[k];
      sh.edge[k].ids[1] = f[(k + 1) % 3];
    }
  }
  auto shape = [&](int t) -> const TriangleShape& { return shapes[shape_of[t]]; };
  for (int T = 0; T < ntet; ++T) {
    for (int t : tet_tris[T]) {
      auto apply = [&](const Plane& p, const TriangleShape* filter) {
        const std::size_t count = cx.tet_cells[T].size();
        for (std::size_t k = 0; k < count; ++k) {
          const int c = cx.tet_cells[T][k];
          if (count > 1) {
            Eigen::AlignedBox3d box;
            for (int i : cx.cell_vertices(c)) box.extend(cx.v.d[i]);
            // The cell's vertices are approximations: grow to hold the exact ones.
            const double pad = approximation_pad(std::max(box.max().cwiseAbs().maxCoeff(), box.min().cwiseAbs().maxCoeff()));
            box.min().array() -= pad;
            box.max().array() += pad;
            if (!box.intersects(tri_box[t])) continue;
          }
          cx.cut(c, p, T, filter);
        }
      };
      // A background tet (still uncut) whose face plane has the whole
      // triangle on its outer closed side cannot have the triangle inside.
      bool misses = false;
      if (cx.tet_cells[T].size() == 1) {
        const auto& q = bg.tets[T];
        for (int k = 0; k < 4 && !misses; ++k) {
          const Vec3 &a = P[q[(k + 1) % 4]], &b = P[q[(k + 2) % 4]], &c = P[q[(k + 3) % 4]];
          const int inner = geometry::orient3d(a, b, c, P[q[k]]);
          misses = true;
          for (int x : triangles[t])
            if (x != q[(k + 1) % 4] && x != q[(k + 2) % 4] && x != q[(k + 3) % 4] &&
                geometry::orient3d(a, b, c, P[x]) == inner)
              misses = false;
        }
      }
      if (!misses) apply(plane(t), &shape(t));
    }
  }

  lap("cuts");
  // Faces lying in a surface triangle.
  // A face in the plane of a triangle whose edge is shared with a coplanar
  // triangle may straddle that edge: it is split along it first (the face
  // only, not the cells), so every face lies in one triangle or none.
  std::vector<char> checked(cx.faces.size(), 0);
  for (int T = 0; T < ntet; ++T) {
    if (tet_tris[T].empty()) continue;
    std::vector<int> work;
    for (int c : cx.tet_cells[T])
      for (int f : cx.cells[c]) work.push_back(f);
    while (!work.empty()) {
      const int f = work.back();
      work.pop_back();
      if (static_cast<int>(checked.size()) < static_cast<int>(cx.faces.size())) checked.resize(cx.faces.size(), 0);
      if (checked[f] || cx.faces[f].tri >= 0) continue;
      checked[f] = 1;
      {
        bool split = false;
        for (int t : tet_tris[T]) {
          const Plane& pl = plane(t);
          // Is the face's supporting plane the triangle's? (exact, on the
          // triangle's double corners)
          const Face& face = cx.faces[f];
          bool in_plane = true;
          if (face.plane == &pl) {
          } else if (face.plane) {
            for (int k = 0; k < 3 && in_plane; ++k) {
              const int x = triangles[t][k];
              const auto& id = face.plane->ids;
              in_plane = x == id[0] || x == id[1] || x == id[2] || side_of(*face.plane, shape(t).corner[k]) == 0;
            }
          } else {
            const auto& o = face.origin;
            for (int k = 0; k < 3 && in_plane; ++k) {
              const int x = triangles[t][k];
              in_plane = x == o[0] || x == o[1] || x == o[2] ||
                         geometry::orient3d(P[o[0]], P[o[1]], P[o[2]], P[x]) == 0;
            }
          }
          if (!in_plane) continue;
          for (const auto& ep : edge_planes[t]) {
            const int g = cx.split_face_by(f, ep.plane);
            if (g >= 0) {
              checked.resize(cx.faces.size(), 0);
              checked[f] = 0;
              work.push_back(f);
              work.push_back(g);
              split = true;
              break;
            }
          }
          if (split) break;
          // The face straddles no edge line of the triangle (the planes of
          // the neighbours, or the edge planes above, split it), so it lies
          // in the closed triangle iff all its vertices do.
          bool inside = true;
          for (int e = 0; e < 3 && inside; ++e)
            for (int i : cx.faces[f].loop)
              if (cx.side(shape(t).edge[e], i) > 0) {
                inside = false;
                break;
              }
          if (inside) {
            cx.faces[f].tri = t;
            break;
          }
        }
      }
    }
  }

  lap("surface faces");
  // Winding numbers by crossing surface faces, from the hull (winding 0).
  const int ncell = static_cast<int>(cx.cells.size());
  constexpr int kUnset = std::numeric_limits<int>::min();
  std::vector<int> winding(ncell, kUnset);
  std::deque<int> queue;
  // Side of cell c of triangle t's plane: by orient3d on a double vertex
  // off it where there is one (most cells), else on the rational plane.
  auto side_of_cell = [&](int c, int t) {
    const auto& q = triangles[t];
    for (int f : cx.cells[c])
      for (int i : cx.faces[f].loop)
        if (cx.v.exact[i]) {
          const int s = geometry::orient3d(P[q[0]], P[q[1]], P[q[2]], cx.v.d[i]);
          if (s != 0) return s;
        }
    for (int f : cx.cells[c])
      for (int i : cx.faces[f].loop) {
        const int s = cx.side(plane(t), i);
        if (s != 0) return s;
      }
    throw Error(ExitCode::internal, "volume: flat BSP cell");
  };
  // Outside the hull the winding is 0; a hull face may lie on the surface.
  for (const auto& f : cx.faces)
    if (f.cell[1] < 0 && winding[f.cell[0]] == kUnset) {
      const int c = f.cell[0];
      winding[c] = f.tri < 0 ? 0 : (side_of_cell(c, f.tri) < 0 ? 1 : -1);
      queue.push_back(c);
    }
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop_front();
    for (int f : cx.cells[c]) {
      const Face& face = cx.faces[f];
      const int o = face.cell[0] == c ? face.cell[1] : face.cell[0];
      if (o < 0) continue;
      int w = winding[c];
      if (face.tri >= 0) w += side_of_cell(c, face.tri) > 0 ? 1 : -1;
      if (winding[o] == kUnset) {
        winding[o] = w;
        queue.push_back(o);
      } else if (winding[o] != w) {
        throw Error(ExitCode::internal, "volume: inconsistent winding numbers (surface not closed?)");
      }
    }
  }

  lap("winding numbers");
  // Tetrahedralize the kept cells; fans on faces are shared.
  InsertedSurface out;
  out.num_cuts = cx.num_cuts;
  out.num_cells = cx.cells.size();
  out.refined.resize(nt);
  auto centroid = [&](const std::vector<int>& ids) {
    QPoint g;
    for (int i : ids)
      for (int k = 0; k < 3; ++k) g.c[k] += cx.v.q[i].c[k];
    for (int k = 0; k < 3; ++k) g.c[k] /= static_cast<long>(ids.size());
    return g;
  };
  auto collinear = [&](int a, int b, int c) { return volume::exact::collinear(cx.points[a], cx.points[b], cx.points[c]); };
  // Face polygons are triangulated without new vertices, once: both cells
  // of a face use the same triangles. Convex loops may hold collinear
  // vertices (where neighbouring faces were split); a fan from loop[k] is
  // used when no fan triangle is flat, else ear clipping at strict corners
  // (never leaving fewer than three corners, so no ear is ever flat).
  std::vector<std::vector<std::array<int, 3>>> face_tris(cx.faces.size());
  auto fan = [&](const std::vector<int>& l, std::size_t k, std::vector<std::array<int, 3>>& tris) {
    const std::size_t n = l.size();
    for (std::size_t j = 1; j + 1 < n; ++j)
      if (collinear(l[k], l[(k + j) % n], l[(k + j + 1) % n])) return false;
    for (std::size_t j = 1; j + 1 < n; ++j) tris.push_back({l[k], l[(k + j) % n], l[(k + j + 1) % n]});
    return true;
  };
  auto ear_clip = [&](std::vector<int> l, std::vector<std::array<int, 3>>& tris) {
    auto corner = [&](std::size_t i) {
      const std::size_t n = l.size();
      return !collinear(l[(i + n - 1) % n], l[i], l[(i + 1) % n]);
    };
    while (l.size() > 3) {
      const std::size_t n = l.size();
      std::size_t corners = 0;
      for (std::size_t i = 0; i < n; ++i) corners += corner(i);
      std::size_t pick = n;
      for (std::size_t i = 0; i < n && pick == n; ++i)
        if (corner(i) && (corners > 3 || !corner((i + n - 1) % n) || !corner((i + 1) % n))) pick = i;
      if (pick == n) throw Error(ExitCode::internal, "volume: BSP face with fewer than three corners");
      tris.push_back({l[(pick + n - 1) % n], l[pick], l[(pick + 1) % n]});
      l.erase(l.begin() + static_cast<std::ptrdiff_t>(pick));
    }
    tris.push_back({l[0], l[1], l[2]});
  };
  // A fan from `apex` (when a loop vertex and no fan triangle is flat).
  auto fan_from = [&](const std::vector<int>& l, int apex, std::vector<std::array<int, 3>>& tris) {
    const auto at = std::find(l.begin(), l.end(), apex);
    return at != l.end() && fan(l, static_cast<std::size_t>(at - l.begin()), tris);
  };
  auto triangulate = [&](const std::vector<int>& l, std::vector<std::array<int, 3>>& tris) {
    if (!fan(l, 0, tris)) ear_clip(l, tris);
  };
  // Triangles of face f: as decided, else fanned from `apex` where possible.
  auto decide_face = [&](int f, int apex) -> const std::vector<std::array<int, 3>>& {
    auto& tris = face_tris[f];
    if (tris.empty() && !fan_from(cx.faces[f].loop, apex, tris)) triangulate(cx.faces[f].loop, tris);
    return tris;
  };
  // Whether apex can cone the cell: every face on it is (or can be) fanned
  // from it; then `cone` holds the positive tets over the other triangles.
  std::vector<std::array<int, 4>> cone;
  std::vector<std::array<int, 3>> trial;
  auto vertex_cone = [&](int c, int apex) {
    cone.clear();
    for (int f : cx.cells[c]) {
      const auto& l = cx.faces[f].loop;
      const std::vector<std::array<int, 3>>* tris = &face_tris[f];
      if (tris->empty()) {
        trial.clear();
        if (std::find(l.begin(), l.end(), apex) != l.end()) {
          if (!fan_from(l, apex, trial)) return false;
          continue; // every triangle has the apex as a corner
        }
        triangulate(l, trial);
        tris = &trial;
      }
      for (const auto& t : *tris) {
        if (t[0] == apex || t[1] == apex || t[2] == apex) continue;
        std::array<int, 4> q{t[0], t[1], t[2], apex};
        const int o = cx.v.orient(q[0], q[1], q[2], q[3]);
        if (o == 0) return false;
        if (o < 0) std::swap(q[0], q[1]);
        cone.push_back(q);
      }
    }
    return true;
  };
  auto add_tet = [&](std::array<int, 4> t) {
    const int o = cx.v.orient(t[0], t[1], t[2], t[3]);
    if (o == 0) throw Error(ExitCode::internal, "volume: flat tet in a BSP cell");
    if (o < 0) std::swap(t[0], t[1]);
    out.tets.push_back(t);
  };
  std::size_t centroid_cells = 0;
  for (int c = 0; c < ncell; ++c) {
    if (winding[c] == kUnset) throw Error(ExitCode::internal, "volume: BSP cell not reached");
    if (winding[c] != keep_winding) continue;
    const std::vector<int> vs = cx.cell_vertices(c);
    if (vs.size() == 4) {
      for (int f : cx.cells[c]) decide_face(f, -1);
      add_tet({vs[0], vs[1], vs[2], vs[3]});
      continue;
    }
    int apex = -1;
    for (int a : vs)
      if (vertex_cone(c, a)) {
        apex = a;
        break;
      }
    for (int f : cx.cells[c]) decide_face(f, apex);
    if (apex >= 0) {
      out.tets.insert(out.tets.end(), cone.begin(), cone.end());
      continue;
    }
    // No vertex cones the cell: a new vertex at its centroid does.
    ++centroid_cells;
    const int g = cx.v.add(centroid(vs));
    for (int f : cx.cells[c])
      for (const auto& t : face_tris[f]) add_tet({t[0], t[1], t[2], g});
  }
  for (int f = 0; f < static_cast<int>(cx.faces.size()); ++f)
    if (cx.faces[f].tri >= 0) {
      const auto& tris = decide_face(f, -1);
      out.refined[cx.faces[f].tri].insert(out.refined[cx.faces[f].tri].end(), tris.begin(), tris.end());
    }
  logger().debug("volume: {} BSP cells coned from a new centroid", centroid_cells);
  lap("cell tetrahedralization");
  out.vertices = std::move(cx.v);
  return out;
}

} // namespace curvetet::volume::exact
