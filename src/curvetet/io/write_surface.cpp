#include "curvetet/io/write_surface.hpp"

#include "curvetet/core/error.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace curvetet::io {

namespace {

void write_off(std::ostream& o, const mesh::SurfaceMesh& m) {
  o << "OFF\n" << m.num_vertices() << ' ' << m.num_faces() << " 0\n";
  for (const auto& p : m.vertices) o << fmt::format("{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  for (const auto& f : m.faces) o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
}

void write_obj(std::ostream& o, const mesh::SurfaceMesh& m) {
  for (const auto& p : m.vertices) o << fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  for (const auto& f : m.faces) o << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
}

template <class T>
void put_le(std::ostream& o, T v) {
  char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(raw, raw + sizeof(T));
  o.write(raw, sizeof(T));
}

void write_ply(std::ostream& o, const mesh::SurfaceMesh& m, bool binary) {
  o << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
    << "element vertex " << m.num_vertices() << "\nproperty double x\nproperty double y\nproperty double z\n"
    << "element face " << m.num_faces() << "\nproperty list uchar int vertex_indices\nend_header\n";
  if (!binary) {
    for (const auto& p : m.vertices) o << fmt::format("{:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
    for (const auto& f : m.faces) o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    return;
  }
  for (const auto& p : m.vertices)
    for (int k = 0; k < 3; ++k) put_le(o, p[k]);
  for (const auto& f : m.faces) {
    put_le<std::uint8_t>(o, 3);
    for (int v : f) put_le<std::int32_t>(o, v);
  }
}

void write_stl(std::ostream& o, const mesh::SurfaceMesh& m, bool binary) {
  auto normal = [&](const mesh::Tri& f) {
    mesh::Vec3 n = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
    double len = n.norm();
    return len > 0 ? mesh::Vec3(n / len) : mesh::Vec3::Zero();
  };
  if (!binary) {
    o << "solid curvetet\n";
    for (const auto& f : m.faces) {
      mesh::Vec3 n = normal(f);
      o << fmt::format("facet normal {:.9g} {:.9g} {:.9g}\nouter loop\n", n.x(), n.y(), n.z());
      for (int v : f) {
        const auto& p = m.vertices[v];
        // The float's exact value, so that a reader parsing doubles gets it back.
        o << fmt::format("vertex {:.17g} {:.17g} {:.17g}\n", double(float(p.x())), double(float(p.y())),
                         double(float(p.z())));
      }
      o << "endloop\nendfacet\n";
    }
    o << "endsolid curvetet\n";
    return;
  }
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL written by curvetet");
  o.write(header, 80);
  put_le<std::uint32_t>(o, static_cast<std::uint32_t>(m.num_faces()));
  for (const auto& f : m.faces) {
    mesh::Vec3 n = normal(f);
    for (int k = 0; k < 3; ++k) put_le<float>(o, float(n[k]));
    for (int v : f)
      for (int k = 0; k < 3; ++k) put_le<float>(o, float(m.vertices[v][k]));
    put_le<std::uint16_t>(o, 0);
  }
}

} // namespace

void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceFormat format,
                   SurfaceWriteOptions options) {
  AtomicFile file(path, options.binary);
  auto& o = file.stream();
  switch (format) {
    case SurfaceFormat::off: write_off(o, mesh); break;
    case SurfaceFormat::obj: write_obj(o, mesh); break;
    case SurfaceFormat::ply: write_ply(o, mesh, options.binary); break;
    case SurfaceFormat::stl: write_stl(o, mesh, options.binary); break;
  }
  file.commit();
}

void write_surface(const std::string& path, const mesh::SurfaceMesh& mesh, SurfaceWriteOptions options) {
  write_surface(path, mesh, format_from_path(path), options);
}

} // namespace curvetet::io
