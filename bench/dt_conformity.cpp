// Measures how much of a surface mesh the 3D Delaunay tetrahedralization of its vertices already contains:
// the input triangles and edges that are not DT faces/edges, plus the DT time. This is the question behind
// a local boundary-recovery fast path for `curvetet tetrahedralize` (standalone; see docs/dt_conformity.md).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;

// Minimal OFF reader (triangles only); '#' starts a comment that runs to the end of the line.
static bool read_off(const std::string& path, std::vector<K::Point_3>& pts, std::vector<std::array<int, 3>>& tris) {
  std::ifstream in(path);
  std::stringstream ss;
  for (std::string line; std::getline(in, line);) ss << line.substr(0, line.find('#')) << '\n';
  std::string header;
  long nv = 0, nf = 0, ne = 0;
  if (!(ss >> header >> nv >> nf >> ne) || header != "OFF") return false;
  pts.resize(nv);
  tris.resize(nf);
  for (auto& p : pts) {
    double x, y, z;
    if (!(ss >> x >> y >> z)) return false;
    p = K::Point_3(x, y, z);
  }
  for (auto& t : tris) {
    int n = 0;
    if (!(ss >> n >> t[0] >> t[1] >> t[2]) || n != 3) return false;
    for (int v : t)
      if (v < 0 || v >= nv) return false;
  }
  return true;
}

int main(int argc, char** argv) {
  std::printf("name faces missing_faces pct_faces edges missing_edges pct_edges seconds\n");
  for (int a = 1; a < argc; ++a) {
    const std::string path = argv[a];
    std::vector<K::Point_3> pts;
    std::vector<std::array<int, 3>> tris;
    if (!read_off(path, pts, tris)) {
      std::fprintf(stderr, "%s: cannot read OFF triangle mesh\n", path.c_str());
      return 1;
    }
    std::vector<std::pair<K::Point_3, int>> input;
    input.reserve(pts.size());
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) input.emplace_back(pts[i], i);

    const auto t0 = std::chrono::steady_clock::now();
    const DT dt(input.begin(), input.end());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::vector<DT::Vertex_handle> vh(pts.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) vh[v->info()] = v;
    if (dt.number_of_vertices() != pts.size()) {
      std::fprintf(stderr, "%s: %zu of %zu points are duplicates; skipped\n", path.c_str(),
                   pts.size() - dt.number_of_vertices(), pts.size());
      continue;
    }

    DT::Cell_handle c;
    int i, j, k;
    long missing_faces = 0;
    std::vector<std::pair<int, int>> edges;
    for (const auto& t : tris) {
      if (!dt.is_facet(vh[t[0]], vh[t[1]], vh[t[2]], c, i, j, k)) ++missing_faces;
      for (int e = 0; e < 3; ++e) edges.emplace_back(std::minmax(t[e], t[(e + 1) % 3]));
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    long missing_edges = 0;
    for (const auto& e : edges)
      if (!dt.is_edge(vh[e.first], vh[e.second], c, i, j)) ++missing_edges;

    std::string name = path.substr(path.find_last_of('/') + 1);
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".off") == 0) name.resize(name.size() - 4);
    std::printf("%s %zu %ld %.2f %zu %ld %.2f %.3f\n", name.c_str(), tris.size(), missing_faces,
                100.0 * missing_faces / tris.size(), edges.size(), missing_edges,
                100.0 * missing_edges / edges.size(), seconds);
    std::fflush(stdout);
  }
  return 0;
}
